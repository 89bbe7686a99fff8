//! The disc as built from its measured points (`measured_profile:`): identify it
//! ([`measure::fit`](crate::measure::fit)) and give the spec whose scenes run on it — the identified modification and
//! the fitted form error (`reducer.deviations.form`), exact geometry (MODEL.md "Measured
//! profiles"). `check` runs every scene and limit on that spec.

use crate::error::{Error, Result};
use crate::measure::fit::{self, Identification};
use crate::measure::points;
use crate::model::measured::MeasuredProfile;
use crate::model::{Deviations, FormTerm};
use crate::numeric;
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
    // The points are the disc as ground: its grinding errors are in the identified
    // modification (as its form error is in the fitted one, which replaces any given), and
    // adding the spec's `deviations.shift_mm` / `equidistant_mm` again would check another disc.
    built.design.deviations.shift_mm = 0.0;
    built.design.deviations.equidistant_mm = 0.0;
    built.design.deviations.form = form_terms(&id);
    crate::spec::deviations::check(&built.design, &built.modification)?;
    // The fitted form error makes the loaded curves repeat only after a whole turn of the
    // disc: a bearing life over the drawing's loaded period no longer spans whole load cycles.
    let what = "the disc identified from `measured_profile`, whose form error repeats only \
                after a whole turn of the disc";
    let scenes = built.scenes.iter().enumerate();
    crate::spec::bearing_life::check_built(&built.limits, &built.design, scenes, what)
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
    let id = fit::identify(&request, &read).map_err(|mut e| {
        if e.location.is_none() {
            e.message = format!("measured profile `{}`: {}", measured.path, e.message);
        }
        e
    })?;
    of_this_design(spec, measured, &id)
        .map_err(|e| spec.locate(e.at_key("measured_profile.file")))?;
    Ok(id)
}

/// The identified disc is a disc of this design, else the points are not (points in inches,
/// of another part): its profile is less than the eccentricity e from the drawing's, the same
/// bound as a part as built (`spec::deviations::check`: the teeth are 2e deep, a hole is e
/// wider than its pin), its hole radii too, and it keeps the design rules (K1, undercut, the
/// pin holes below the tooth root, a form error that leaves the flank regular). The profile's
/// distance from the drawing's is bounded by |ΔRp − ΔRp₀| + |ΔRrp − ΔRrp₀| + Σ|w_k|: a change of
/// ΔRp moves it along the normal by (cos t, sin t)·N, at most 1, a change of ΔRrp by 1.
fn of_this_design(spec: &Spec, measured: &MeasuredProfile, id: &Identification) -> Result<()> {
    let (m, m0) = (id.modification, spec.modification);
    let e = spec.design.eccentricity_mm;
    let (shift, equidistant) = (
        m.shift_mm - m0.shift_mm,
        m.equidistant_mm - m0.equidistant_mm,
    );
    let deviations = Deviations {
        form: form_terms(id),
        ..Deviations::default()
    };
    let form_bound = deviations.form_bound_mm();
    let moved = shift.abs() + equidistant.abs() + form_bound;
    let file = &measured.path;
    let not_this = "the points are not a disc of this design, or not in mm";
    // NaN (no finite fit) is refused too.
    if moved.is_nan() || moved >= e {
        return Err(Error::invalid_value(format!(
            "the disc identified from `{file}` lies up to {} mm from the drawing's profile \
             (shift_mm {} mm and equidistant_mm {} mm from the spec's, form error up to {} \
             mm), not less than the eccentricity e = {} mm that a part as built may move \
             (the teeth are 2e deep): {not_this}",
            numeric::number(moved),
            numeric::change(m0.shift_mm, m.shift_mm),
            numeric::change(m0.equidistant_mm, m.equidistant_mm),
            numeric::number(form_bound),
            numeric::input(e)
        )));
    }
    if let Some(hole) = id
        .hole_radius_offset_mm
        .filter(|h| h.value.is_nan() || h.value.abs() >= e)
    {
        return Err(Error::invalid_value(format!(
            "the holes identified from `{file}` are {} mm off the design's radius {} mm, \
             not less than the eccentricity e = {} mm (a hole is e wider than its pin): \
             {not_this}",
            numeric::number(hole.value),
            numeric::number(spec.design.hole_radius_mm()),
            numeric::input(e)
        )));
    }
    let mut disc = spec.design.clone();
    disc.deviations = deviations;
    crate::spec::deviations::check(&disc, &m).map_err(|r| {
        Error::invalid_value(format!(
            "the disc identified from `{file}` (shift_mm {}, equidistant_mm {}) breaks a \
             design rule, {not_this}: {}",
            numeric::number(m.shift_mm),
            numeric::number(m.equidistant_mm),
            r.message
        ))
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
