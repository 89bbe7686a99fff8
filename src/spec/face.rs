//! The keys of the contact along the face width (MODEL.md "Along the face width"):
//! `modification.crowning`, `scenes[].misalignment`, `scenes[].face_slices`, and the rule that a
//! crowned or tilted face is cut into slices where the scene loads it.

use super::raw::{RawCrowning, RawMisalignment};
use super::values::{finite, length, positive, tilt_rad};
use crate::error::{Error, Result};
use crate::model::face::{Crowning, Face, Misalignment};
use crate::model::scene::MAX_ROLLER_ANGLES;
use crate::model::{Design, Effect, Scene};
use crate::numeric;

/// Most slices a face may be cut into: 1000 resolve a line load to 0.1 % of the face width,
/// far below what the Winkler model itself resolves.
pub(crate) const MAX_FACE_SLICES: usize = 1000;

/// A crowning at `at` (`modification.crowning`, or a requirements file's `crowning`), checked
/// against the face width B = `face.0`, mm (`face.1` says which face width that is when it is
/// not the design's own; empty: the design's): a circular crown's radius > 0 and its flat
/// half-length in [0, B/2); a logarithmic profile's load, end drop and load coefficient > 0
/// and its crowned fraction in (0, 1]. A key of the other kind is refused.
pub(crate) fn crowning_at(at: &str, raw: &RawCrowning, face: (f64, &str)) -> Result<Crowning> {
    let key = |k: &str| format!("{at}.{k}");
    // The kind matched below (`circular`, `logarithmic`), which names both refusals.
    let kind = raw.kind.as_str();
    let refuse_foreign = |names: &[(&str, bool)]| -> Result<()> {
        match names.iter().find(|(_, given)| *given) {
            Some((name, _)) => Err(Error::invalid(
                key(name),
                format!("is not a key of the `{kind}` crowning"),
            )),
            None => Ok(()),
        }
    };
    let needed = |k: &str, v: Option<f64>| {
        v.ok_or_else(|| Error::invalid(at, format!("a `{kind}` crowning needs `{k}`")))
    };
    let half = 0.5 * face.0;
    let which = if face.1.is_empty() {
        String::new()
    } else {
        format!(" (B {})", face.1)
    };
    match kind {
        "circular" => {
            refuse_foreign(&[
                ("design_load_n", raw.design_load_n.is_some()),
                ("end_drop_mm", raw.end_drop_mm.is_some()),
                ("load_coefficient", raw.load_coefficient.is_some()),
                ("crowned_fraction", raw.crowned_fraction.is_some()),
            ])?;
            let radius_mm = length(&key("radius_mm"), needed("radius_mm", raw.radius_mm)?)?;
            let start_mm = finite(&key("start_mm"), raw.start_mm.unwrap_or(0.0))?;
            if !(0.0..half).contains(&start_mm) {
                return Err(Error::invalid(
                    key("start_mm"),
                    format!(
                        "the flat middle's half-length must lie in [0, B/2) = [0, {} mm){which}, \
                         got {}",
                        numeric::input(half),
                        numeric::input(start_mm)
                    ),
                ));
            }
            Ok(Crowning::Circular {
                radius_mm,
                start_mm,
            })
        }
        "logarithmic" => {
            refuse_foreign(&[
                ("radius_mm", raw.radius_mm.is_some()),
                ("start_mm", raw.start_mm.is_some()),
            ])?;
            let design_load_n = positive(
                &key("design_load_n"),
                needed("design_load_n", raw.design_load_n)?,
            )?;
            let end_drop_mm = length(&key("end_drop_mm"), needed("end_drop_mm", raw.end_drop_mm)?)?;
            let load_coefficient = positive(
                &key("load_coefficient"),
                raw.load_coefficient.unwrap_or(1.0),
            )?;
            let crowned_fraction = finite(
                &key("crowned_fraction"),
                raw.crowned_fraction.unwrap_or(1.0),
            )?;
            if !(crowned_fraction > 0.0 && crowned_fraction <= 1.0) {
                return Err(Error::invalid(
                    key("crowned_fraction"),
                    format!(
                        "the crowned share of each half of the face must lie in (0, 1], got {}",
                        numeric::input(crowned_fraction)
                    ),
                ));
            }
            Ok(Crowning::Logarithmic {
                design_load_n,
                end_drop_mm,
                load_coefficient,
                crowned_fraction,
            })
        }
        other => Err(Error::invalid(
            key("kind"),
            format!("unknown crowning `{other}`; known: circular, logarithmic"),
        )),
    }
}

/// A scene's `misalignment` (within ±`values::MAX_TILT_MRAD`, mrad → rad) and `face_slices` (1 to `MAX_FACE_SLICES`),
/// with no crowning yet (`apply` adds the design's); `key` the keys' prefix (`scenes[0].`, or
/// nothing for a requirements file's).
pub(crate) fn scene_face(
    key: &str,
    misalignment: Option<RawMisalignment>,
    slices: Option<i64>,
) -> Result<Face> {
    let misalignment = misalignment_at(&format!("{key}misalignment"), misalignment)?;
    let slices = match slices {
        None => 1,
        Some(n) if (1..=MAX_FACE_SLICES as i64).contains(&n) => n as usize,
        Some(n) => {
            return Err(Error::invalid(
                format!("{key}face_slices"),
                format!("must be an integer from 1 to {MAX_FACE_SLICES}, got {n}"),
            ))
        }
    };
    Ok(Face {
        crowning: Crowning::None,
        misalignment,
        slices,
    })
}

/// A tilt at `key` (a scene's `misalignment`, `reducer.deviations.misalignment`): each axis
/// within ±`values::MAX_TILT_MRAD`, mrad → rad; none given: no tilt.
pub(crate) fn misalignment_at(key: &str, raw: Option<RawMisalignment>) -> Result<Misalignment> {
    Ok(match raw {
        Some(m) => Misalignment {
            about_x_rad: tilt_rad(&format!("{key}.about_x_mrad"), m.about_x_mrad)?,
            about_y_rad: tilt_rad(&format!("{key}.about_y_mrad"), m.about_y_mrad)?,
        },
        None => Misalignment::default(),
    })
}

/// Give every scene the design's crowning and hold the rule of slices: a scene that loads the
/// contacts of a crowned or tilted face must cut it into 2 slices or more (the line load is
/// reported at the slices' centres; one slice would report none of its variation), refused at
/// its `face_slices` (or its `misalignment`, or the crowning, whichever it wrote; or at
/// `reducer.deviations.misalignment` when that tilt alone makes the face uneven); and its
/// line loads, rollers × crank angles × slices, must fit in memory.
pub(crate) fn apply(
    crowning: Crowning,
    design: &Design,
    scenes: &mut [Scene],
    written: &[(bool, bool)],
) -> Result<()> {
    for (i, (scene, &(tilt_given, slices_given))) in scenes.iter_mut().zip(written).enumerate() {
        scene.face.crowning = crowning;
        // The face as run: with the tilt as built (`reducer.deviations.misalignment`).
        let face = design.deviations.face(&scene.face);
        let loads = scene.effects.iter().any(|e| *e != Effect::Clearance);
        if loads && !face.is_uniform() && face.slices < 2 {
            let tilt = design.deviations.misalignment;
            if scene.face.is_uniform() {
                // Only the tilt as built makes this face uneven: refused at that tilt.
                return Err(Error::invalid(
                    "reducer.deviations.misalignment",
                    format!(
                        "tilts every scene's face by θx {} mrad, θy {} mrad, and scene `{}` \
                         (scenes[{i}]) loads its contacts with face_slices {}: a scene that \
                         loads a tilted face needs `face_slices: 2` or more (20 is a good \
                         start), the slices the line load is reported at",
                        numeric::number(1e3 * tilt.about_x_rad),
                        numeric::number(1e3 * tilt.about_y_rad),
                        scene.name,
                        face.slices
                    ),
                ));
            }
            let at = if slices_given {
                format!("scenes[{i}].face_slices")
            } else if tilt_given && !face.misalignment.is_zero() {
                format!("scenes[{i}].misalignment")
            } else {
                "modification.crowning".to_string()
            };
            return Err(Error::invalid(
                at,
                format!(
                    "scene `{}` loads a crowned or tilted face: give it `face_slices: 2` or more \
                     (20 is a good start), the slices the line load is reported at",
                    scene.name
                ),
            ));
        }
        let contacts = design.rollers.max(design.pins.count);
        let key = format!("scenes[{i}].face_slices");
        line_loads_fit(&key, face.slices, (contacts, scene.crank_rad.len()), "")?;
    }
    Ok(())
}

/// The line loads of a face cut into `slices` (2 or more; one slice holds none), `contacts`
/// × `angles` × `slices` of them, fit in a scene's memory (`MAX_ROLLER_ANGLES`), else the
/// refusal at `key`; `case` names the design they are of (" (ratio 9, 6 pins)"), or is empty.
pub(crate) fn line_loads_fit(
    key: &str,
    slices: usize,
    (contacts, angles): (usize, usize),
    case: &str,
) -> Result<()> {
    let cells = (contacts * angles) as i64 * slices as i64;
    if slices < 2 || cells <= MAX_ROLLER_ANGLES {
        return Ok(());
    }
    Err(Error::invalid(
        key,
        format!(
            "{slices} slices × {contacts} contacts × {angles} crank angles{case} is {cells} line \
             loads, more than the {MAX_ROLLER_ANGLES} a scene may hold; give fewer slices or steps"
        ),
    ))
}
