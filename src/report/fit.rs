//! The identification of a measured disc (`cycloid fit`) as text, and its form-error curve as
//! CSV. Lengths in mm for values, µm for uncertainties, residuals and deviations; angles in
//! degrees. Fixed decimals, so that a run reads the same on every machine.

use crate::geometry::profile::Profile;
use crate::measure::fit::Identification;
use crate::measure::fitted::Estimate;
use crate::measure::flanks::arc_length_mm;
use crate::numeric::fixed;
use crate::spec::Spec;
use crate::units;
use serde::Serialize;
use std::f64::consts::TAU;

fn row(name: &str, e: Estimate, unit: &str) -> String {
    let (value, sigma) = match unit {
        "deg" => (
            format!("{} deg", fixed(units::deg(e.value), 6)),
            format!("{} deg", fixed(units::deg(e.sigma), 6)),
        ),
        _ => (
            format!("{} mm", fixed(e.value, 6)),
            format!("{} µm", fixed(units::um(e.sigma), 3)),
        ),
    };
    format!("  {name:<16} {value:>18}   ± {sigma}\n")
}

/// The text `cycloid fit` prints.
pub fn render(spec: &Spec, id: &Identification) -> String {
    let profile_points = id.profile.len();
    let mut out = format!(
        "cycloid fit `{}`: {profile_points} profile points, {} hole points, {} unknowns, \
         {} Gauss-Newton steps\n",
        spec.name, id.hole_points, id.unknowns, id.iterations
    );
    if let Some(line) = thinned(id) {
        out += &line;
    }
    out += &format!(
        "condition number {:.1} (column-scaled Jacobian; refused above 1e8)\n",
        id.condition
    );
    out += &format!(
        "residual: RMS {} µm, max {} µm (line {})\n",
        fixed(units::um(id.residual_rms_mm), 3),
        fixed(units::um(id.residual_max_mm), 3),
        id.residual_max_line
    );
    out += &format!(
        "coverage: {:.1} % of the profile (bins of 1/16 tooth pitch), {} of {} teeth with both \
         flanks measured\n",
        100.0 * id.coverage.fraction,
        id.coverage.teeth_measured,
        spec.design.teeth
    );
    out += "identified (value ± standard uncertainty):\n";
    out += &row("centre x0", id.centre_mm[0], "mm");
    out += &row("centre y0", id.centre_mm[1], "mm");
    out += &row("orientation", id.orientation_rad, "deg");
    for (name, e, unit) in [
        ("shift_mm", id.shift_mm, "mm"),
        ("equidistant_mm", id.equidistant_mm, "mm"),
        ("rotation_deg", id.rotation_rad, "deg"),
        ("hole radius +", id.hole_radius_offset_mm, "mm"),
    ] {
        if let Some(e) = e {
            out += &row(name, e, unit);
        }
    }
    if !id.form.harmonics.is_empty() {
        out += "form error w(t) along the normal (w > 0: material missing), µm:\n";
        out += "  order       cos       sin   amplitude   ± (cos, sin)\n";
        for h in &id.form.harmonics {
            out += &format!(
                "  {:>5} {:>9} {:>9} {:>11}   ± {}, {}\n",
                h.order,
                fixed(units::um(h.cos_mm.value), 3),
                fixed(units::um(h.sin_mm.value), 3),
                fixed(units::um(h.amplitude_mm()), 3),
                fixed(units::um(h.cos_mm.sigma), 3),
                fixed(units::um(h.sin_mm.sigma), 3)
            );
        }
    }
    out += &format!(
        "per flank, as on a gear inspection sheet (ISO 1328-1 F, f_f, f_H over the arc length \
         s along the profile from the flank's root; each flank {} mm root to tip): the \
         deviation from the identified modified profile (form error plus residual, positive: \
         material missing) over the measured extent s_from..s_to (mm); F total, f_f form, f_H \
         slope (positive: more missing towards the tip), µm:\n",
        fixed(flank_length_mm(spec, id), 3)
    );
    out += "  tooth flank points  s_from    s_to        F      f_f      f_H\n";
    for f in &id.flanks {
        let cells = f.summary.map_or_else(
            || format!("{:>7} {:>7} {:>8} {:>8} {:>8}", "-", "-", "-", "-", "-"),
            |s| {
                let um = |v: f64| fixed(units::um(v), 3);
                format!(
                    "{:>7} {:>7} {:>8} {:>8} {:>8}",
                    fixed(s.from_mm, 3),
                    fixed(s.to_mm, 3),
                    um(s.total_mm),
                    um(s.form_mm),
                    um(s.slope_mm)
                )
            },
        );
        out += &format!("  {:>5} {:>5} {:>6} {cells}\n", f.tooth, f.side, f.points);
    }
    out
}

/// The line naming the thinning of a scan denser than the fit holds, if it was thinned.
pub fn thinned(id: &Identification) -> Option<String> {
    id.thinning.map(|t| {
        format!(
            "thinned: every {} of {} profile points ({} used; hole points all kept; the \
             residuals, coverage and flanks below are those of the points used)\n",
            ordinal(t.every),
            t.of,
            t.used
        )
    })
}

/// `k` as an English ordinal: 2nd, 3rd, 4th, 11th, 21st.
pub fn ordinal(k: usize) -> String {
    let suffix = match (k % 10, k % 100) {
        (_, 11..=13) => "th",
        (1, _) => "st",
        (2, _) => "nd",
        (3, _) => "rd",
        _ => "th",
    };
    format!("{k}{suffix}")
}

/// Arc length of a flank of the identified modified profile from root to tip, mm.
pub fn flank_length_mm(spec: &Spec, id: &Identification) -> f64 {
    let reference = Profile::new(&spec.design, &id.modification);
    arc_length_mm(
        &reference,
        0.0,
        std::f64::consts::PI / spec.design.teeth as f64,
    )
}

/// `x` as the number [`fixed`] writes with `decimals`: what a reader of that text reads back.
fn at_decimals(x: f64, decimals: usize) -> f64 {
    // The text of a number parses back (NaN and infinities included), so `x` is never used.
    fixed(x, decimals).parse().unwrap_or(x)
}

/// A value and its standard uncertainty, in the unit its key names: a pair in JSON, a tuple in
/// Python.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ValueSigma(pub f64, pub f64);

impl ValueSigma {
    /// `e` with lengths in mm (the engine's unit).
    fn mm(e: Estimate) -> Self {
        ValueSigma(e.value, e.sigma)
    }

    /// `e`, an angle in rad, in degrees.
    fn deg(e: Estimate) -> Self {
        ValueSigma(units::deg(e.value), units::deg(e.sigma))
    }
}

/// The identified modification, in the spec's units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ModificationDoc {
    pub shift_mm: f64,
    pub equidistant_mm: f64,
    pub rotation_deg: f64,
}

/// The form-error curve w(t) along the normal (w > 0: material missing) at 1/16 of a tooth
/// pitch (nc·16 points), as `--form-csv` states it: t in degrees and w in µm, each at 4
/// decimals (0.1 nm).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FormCurve {
    pub t_deg: Vec<f64>,
    pub w_um: Vec<f64>,
}

/// What `cycloid fit` finds: each estimate as (value, standard uncertainty) in its key's unit
/// (None when not fitted), the identified modification, the residuals (mm), the Jacobian's
/// condition number, the text `cycloid fit` prints and the form-error curve. What the Python
/// `fit` returns.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitDoc {
    pub centre_x_mm: ValueSigma,
    pub centre_y_mm: ValueSigma,
    pub orientation_deg: ValueSigma,
    pub shift_mm: Option<ValueSigma>,
    pub equidistant_mm: Option<ValueSigma>,
    pub rotation_deg: Option<ValueSigma>,
    pub modification: ModificationDoc,
    pub residual_rms_mm: f64,
    pub residual_max_mm: f64,
    pub condition: f64,
    pub report: String,
    pub form: FormCurve,
}

/// The fit document of the identification `id` of `spec`'s measured disc.
pub fn document(spec: &Spec, id: &Identification) -> FitDoc {
    let m = &id.modification;
    FitDoc {
        centre_x_mm: ValueSigma::mm(id.centre_mm[0]),
        centre_y_mm: ValueSigma::mm(id.centre_mm[1]),
        orientation_deg: ValueSigma::deg(id.orientation_rad),
        shift_mm: id.shift_mm.map(ValueSigma::mm),
        equidistant_mm: id.equidistant_mm.map(ValueSigma::mm),
        rotation_deg: id.rotation_rad.map(ValueSigma::deg),
        modification: ModificationDoc {
            shift_mm: m.shift_mm,
            equidistant_mm: m.equidistant_mm,
            rotation_deg: units::deg(m.rotation_rad),
        },
        residual_rms_mm: id.residual_rms_mm,
        residual_max_mm: id.residual_max_mm,
        condition: id.condition,
        report: render(spec, id),
        form: form_curve(spec, id),
    }
}

/// The form-error curve at t_k = 2πk/(16·nc), k = 0 … 16·nc − 1.
pub fn form_curve(spec: &Spec, id: &Identification) -> FormCurve {
    let rows = 16 * spec.design.teeth;
    let t = |k: usize| TAU * k as f64 / rows as f64;
    FormCurve {
        t_deg: (0..rows)
            .map(|k| at_decimals(units::deg(t(k)), 4))
            .collect(),
        w_um: (0..rows)
            .map(|k| at_decimals(units::um(id.form.value_mm(t(k))), 4))
            .collect(),
    }
}

/// The form-error curve as CSV: `t_deg,w_um`, a row per point of [`form_curve`].
pub fn form_csv(spec: &Spec, id: &Identification) -> String {
    let curve = form_curve(spec, id);
    let mut out = String::from("t_deg,w_um\n");
    for (t, w) in curve.t_deg.iter().zip(&curve.w_um) {
        out += &format!("{},{}\n", fixed(*t, 4), fixed(*w, 4));
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn ordinals_read_as_english() {
        let read: Vec<String> = [1, 2, 3, 4, 11, 12, 13, 21, 102, 111]
            .map(super::ordinal)
            .into();
        assert_eq!(
            read,
            ["1st", "2nd", "3rd", "4th", "11th", "12th", "13th", "21st", "102nd", "111th"]
        );
    }
}
