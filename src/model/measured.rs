//! `measured_profile:` of a spec: points measured on a ground disc (or cut from a CAD file), and
//! what to identify from them (MODEL.md "Measured profiles").

/// The file format of the measured points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointsFormat {
    /// `x_mm,y_mm[,feature]` rows after a header line.
    Csv,
    /// Polylines (profile) and circles (pin holes) of a DXF drawing.
    Dxf,
}

named!(PointsFormat "points format" {
    Csv => "csv",
    Dxf => "dxf",
});

/// The modifications a fit identifies; the others keep the spec's values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Fitted {
    /// Identify ΔRp (`fit: [shift_mm]`).
    pub shift: bool,
    /// Identify ΔRrp (`equidistant_mm`).
    pub equidistant: bool,
    /// Identify Δδ (`rotation_deg`): only measured hole points tell it from the disc's turn θ0.
    pub rotation: bool,
}

/// The names `fit:` takes, in the order of `Fitted`'s fields.
pub const FITTED_NAMES: [&str; 3] = ["shift_mm", "equidistant_mm", "rotation_deg"];

/// A measured profile to identify.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredProfile {
    /// The points file, resolved against the spec's directory.
    pub path: String,
    /// The points file's format (`format`).
    pub format: PointsFormat,
    /// Highest harmonic of the form-error series (0: no form error).
    pub harmonics: usize,
    /// The modifications the fit identifies (`fit`).
    pub fit: Fitted,
}
