//! The disc as built from its measured points (`measured_profile:`): identify it
//! ([`measure::fit`](crate::measure::fit)) and give the spec whose scenes run on it — the identified modification and
//! the fitted form error (`reducer.deviations.form`), exact geometry (MODEL.md "Measured
//! profiles"). `check` runs every scene and limit on that spec.

use crate::error::Result;
use crate::measure::fit::{self, Identification};
use crate::measure::points;
use crate::model::measured::MeasuredProfile;
use crate::model::FormTerm;
use crate::spec::Spec;

/// The spec of the disc as built and its identification, or `None` without measured points.
pub fn identify(spec: &Spec) -> Result<Option<(Spec, Identification)>> {
    let Some(measured) = &spec.measured else {
        return Ok(None);
    };
    crate::spec::refuse_first_order(
        &spec.scenes,
        "with `measured_profile` the scenes run on the disc as built, whose form error only \
         the exact geometry holds: use `geometry: exact`",
    )?;
    let id = fit(spec, measured)?;
    let mut built = spec.clone();
    built.modification = id.modification;
    built.design.deviations.form = form_terms(&id);
    crate::spec::deviations::check(&built.design, &built.modification)?;
    // The fitted form error makes the loaded curves repeat only after a whole turn of the
    // disc: a bearing life over the drawing's loaded period no longer spans whole load cycles.
    let what = "the disc identified from `measured_profile`, whose form error repeats only \
                after a whole turn of the disc";
    crate::spec::bearing_life::check(&built.limits, &built.design, &built.scenes, Some(what))
        .map_err(|e| spec.locate(e))?;
    Ok(Some((built, id)))
}

/// Identify the disc of `measured`'s points against `spec`'s design ([`measure::fit`](crate::measure::fit)), an
/// error about the points naming their file.
pub fn fit(spec: &Spec, measured: &MeasuredProfile) -> Result<Identification> {
    // A file that cannot be read is an error of the spec key that names it; an error inside
    // the file keeps its own location there.
    let read = points::read(&measured.path, measured.format).map_err(|e| match e.location {
        Some(_) => e,
        None => spec.locate(e.at_key("measured_profile.file")),
    })?;
    let request = fit::Request {
        design: &spec.design,
        nominal: spec.modification,
        fit: measured.fit,
        harmonics: measured.harmonics,
    };
    fit::identify(&request, &read).map_err(|mut e| {
        if e.location.is_none() {
            e.message = format!("measured profile `{}`: {}", measured.path, e.message);
        }
        e
    })
}

/// The fitted form error as the spec's harmonics (their values; the uncertainties stay with
/// the identification).
pub fn form_terms(id: &Identification) -> Vec<FormTerm> {
    id.form
        .harmonics
        .iter()
        .map(|h| FormTerm {
            order: h.order,
            cos_mm: h.cos_mm.value,
            sin_mm: h.sin_mm.value,
        })
        .collect()
}
