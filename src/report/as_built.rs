//! The disc as built in one line for the terminal: what the scenes of a spec with a
//! `measured_profile` run on ([`engine::as_built::identify`](crate::engine::as_built::identify)).

use crate::measure::fit::Identification;
use crate::spec::Spec;
use crate::units;

/// One line for the terminal: what the scenes of `spec`, the disc as built
/// ([`engine::as_built::identify`](crate::engine::as_built::identify)), run on.
pub fn describe(spec: &Spec, id: &Identification) -> String {
    let m = &id.modification;
    let form = &spec.design.deviations;
    let thinned = id.thinning.map_or(String::new(), |t| {
        format!(
            "; thinned: every {} of {} profile points ({} used)",
            super::fit::ordinal(t.every),
            t.of,
            t.used
        )
    });
    format!(
        "as built: the scenes run on the disc identified from `{}`: shift {:.4} mm, \
         equidistant {:.4} mm, rotation {:.4}°, form error of {} harmonics (|w| ≤ {:.3} µm), \
         residual RMS {:.3} µm{thinned}",
        spec.measured.as_ref().map_or("", |m| m.path.as_str()),
        m.shift_mm,
        m.equidistant_mm,
        units::deg(m.rotation_rad),
        form.form.len(),
        units::um(form.form_bound_mm()),
        units::um(id.residual_rms_mm)
    )
}
