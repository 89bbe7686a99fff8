//! The measured disc: points read from a CMM file or a CAD drawing (`points`, its text decoded
//! by `encoding`, its splines evaluated by `spline`), and the
//! least-squares identification of the disc they lie on (`fit`, MODEL.md "Measured profiles";
//! what it finds along the profile, `fitted`), and the per-flank summaries of its deviations
//! over arc length (`flanks`); a scan too dense for the fit is thinned (`thinning`).

pub mod encoding;
pub mod fit;
pub mod fitted;
pub mod flanks;
pub mod points;
pub mod spline;
pub mod thinning;

use crate::geometry::Vec2;

/// What a measured point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// The tooth profile.
    Profile,
    /// The bore of output-pin hole j (0-based, at angle 2πj/M on the pin circle in the disc
    /// frame, MODEL.md "Equilibrium").
    Hole(usize),
}

/// One measured point, in the frame of the measuring machine (mm), with where it came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredPoint {
    pub point: Vec2,
    pub feature: Feature,
    /// 1-based line of the file it was read from (0 when made in code).
    pub line: usize,
}
