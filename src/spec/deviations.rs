//! `reducer.deviations` → [`model::Deviations`](crate::model::Deviations), and the rules an as-built state must keep
//! (MODEL.md "Part deviations"): indices in range, parts that stay in their mesh, rollers that
//! do not overlap, a ground profile that is still a disc.

use super::raw::RawDeviations;
use super::rules::rule;
use super::values::finite;
use crate::error::{Error, Result};
use crate::model::{
    CentreDeviation, Design, Deviations, FormTerm, Modification, RollerDeviation, MAX_FORM_ORDER,
};
use crate::numeric;
use std::f64::consts::TAU;

const KEY: &str = "reducer.deviations";

/// An index into `count` parts named `what`, each given once (`seen`).
fn index(key: String, value: i64, count: usize, what: &str, seen: &mut [bool]) -> Result<usize> {
    if !(0..count as i64).contains(&value) {
        return Err(Error::invalid(
            format!("{key}.index"),
            format!(
                "the reducer has {count} {what}, numbered 0 to {}; got {value}",
                count - 1
            ),
        ));
    }
    let i = value as usize;
    if std::mem::replace(&mut seen[i], true) {
        return Err(Error::invalid(
            format!("{key}.index"),
            format!("{what} {i} is given twice"),
        ));
    }
    Ok(i)
}

/// A part's centre deviation at `key`: (radial, tangential), mm, each finite.
fn centre(key: &str, (radial, tangential): (f64, f64)) -> Result<CentreDeviation> {
    Ok(CentreDeviation {
        radial_mm: finite(&format!("{key}.radial_mm"), radial)?,
        tangential_mm: finite(&format!("{key}.tangential_mm"), tangential)?,
    })
}

/// The validated deviations of `design` (the design rules of the parts are `check`'s).
pub(crate) fn build(raw: &RawDeviations, design: &Design) -> Result<Deviations> {
    let mut d = Deviations {
        eccentricity_mm: finite(&format!("{KEY}.eccentricity_mm"), raw.eccentricity_mm)?,
        shift_mm: finite(&format!("{KEY}.shift_mm"), raw.shift_mm)?,
        equidistant_mm: finite(&format!("{KEY}.equidistant_mm"), raw.equidistant_mm)?,
        // mrad → rad, as a scene's.
        misalignment: super::face::misalignment_at(
            &format!("{KEY}.misalignment"),
            raw.misalignment,
        )?,
        ..Deviations::default()
    };
    let mut seen = vec![false; design.rollers];
    if !raw.rollers.is_empty() {
        d.rollers = vec![RollerDeviation::default(); design.rollers];
    }
    for (n, r) in raw.rollers.iter().enumerate() {
        let key = format!("{KEY}.rollers[{n}]");
        let i = index(key.clone(), r.index, design.rollers, "rollers", &mut seen)?;
        d.rollers[i] = RollerDeviation {
            centre: centre(&key, (r.radial_mm, r.tangential_mm))?,
            radius_mm: finite(&format!("{key}.radius_mm"), r.radius_mm)?,
        };
    }
    let pins = design.pins.count;
    let mut seen = vec![false; pins];
    if !raw.pins.is_empty() {
        d.pins = vec![CentreDeviation::default(); pins];
    }
    for (n, p) in raw.pins.iter().enumerate() {
        let key = format!("{KEY}.pins[{n}]");
        if p.disc.is_some() {
            return Err(Error::invalid(
                format!("{key}.disc"),
                "the pins sit on the output flange, which all discs share: a pin names no disc"
                    .into(),
            ));
        }
        let j = index(key.clone(), p.index, pins, "output pins", &mut seen)?;
        d.pins[j] = centre(&key, (p.radial_mm, p.tangential_mm))?;
    }
    d.form = form(&raw.form, design.teeth, design.roller_circle_radius_mm)?;
    let mut seen = vec![vec![false; pins]; design.discs];
    if !raw.holes.is_empty() {
        d.holes = vec![vec![CentreDeviation::default(); pins]; design.discs];
    }
    for (n, h) in raw.holes.iter().enumerate() {
        let key = format!("{KEY}.holes[{n}]");
        let k = match (h.disc, design.discs) {
            (None, 1) => 0,
            (None, discs) => {
                return Err(Error::invalid(
                    format!("{key}.disc"),
                    format!(
                        "the reducer has {discs} discs: say whose hole this is (disc: 0 to {})",
                        discs - 1
                    ),
                ))
            }
            (Some(k), discs) => super::values::disc_index(&format!("{key}.disc"), k, discs)?,
        };
        let j = index(key.clone(), h.index, pins, "holes per disc", &mut seen[k])?;
        d.holes[k][j] = centre(&key, (h.radial_mm, h.tangential_mm))?;
    }
    Ok(d)
}

/// `reducer.deviations.form`: orders from 2 to `MAX_FORM_ORDER`, each once, none a multiple of
/// the tooth count (such a harmonic moves every tooth alike: it is the modification, `shift_mm`
/// and `equidistant_mm`, or the orientation; order 1 is the disc's centre).
fn form(raw: &[super::raw::RawFormTerm], teeth: usize, rp: f64) -> Result<Vec<FormTerm>> {
    let mut terms: Vec<FormTerm> = Vec::new();
    for (n, f) in raw.iter().enumerate() {
        let key = format!("{KEY}.form[{n}]");
        let order = f.order;
        if order > MAX_FORM_ORDER as i64 {
            return Err(Error::invalid(
                format!("{key}.order"),
                format!(
                    "order {order} is above {MAX_FORM_ORDER}, the highest a form error may \
                     have: a wave of order k is about 2π·Rp/k long along the disc ({} mm here, \
                     {} mm at order {MAX_FORM_ORDER}), and a wave shorter than a loaded \
                     roller's contact (~0.1 mm wide) is flattened by it: the model, one contact \
                     point per roller, does not resolve it (a fit identifies orders up to 200)",
                    numeric::number(TAU * rp / order as f64),
                    numeric::number(TAU * rp / MAX_FORM_ORDER as f64)
                ),
            ));
        }
        if order < 2 || (order as usize).is_multiple_of(teeth) {
            return Err(Error::invalid(
                format!("{key}.order"),
                format!(
                    "the form error's harmonics are of orders 2 and up that are not multiples \
                     of the tooth count {teeth} (order 1 is the disc's centre, a multiple of \
                     {teeth} moves every tooth alike: the modification); got {order}"
                ),
            ));
        }
        if terms.iter().any(|t| t.order == order as usize) {
            return Err(Error::invalid(
                format!("{key}.order"),
                format!("order {order} is given twice"),
            ));
        }
        terms.push(FormTerm {
            order: order as usize,
            cos_mm: finite(&format!("{key}.cos_mm"), f.cos_mm)?,
            sin_mm: finite(&format!("{key}.sin_mm"), f.sin_mm)?,
        });
    }
    Ok(terms)
}

/// The rules of an as-built state: the ground profile (modification plus grinding errors) is a
/// disc (`rules::check`); no part moves by the eccentricity or more (the teeth are 2e deep and a
/// pin hole is e wider than its pin: a part moved that far is out of its mesh, as a disc centre
/// moved by e is, `SolveFailure::OutOfMesh`); and neighbouring rollers, as built, do not overlap.
pub(crate) fn check(design: &Design, m: &Modification) -> Result<()> {
    let d = &design.deviations;
    super::rules::check(design, &d.ground(m)).map_err(|mut e| {
        if d.shift_mm != 0.0 || d.equidistant_mm != 0.0 {
            e.message = format!(
                "as ground (with the grinding errors of {KEY}): {}",
                e.message
            );
        }
        e
    })?;
    let e = design.eccentricity_mm;
    let too_far = |key: String, what: String, moved: f64| -> Result<()> {
        if moved < e {
            return Ok(());
        }
        Err(rule(
            &key,
            format!(
                "{what} moves by {} mm, not less than the eccentricity e = {} mm: a part moved \
                 that far is out of its mesh (the teeth are 2e deep, a hole is e wider than its pin)",
                numeric::number(moved),
                numeric::input(e)
            ),
        ))
    };
    too_far(
        format!("{KEY}.eccentricity_mm"),
        "the crank eccentricity".into(),
        d.eccentricity_mm.abs(),
    )?;
    for (i, r) in d.rollers.iter().enumerate() {
        let moved = r.centre.size_mm() + r.radius_mm.abs();
        too_far(
            format!("{KEY}.rollers"),
            format!("roller {i} (centre and radius)"),
            moved,
        )?;
    }
    for (j, p) in d.pins.iter().enumerate() {
        too_far(format!("{KEY}.pins"), format!("pin {j}"), p.size_mm())?;
    }
    for (k, holes) in d.holes.iter().enumerate() {
        for (j, h) in holes.iter().enumerate() {
            let what = format!("hole {j} of disc {k}");
            too_far(format!("{KEY}.holes"), what, h.size_mm())?;
        }
    }
    too_far(
        format!("{KEY}.form"),
        "the form error (the sum of its amplitudes)".into(),
        d.form_bound_mm(),
    )?;
    regular_with_form(design, m)?;
    rollers_apart(design)
}

/// The ground profile with its form error stays regular: Γ' = A·T + B·N with
/// A = |C'|·(1 − (r' + w)·κ_C) must not turn back (A > 0), sampled at 64 points per period of
/// the highest harmonic and of the tooth; a form error that curls the flank is no disc.
fn regular_with_form(design: &Design, m: &Modification) -> Result<()> {
    let d = &design.deviations;
    if d.form.is_empty() {
        return Ok(());
    }
    let ground = d.ground(m);
    let locus = design.locus(&ground);
    let offset = design.roller_radius_mm + ground.equidistant_mm;
    let highest = d
        .form
        .iter()
        .map(|f| f.order)
        .max()
        .unwrap_or(1)
        .max(design.rollers);
    let samples = 16 * highest * 4;
    for k in 0..samples {
        let t = std::f64::consts::TAU * k as f64 / samples as f64;
        let kappa = locus.curvature_at(((design.rollers - 1) as f64 * t).cos());
        let w = d.form_mm(t);
        if 1.0 - (offset + w) * kappa <= 0.0 {
            return Err(rule(
                &format!("{KEY}.form"),
                format!(
                    "the form error undercuts the profile at t = {}°: r' + w = {} mm reaches \
                     the locus's radius of curvature {} mm there",
                    numeric::number(t.to_degrees()),
                    numeric::number(offset + w),
                    numeric::number(1.0 / kappa)
                ),
            ));
        }
    }
    Ok(())
}

/// Neighbouring rollers as built keep apart: centre distance above the sum of their radii.
fn rollers_apart(design: &Design) -> Result<()> {
    let d = &design.deviations;
    if !d.moves_rollers() {
        return Ok(());
    }
    let np = design.rollers;
    let rp = design.roller_circle_radius_mm;
    let centre = |i: usize| {
        let a = design.roller_angle(i);
        let (dx, dy) = d.roller(i).centre.displacement_mm(rp, (a.cos(), a.sin()));
        (rp * a.cos() + dx, rp * a.sin() + dy)
    };
    for i in 0..np {
        let j = (i + 1) % np;
        let ((xi, yi), (xj, yj)) = (centre(i), centre(j));
        let apart = (xi - xj).hypot(yi - yj);
        let radii = 2.0 * design.roller_radius_mm + d.roller(i).radius_mm + d.roller(j).radius_mm;
        if apart <= radii {
            return Err(rule(
                &format!("{KEY}.rollers"),
                format!(
                    "rollers {i} and {j} overlap as built: their centres are {} mm apart, \
                     less than the sum of their radii {} mm",
                    numeric::number(apart),
                    numeric::number(radii)
                ),
            ));
        }
    }
    Ok(())
}
