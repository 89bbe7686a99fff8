//! The raw spec → the validated model: every value checked and converted to engine units; the
//! first broken rule is the error, with its key path.

use super::paths::resolve;
use super::raw::*;
use super::rules::rule;
use super::scenes::{refuse_duty, refuse_first_order, scene_index};
use super::validated::{Accuracy, Spec};
use super::values::{disc_index, finite, length, named, not_blank, positive, zero_or_positive};
use super::yaml::{did_you_mean, unknown_key};
use crate::error::{Error, ErrorKind, Result};
use crate::model::accuracy as acc;
use crate::model::quantity;
use crate::model::scene::MAX_ROLLER_ANGLES;
use crate::model::study::{
    default_boundary_samples, default_global_samples, default_verify_grid, MAX_GLOBAL_SAMPLES,
    MAX_LOCAL_EVALUATIONS, MAX_VERIFY_POINTS,
};
use crate::model::*;
use crate::{numeric, units};
use std::collections::BTreeMap;

/// Largest crank angle magnitude, degrees (~28,000 revolutions): an angle's rounding stays
/// below 1e-9 rad.
pub const MAX_CRANK_DEG: f64 = 1e7;

/// An angle in degrees within ±`MAX_CRANK_DEG` (a crank angle, a profile rotation).
fn angle_deg(key: &str, value: f64) -> Result<f64> {
    let value = finite(key, value)?;
    if value.abs() > MAX_CRANK_DEG {
        return Err(Error::invalid(
            key,
            format!(
                "{}° is beyond ±{MAX_CRANK_DEG}° (about 28,000 revolutions), where the \
                 angle's rounding would exceed 1e-9 rad",
                numeric::input(value)
            ),
        ));
    }
    Ok(value)
}

fn count(key: &str, value: i64, min: i64) -> Result<usize> {
    if value >= min {
        Ok(value as usize)
    } else {
        Err(Error::invalid(
            key,
            format!("must be at least {min}, got {value}"),
        ))
    }
}

/// A count in [min, max]; `why` says where the cap comes from.
fn count_capped(key: &str, value: i64, min: i64, max: usize, why: &str) -> Result<usize> {
    let n = count(key, value, min)?;
    if n <= max {
        Ok(n)
    } else {
        Err(Error::invalid(
            key,
            format!("must be at most {max} ({why}), got {value}"),
        ))
    }
}

pub(super) fn material(key: &str, raw: RawMaterial) -> Result<Material> {
    let youngs_gpa = positive(&format!("{key}.youngs_modulus_gpa"), raw.youngs_modulus_gpa)?;
    let nu = raw.poisson_ratio;
    if !(nu.is_finite() && (0.0..0.5).contains(&nu)) {
        return Err(Error::invalid(
            format!("{key}.poisson_ratio"),
            format!("must lie in [0, 0.5), got {}", numeric::input(nu)),
        ));
    }
    Ok(Material {
        youngs_modulus_mpa: units::mpa(youngs_gpa),
        poisson_ratio: nu,
    })
}

fn design(raw: &RawReducer) -> Result<Design> {
    let mut design = nominal_design(raw)?;
    bore_fits(&design)?;
    design.friction = (raw.friction.as_ref())
        .map(|f| super::friction::friction(f, &design))
        .transpose()?;
    // Its rule reads the rollers' friction mode.
    design.roller_inertia_kgmm2 = super::mass::roller_inertia(raw.roller_inertia_kgm2, &design)?;
    if let Some(d) = &raw.deviations {
        design.deviations = super::deviations::build(d, &design)?;
    }
    Ok(design)
}

fn nominal_design(raw: &RawReducer) -> Result<Design> {
    let teeth = count("reducer.teeth", raw.teeth, 2)?;
    let rollers = count("reducer.rollers", raw.rollers, 3)?;
    if rollers != teeth + 1 {
        return Err(rule(
            "reducer.rollers",
            format!(
                "rollers must equal teeth + 1 (one-tooth-difference reducer): \
                 rollers = {rollers}, teeth = {teeth}"
            ),
        ));
    }
    let pins = &raw.output_pins;
    let strength =
        super::strength::materials_at("reducer.", &raw.material, raw.roller_material.as_ref())?;
    let mass = super::mass::inputs(raw)?;
    let disc_material = material("reducer.material", raw.material)?;
    let roller_material = match raw.roller_material {
        Some(m) => material("reducer.roller_material", m)?,
        None => disc_material,
    };
    let clearance_key = "reducer.output_pins.hole_clearance_mm";
    let clearance = zero_or_positive(clearance_key, raw.output_pins.hole_clearance_mm)?;
    if clearance > 0.0 {
        length(clearance_key, clearance)?;
    }
    let discs = count_capped(
        "reducer.discs",
        raw.discs,
        1,
        MAX_DISCS,
        "reducers are built with one to three discs",
    )?;
    let face_width_mm = length("reducer.face_width_mm", raw.face_width_mm)?;
    let support = pins
        .support
        .as_ref()
        .map(|s| pin_support("reducer.output_pins.support", s, discs, face_width_mm))
        .transpose()?;
    let structure_compliance_rad_per_nmm = raw
        .structure_compliance_arcmin_per_knm
        .map(structure_compliance)
        .transpose()?
        .unwrap_or(0.0);
    Ok(Design {
        teeth,
        rollers,
        discs,
        eccentricity_mm: length("reducer.eccentricity_mm", raw.eccentricity_mm)?,
        roller_circle_radius_mm: length(
            "reducer.roller_circle_radius_mm",
            raw.roller_circle_radius_mm,
        )?,
        roller_radius_mm: length("reducer.roller_radius_mm", raw.roller_radius_mm)?,
        face_width_mm,
        pins: OutputPins {
            count: count("reducer.output_pins.count", pins.count, 2)?,
            circle_radius_mm: length(
                "reducer.output_pins.circle_radius_mm",
                pins.circle_radius_mm,
            )?,
            pin_radius_mm: length("reducer.output_pins.pin_radius_mm", pins.pin_radius_mm)?,
            hole_clearance_mm: clearance,
            support,
        },
        disc_material,
        roller_material,
        strength,
        crank_bearing: (raw.crank_bearing.as_ref())
            .map(|b| crank_bearing("reducer.crank_bearing", b))
            .transpose()?,
        deviations: Deviations::default(),
        friction: None,
        thermal: raw
            .thermal
            .as_ref()
            .map(|t| super::friction::thermal_at("reducer.thermal", t))
            .transpose()?,
        structure_compliance_rad_per_nmm,
        density_kg_per_mm3: mass.density_kg_per_mm3,
        output_inertia_kgmm2: mass.output_inertia_kgmm2,
        roller_inertia_kgmm2: 0.0,
    })
}

/// `reducer.output_pins.support` (at `key`): a known kind, a length within the lengths the
/// tool takes, one position per disc, each in (0, length], and the discs' mid-planes at least a
/// face width B apart (two discs cannot overlap along the pin).
pub(super) fn pin_support(
    key: &str,
    raw: &RawPinSupport,
    discs: usize,
    face_width_mm: f64,
) -> Result<PinSupport> {
    let kind = named::<PinSupportKind>(&format!("{key}.kind"), Some(&raw.kind))?
        .expect("a kind was given");
    let length_mm = length(&format!("{key}.length_mm"), raw.length_mm)?;
    let positions_key = format!("{key}.disc_positions_mm");
    if raw.disc_positions_mm.len() != discs {
        return Err(Error::invalid(
            positions_key,
            format!(
                "gives {} position(s) for {discs} disc(s) (`reducer.discs`): one mid-plane per \
                 disc, mm from the flange",
                raw.disc_positions_mm.len()
            ),
        ));
    }
    for (k, &a) in raw.disc_positions_mm.iter().enumerate() {
        let at = format!("{positions_key}[{k}]");
        let a = finite(&at, a)?;
        if !(a > 0.0 && a <= length_mm) {
            return Err(Error::invalid(
                at,
                format!(
                    "disc {k}'s mid-plane at {} mm is outside the pin, (0, {}] mm from the flange \
                     (`length_mm`)",
                    numeric::input(a),
                    numeric::input(length_mm)
                ),
            ));
        }
        for (m, &b) in raw.disc_positions_mm[..k].iter().enumerate() {
            if (a - b).abs() < face_width_mm {
                return Err(Error::invalid(
                    at,
                    format!(
                        "disc {k}'s mid-plane at {} mm is {} mm from disc {m}'s, less than the \
                         face width {} mm: the discs would overlap along the pin",
                        numeric::input(a),
                        numeric::input((a - b).abs()),
                        numeric::input(face_width_mm)
                    ),
                ));
            }
        }
    }
    let mut disc_positions_mm = [0.0; MAX_DISCS];
    disc_positions_mm[..discs].copy_from_slice(&raw.disc_positions_mm);
    Ok(PinSupport {
        kind,
        length_mm,
        disc_positions_mm,
    })
}

/// `reducer.structure_compliance_arcmin_per_knm` (≥ 0, finite) in rad/(N·mm): arcmin/(kN·m)
/// × (π/10800 rad/arcmin) / (10⁶ N·mm/(kN·m)).
fn structure_compliance(arcmin_per_knm: f64) -> Result<f64> {
    let key = "reducer.structure_compliance_arcmin_per_knm";
    if !(arcmin_per_knm.is_finite() && arcmin_per_knm >= 0.0) {
        return Err(Error::invalid(
            key,
            format!(
                "must be zero or positive (a compliance, arcmin per kN·m), got {}",
                numeric::input(arcmin_per_knm)
            ),
        ));
    }
    Ok(units::rad_per_nmm_from_arcmin_per_knm(arcmin_per_knm))
}

/// `reducer.crank_bearing` (or a requirements file's `crank_bearing`, at `key`): a positive
/// rating and life exponent (10/3 by default).
pub(super) fn crank_bearing(key: &str, raw: &RawCrankBearing) -> Result<CrankBearing> {
    Ok(CrankBearing {
        dynamic_load_rating_n: positive(
            &format!("{key}.dynamic_load_rating_n"),
            raw.dynamic_load_rating_n,
        )?,
        life_exponent: raw
            .life_exponent
            .map(|p| life_exponent(&format!("{key}.life_exponent"), p))
            .transpose()?
            .unwrap_or(CrankBearing::ROLLER_LIFE_EXPONENT),
        outer_diameter_mm: raw
            .outer_diameter_mm
            .map(|d| length(&format!("{key}.outer_diameter_mm"), d))
            .transpose()?,
        static_load_rating_n: raw
            .static_load_rating_n
            .map(|c| positive(&format!("{key}.static_load_rating_n"), c))
            .transpose()?,
    })
}

/// `reducer.crank_bearing.outer_diameter_mm`: the bore it cuts stays clear of the output-pin
/// holes, whose edges come within rw − (rrp + e + c) of the disc centre (the profile's root lies
/// farther out: the holes are inside the disc).
fn bore_fits(design: &Design) -> Result<()> {
    let Some(d) = design.crank_bearing.and_then(|b| b.outer_diameter_mm) else {
        return Ok(());
    };
    let inner_edge = design.pins.circle_radius_mm - design.hole_radius_mm();
    if 0.5 * d < inner_edge {
        return Ok(());
    }
    Err(rule(
        "reducer.crank_bearing.outer_diameter_mm",
        format!(
            "the bore of the crank bearing (radius {} mm) reaches the output-pin holes, whose \
             edges come within rw − (pin radius + e + hole clearance) = {} − {} = {} mm of the \
             disc centre: the bore's radius must be smaller",
            numeric::input(0.5 * d),
            numeric::input(design.pins.circle_radius_mm),
            numeric::input(design.hole_radius_mm()),
            numeric::input(inner_edge)
        ),
    ))
}

/// The exponents a rating life accepts (`reducer.crank_bearing.life_exponent`): ISO 281 uses
/// 3 for ball bearings and 10/3 for roller bearings, and rolling-contact fatigue laws in the
/// literature stay within 1 to 10. Outside it the life (C/P)^p is no bearing's: at p = 1000
/// a load 1 % below the rating would live (1/0.99)^1000 ≈ 2.3·10⁴ times longer than at it,
/// and (C/P)^p overflows a double once C/P passes 2.03.
const LIFE_EXPONENTS: (f64, f64) = (1.0, 10.0);

/// A life exponent within `LIFE_EXPONENTS`.
pub(super) fn life_exponent(key: &str, p: f64) -> Result<f64> {
    let (lo, hi) = LIFE_EXPONENTS;
    if p.is_finite() && (lo..=hi).contains(&p) {
        return Ok(p);
    }
    Err(Error::invalid(
        key,
        format!(
            "must be between {lo} and {hi}, got {}: ISO 281 uses 3 for ball bearings and 10/3 \
             for roller bearings (the default); rolling-contact fatigue laws stay within {lo} \
             to {hi}",
            numeric::input(p)
        ),
    ))
}

/// `torque_sweep` of a scene with `angles` crank angles: a positive rated torque, at least one
/// step per quarter of the loop, and angles × loop torques within the results' memory cap.
fn torque_sweep(key: &str, raw: &RawTorqueSweep, angles: usize) -> Result<TorqueSweep> {
    let rated = positive(&format!("{key}.rated_nm"), raw.rated_nm)?;
    let per_loop = (MAX_ROLLER_ANGLES as usize / angles.max(1) - 1) / 4;
    let steps = count_capped(
        &format!("{key}.steps"),
        raw.steps,
        1,
        per_loop,
        "crank angles × loop torques (4·steps + 1) ≤ 10 000 000, so the torsion curves fit in \
         memory",
    )?;
    Ok(TorqueSweep {
        rated_nmm: units::nmm(rated),
        steps,
    })
}

/// A modification at `key` (`modification`, or a study's `references[j]`): shift and
/// equidistant finite, mm; rotation within ±`MAX_CRANK_DEG`, degrees → rad.
fn modification_at(
    key: &str,
    (shift, equidistant, rotation_deg): (f64, f64, f64),
) -> Result<Modification> {
    Ok(Modification {
        shift_mm: finite(&format!("{key}.shift_mm"), shift)?,
        equidistant_mm: finite(&format!("{key}.equidistant_mm"), equidistant)?,
        rotation_rad: units::rad(angle_deg(&format!("{key}.rotation_deg"), rotation_deg)?),
    })
}

/// The crank angles of a scene; `used` is the rollers × steps of the scenes before it.
fn crank(key: &str, raw: &RawCrank, rollers: usize, used: i64) -> Result<Vec<f64>> {
    let from = angle_deg(&format!("{key}.from_deg"), raw.from_deg)?;
    let to = angle_deg(&format!("{key}.to_deg"), raw.to_deg)?;
    let steps = raw.steps;
    if steps < 1 {
        return Err(Error::invalid(
            format!("{key}.steps"),
            format!("a crank range needs at least 1 step, got {steps}"),
        ));
    }
    let max_steps = (MAX_ROLLER_ANGLES - used) / rollers.max(1) as i64;
    if steps > max_steps {
        let others = if used > 0 {
            format!(" over all scenes; the scenes before this one use {used}")
        } else {
            String::new()
        };
        return Err(Error::invalid(
            format!("{key}.steps"),
            format!(
                "at most {max_steps} steps with {rollers} rollers \
                 (rollers × steps ≤ {MAX_ROLLER_ANGLES}{others}), got {steps}"
            ),
        ));
    }
    if to <= from {
        return Err(Error::invalid(
            format!("{key}.to_deg"),
            format!("the crank range is empty: to_deg = {to} must exceed from_deg = {from}"),
        ));
    }
    let angles = crank_angles(from, to, steps as usize);
    // Each step must move the crank: a range narrower than the doubles' spacing near it
    // repeats angles, and the ratio (a derivative over neighbours) is then undefined.
    if let Some(k) = angles.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::invalid(
            format!("{key}.steps"),
            format!(
                "{steps} steps from {from}° to {to}° are not distinct angles (steps {k} and {} \
                 are the same double, {} rad): the range is too narrow for double precision \
                 there; give fewer steps or a wider range",
                k + 1,
                angles[k]
            ),
        ));
    }
    Ok(angles)
}

/// Crank angles of a range in rad: `from + k·(to − from)/steps` degrees, k = 0 … steps − 1.
/// Grids of `steps` and `steps·2^m` over the same range nest exactly: every angle of the coarser
/// is, bit for bit, the angle 2^m·k of the finer (division and multiplication by a power of two
/// are exact in binary floating point).
pub fn crank_angles(from_deg: f64, to_deg: f64, steps: usize) -> Vec<f64> {
    let step = (to_deg - from_deg) / steps as f64;
    (0..steps)
        .map(|k| units::rad(from_deg + step * k as f64))
        .collect()
}

fn scene(index: usize, raw: RawScene, rollers: usize, used: i64) -> Result<Scene> {
    let key = format!("scenes[{index}]");
    not_blank(&format!("{key}.name"), &raw.name)?;
    let mut effects = Vec::new();
    for (j, name) in raw.effects.iter().enumerate() {
        let effect = Effect::listed().find(|e| e.name() == name).ok_or_else(|| {
            let known: Vec<&str> = Effect::listed().map(|e| e.name()).collect();
            let message = match did_you_mean(name, known.iter().copied()) {
                Some(close) => format!("unknown effect `{name}`; did you mean `{close}`?"),
                None => format!(
                    "unknown effect `{name}`; known effects: {}",
                    known.join(", ")
                ),
            };
            Error::invalid(format!("{key}.effects[{j}]"), message)
        })?;
        if !effects.contains(&effect) {
            effects.push(effect);
        }
    }
    if effects.is_empty() {
        return Err(Error::invalid(
            format!("{key}.effects"),
            "a scene must ask for at least one effect".into(),
        ));
    }
    let contact_law = named(&format!("{key}.contact_law"), raw.contact_law.as_deref())?
        .unwrap_or(ContactLaw::PaperLinear);
    let geometry =
        named(&format!("{key}.geometry"), raw.geometry.as_deref())?.unwrap_or(GeometryMode::Exact);
    let bearing_stiffness_n_per_mm = raw
        .bearing_stiffness_n_per_mm
        .map(|k| positive(&format!("{key}.bearing_stiffness_n_per_mm"), k))
        .transpose()?;
    let crank_rad = crank(&format!("{key}.crank"), &raw.crank, rollers, used)?;
    let duty_cycle = super::duty_cycle::duty_cycle(&key, &raw, &effects)?;
    if raw.torque_sweep.is_some() && raw.output_torque_nm.is_some() {
        return Err(Error::invalid(
            format!("{key}.output_torque_nm"),
            "a scene with `torque_sweep` loads the output with its own torque loop; give \
             either `torque_sweep` or `output_torque_nm`, not both"
                .into(),
        ));
    }
    let torque_sweep = (raw.torque_sweep.as_ref())
        .map(|t| torque_sweep(&format!("{key}.torque_sweep"), t, crank_rad.len()))
        .transpose()?;
    if let Some(e) = effects.iter().find(|e| e.reads_the_sweep()) {
        if torque_sweep.is_some() {
            return Err(Error::invalid(
                format!("{key}.effects"),
                format!(
                    "`{e}` is read off the loaded curves over the crank angle, which a scene \
                     with `torque_sweep` does not compute (it locks the input at each angle: \
                     docs/effects/torsion.md); ask for it in a scene with `output_torque_nm`"
                ),
            ));
        }
    }
    let input_speed_rpm = raw
        .input_speed_rpm
        .map(|n| {
            let key = format!("{key}.input_speed_rpm");
            super::values::speed_rpm(&key, positive(&key, n)?)
        })
        .transpose()?;
    let face = super::face::scene_face(&format!("{key}."), raw.misalignment, raw.face_slices)?;
    Ok(Scene {
        output_torque_nmm: units::nmm(finite(
            &format!("{key}.output_torque_nm"),
            raw.output_torque_nm.unwrap_or(0.0),
        )?),
        crank_rad,
        torque_sweep,
        input_speed_rpm,
        crank_from_deg: raw.crank.from_deg,
        crank_to_deg: raw.crank.to_deg,
        name: raw.name,
        effects,
        contact_law,
        geometry,
        bearing_stiffness_n_per_mm,
        duty_cycle,
        face,
    })
}

/// The limits a spec sets, in the registry's order; an unknown key is an error naming the
/// closest known one.
pub(super) fn limits(raw: &RawLimits) -> Result<Limits> {
    const OPTIMUM: &str = "optimum_max_objective";
    const RESOLVED: &str = "accuracy_resolved";
    let known: Vec<&str> = (quantity::LIMITS.iter().map(|l| l.key))
        .chain([OPTIMUM, RESOLVED])
        .collect();
    if let Some(unknown) = raw.keys().find(|k| !known.contains(&k.as_str())) {
        let message = unknown_key(unknown, &known);
        return Err(Error::new(ErrorKind::Syntax, message).at_key(format!("limits.{unknown}")));
    }
    let bound = |key: &str| -> Result<Option<f64>> {
        let at = format!("limits.{key}");
        match raw.get(key) {
            None => Ok(None),
            Some(RawLimit::Bound(x)) => finite(&at, *x).map(Some),
            Some(RawLimit::Flag(b)) => {
                Err(Error::invalid(&at, format!("must be a number, got {b}")))
            }
        }
    };
    let mut entries = Vec::new();
    for def in quantity::LIMITS {
        let Some(value) = bound(def.key)? else {
            continue;
        };
        if def.quantity.is_count() && (value.fract() != 0.0 || value < 0.0) {
            return Err(Error::invalid(
                format!("limits.{}", def.key),
                format!(
                    "must be a whole number of at least 0, got {}",
                    numeric::input(value)
                ),
            ));
        }
        let (lowest, highest) = def.range;
        if !(lowest..=highest).contains(&value) {
            return Err(Error::invalid(
                format!("limits.{}", def.key),
                format!(
                    "must be {}: {} takes no other value, got {}",
                    if highest.is_finite() {
                        format!(
                            "in [{}, {}]",
                            numeric::input(lowest),
                            numeric::input(highest)
                        )
                    } else {
                        format!("at least {}", numeric::input(lowest))
                    },
                    def.quantity.key,
                    numeric::input(value)
                ),
            ));
        }
        entries.push(Limit { def, value });
    }
    let accuracy_resolved = match raw.get(RESOLVED) {
        None => false,
        Some(RawLimit::Flag(b)) => *b,
        Some(RawLimit::Bound(x)) => {
            return Err(Error::invalid(
                format!("limits.{RESOLVED}"),
                format!("must be true or false, got {x}"),
            ))
        }
    };
    Ok(Limits {
        entries,
        optimum_max_objective: bound(OPTIMUM)?,
        accuracy_resolved,
    })
}

pub(crate) fn build(path: &str, text: &str, raw: RawSpec) -> Result<Spec> {
    not_blank("name", &raw.name)?;
    let design = design(&raw.reducer)?;
    let m = &raw.modification;
    let modification = modification_at(
        "modification",
        (m.shift_mm, m.equidistant_mm, m.rotation_deg),
    )?;
    super::deviations::check(&design, &modification)?;
    if raw.scenes.is_empty() {
        return Err(Error::invalid(
            "scenes",
            "a spec needs at least one scene".into(),
        ));
    }
    let crowning = (raw.modification.crowning.as_ref())
        .map(|c| super::face::crowning_at("modification.crowning", c, (design.face_width_mm, "")))
        .transpose()?
        .unwrap_or_default();
    let written: Vec<(bool, bool)> = (raw.scenes.iter())
        .map(|s| (s.misalignment.is_some(), s.face_slices.is_some()))
        .collect();
    let mut scenes: Vec<Scene> = Vec::new();
    for (i, s) in raw.scenes.into_iter().enumerate() {
        // The cap on rollers × steps holds for all scenes together: they are computed, and
        // their results held, at once.
        let used = scenes.iter().map(|s| s.crank_rad.len()).sum::<usize>() * design.rollers;
        let s = scene(i, s, design.rollers, used as i64)?;
        if scenes.iter().any(|other| other.name == s.name) {
            return Err(Error::invalid(
                format!("scenes[{i}].name"),
                format!("scene name `{}` is used twice", s.name),
            ));
        }
        scenes.push(s);
    }
    super::face::apply(crowning, &design, &mut scenes, &written)?;
    exact_as_built(&design, &scenes)?;
    super::friction::check_scenes(&design, &scenes)?;
    first_order_torques(&design, &scenes)?;
    let (raws, many) = match raw.optimise {
        None => (Vec::new(), false),
        Some(RawOptimise::One(s)) => (vec![*s], false),
        Some(RawOptimise::Many(v)) => (v, true),
    };
    let mut studies: Vec<Study> = Vec::new();
    for (i, r) in raws.into_iter().enumerate() {
        let key = if many {
            format!("optimise[{i}]")
        } else {
            "optimise".to_string()
        };
        let s = study(&key, i, r, &scenes, (&modification, crowning, &design))?;
        super::periods::check_study(&s, &key, &design, &scenes)?;
        if studies.iter().any(|o| o.name == s.name) {
            return Err(Error::invalid(
                format!("{key}.name"),
                format!("study name `{}` is used twice", s.name),
            ));
        }
        studies.push(s);
    }
    let limits = limits(&raw.limits)?;
    let built = (!design.deviations.is_nominal()).then_some("`reducer.deviations`");
    let every_scene = || scenes.iter().enumerate();
    every_scene().try_for_each(|s| super::bearing_life::check_scene(&limits, &design, s, built))?;
    super::strength::check(&limits, &design, &scenes)?;
    super::inertia::check(&design, &scenes)?;
    super::bearing_push::check(&design, &scenes)?;
    every_scene().try_for_each(|s| super::periods::check_scene(&limits, &design, s, built))?;
    super::friction::check_limits(&limits, &design, &scenes)?;
    let mut golden = Vec::new();
    for (i, g) in raw.golden.into_iter().enumerate() {
        let g = golden_entry(path, i, g, (&scenes, design.discs))?;
        if let Some(other) = golden.iter().find(|o: &&Golden| o.path == g.path) {
            return Err(Error::invalid(
                format!("golden[{i}].file"),
                format!(
                    "golden file `{}` is already used by {}; every golden curve needs its own file",
                    g.file, other.key
                ),
            ));
        }
        golden.push(g);
    }
    let golden_root = (raw.golden_root.as_deref())
        .map(|r| not_blank("golden_root", r).map(|()| resolve(path, r)))
        .transpose()?;
    let accuracy = raw
        .accuracy
        .map(|a| accuracy_section(a, &scenes, &design))
        .transpose()?;
    if limits.accuracy_resolved && accuracy.is_none() {
        return Err(Error::invalid(
            "limits.accuracy_resolved",
            "needs an `accuracy:` section: its scene and tolerances say what resolved means"
                .to_string(),
        ));
    }
    let measured = raw
        .measured_profile
        .map(|m| super::measured::build(path, m))
        .transpose()?;
    let tolerances = raw
        .tolerances
        .map(|t| super::tolerances::build(&t, (&design, &modification), &scenes, &limits))
        .transpose()?;
    Ok(Spec {
        tolerances,
        measured,
        name: raw.name,
        path: path.to_string(),
        source: text.to_string(),
        design,
        modification,
        scenes,
        limits,
        golden,
        golden_root,
        studies,
        accuracy,
    })
}

/// Parts as built are computed with the exact geometry: the first-order closed form holds every
/// roller and pin on its nominal place (MODEL.md "Part deviations").
fn exact_as_built(design: &Design, scenes: &[Scene]) -> Result<()> {
    if design.deviations.is_nominal() {
        return Ok(());
    }
    refuse_first_order(
        scenes,
        "`reducer.deviations` puts parts off their nominal places: the closed form assumes \
         every roller and pin on its place, so parts as built are computed with \
         `geometry: exact`",
    )
}

/// A first-order scene's torque (its output torque, or its loop's rated torque) within
/// `Design::first_order_torque_bound_nmm`, where the closed form's forces are still contact
/// forces and finite.
fn first_order_torques(design: &Design, scenes: &[Scene]) -> Result<()> {
    let bound = design.first_order_torque_bound_nmm();
    for (i, s) in scenes.iter().enumerate() {
        if s.geometry != GeometryMode::FirstOrder {
            continue;
        }
        let (key, torque) = match &s.torque_sweep {
            Some(t) => ("torque_sweep.rated_nm", t.rated_nmm),
            None => ("output_torque_nm", s.output_torque_nmm),
        };
        if torque.abs() > bound {
            return Err(Error::invalid(
                format!("scenes[{i}].{key}"),
                format!(
                    "{} N·m is beyond what the first-order geometry can hold, {} N·m: that \
                     torque presses every roller by its own radius ({} mm) at the largest \
                     first-order arm e·nc = {} mm, on the paper's law, where no contact is \
                     left to linearise; use `geometry: exact`, which says how much the \
                     rollers hold",
                    numeric::input(units::nm(torque)),
                    numeric::number(units::nm(bound)),
                    numeric::input(design.roller_radius_mm),
                    numeric::number(design.eccentricity_mm * design.teeth as f64)
                ),
            ));
        }
    }
    Ok(())
}

/// `accuracy:`: the scene exists and computes something the ladder compares, the rungs are
/// rungs of the ladder, the tolerances are positive.
fn accuracy_section(raw: RawAccuracy, scenes: &[Scene], design: &Design) -> Result<Accuracy> {
    let scene = scene_index(scenes, &raw.scene, "accuracy.scene")?;
    refuse_duty(scenes, scene, "accuracy.scene", "the accuracy ladder")?;
    let steps = |key: &str, value: Option<i64>, min: usize| {
        value
            .map(|n| {
                acc::ladder_steps(n, min).map_err(|m| Error::invalid(format!("accuracy.{key}"), m))
            })
            .transpose()
    };
    let finest = steps(
        "finest_steps_per_period",
        raw.finest_steps_per_period,
        2 * acc::COARSEST,
    )?
    .unwrap_or(acc::DEFAULT_FINEST);
    let settings_steps = steps(
        "settings_steps_per_period",
        raw.settings_steps_per_period,
        acc::COARSEST,
    )?;
    let defaults = acc::LadderTolerances::default();
    let t = &raw.tolerance;
    let tol = |key: &str, value: Option<f64>, default: f64| {
        value.map_or(Ok(default), |v| {
            acc::tolerance(v).map_err(|m| Error::invalid(format!("accuracy.tolerance.{key}"), m))
        })
    };
    let options = acc::Options {
        finest,
        settings_steps,
        tolerances: acc::LadderTolerances {
            te_arcsec: tol("te_arcsec", t.te_arcsec, defaults.te_arcsec)?,
            force_n: tol("force_n", t.force_n, defaults.force_n)?,
            ratio: tol("ratio", t.ratio, defaults.ratio)?,
            clearance_um: tol("clearance_um", t.clearance_um, defaults.clearance_um)?,
            face_load_factor: tol(
                "face_load_factor",
                t.face_load_factor,
                defaults.face_load_factor,
            )?,
            line_load_n_per_mm: tol(
                "line_load_n_per_mm",
                t.line_load_n_per_mm,
                defaults.line_load_n_per_mm,
            )?,
        },
    };
    acc::check(design, &scenes[scene], &options).map_err(|(which, m)| {
        let key = match which {
            acc::Setting::Scene => "accuracy.scene",
            acc::Setting::Finest => "accuracy.finest_steps_per_period",
            acc::Setting::SettingsSteps => "accuracy.settings_steps_per_period",
        };
        Error::invalid(key, m)
    })?;
    Ok(Accuracy { scene, options })
}

fn golden_entry(
    path: &str,
    i: usize,
    raw: RawGolden,
    (scenes, discs): (&[Scene], usize),
) -> Result<Golden> {
    let key = format!("golden[{i}]");
    let disc = raw
        .disc
        .map(|k| disc_index(&format!("{key}.disc"), k, discs))
        .transpose()?;
    let index = scene_index(scenes, &raw.scene, &format!("{key}.scene"))?;
    refuse_duty(scenes, index, &format!("{key}.scene"), "a golden curve")?;
    let quantity = quantity::find_curve(&raw.quantity).ok_or_else(|| {
        Error::invalid(
            format!("{key}.quantity"),
            format!(
                "unknown quantity `{}`; known quantities: {}",
                raw.quantity,
                quantity::curve_keys()
            ),
        )
    })?;
    match (discs > 1, quantity.of_reducer(), disc) {
        (true, false, None) => {
            return Err(Error::invalid(
                format!("{key}.quantity"),
                format!(
                    "with {discs} discs `{}` is a curve of each disc: name the disc \
                     (`disc: 0` to `disc: {}`)",
                    quantity.key,
                    discs - 1
                ),
            ))
        }
        (true, true, Some(_)) => {
            return Err(Error::invalid(
                format!("{key}.disc"),
                format!("`{}` is the reducer's curve, not a disc's", quantity.key),
            ))
        }
        _ => {}
    }
    not_blank(&format!("{key}.file"), &raw.file)?;
    let (abs, rel) = (raw.tolerance.abs, raw.tolerance.rel);
    zero_or_positive(&format!("{key}.tolerance.abs"), abs)?;
    zero_or_positive(&format!("{key}.tolerance.rel"), rel)?;
    if abs == 0.0 && rel == 0.0 {
        return Err(Error::invalid(
            format!("{key}.tolerance"),
            "abs and rel are both zero: no computed curve matches to the last bit on every \
             machine; give a band"
                .into(),
        ));
    }
    Ok(Golden {
        path: resolve(path, &raw.file),
        key,
        scene: raw.scene,
        quantity,
        disc,
        file: raw.file,
        tolerance: GoldenTolerance { abs, rel },
    })
}

fn bounds(key: &str, b: [f64; 2]) -> Result<(f64, f64)> {
    let [lo, hi] = b;
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return Err(Error::invalid(
            key,
            format!(
                "bounds must be two finite numbers [lower, upper] with lower < upper, got [{}, {}]",
                numeric::input(lo),
                numeric::input(hi)
            ),
        ));
    }
    Ok((lo, hi))
}

/// The objective named `name`, else an error at `key` listing the objectives.
fn find_objective(key: &str, name: &str) -> Result<Objective> {
    quantity::find_objective(name).ok_or_else(|| {
        Error::invalid(
            key,
            format!(
                "unknown objective `{name}`; known objectives: {}",
                quantity::objective_names()
            ),
        )
    })
}

fn objective(key: &str, raw: RawObjective) -> Result<Vec<(Objective, f64)>> {
    let named = |name: &str| find_objective(key, name);
    match raw {
        RawObjective::Name(name) => Ok(vec![(named(&name)?, 1.0)]),
        RawObjective::Weighted(map) => {
            if map.is_empty() {
                return Err(Error::invalid(
                    key,
                    "a weighted objective needs at least one term".into(),
                ));
            }
            map.into_iter()
                .map(|(name, w)| {
                    if !(w.is_finite() && w > 0.0) {
                        return Err(Error::invalid(
                            key,
                            format!(
                                "the weight of `{name}` must be a positive number, got {}",
                                numeric::input(w)
                            ),
                        ));
                    }
                    Ok((named(&name)?, w))
                })
                .collect()
        }
    }
}

/// Points per variable of a verification grid: 0 (none) or at least 2, with steps^dims at most
/// `MAX_VERIFY_POINTS`.
fn verify_grid(key: &str, value: i64, dims: usize) -> Result<usize> {
    if value == 0 {
        return Ok(0);
    }
    if value < 2 {
        return Err(Error::invalid(
            key,
            format!("must be 0 (no verification) or at least 2, got {value}"),
        ));
    }
    let steps = value as usize;
    let points = u32::try_from(dims)
        .ok()
        .and_then(|d| steps.checked_pow(d))
        .unwrap_or(usize::MAX);
    if points > MAX_VERIFY_POINTS {
        return Err(Error::invalid(
            key,
            format!(
                "{steps} points per variable make {} grid points over {dims} variables; at most \
                 {MAX_VERIFY_POINTS} (the cap on the verification grid), or 0 for none",
                if points == usize::MAX {
                    "too many".to_string()
                } else {
                    points.to_string()
                }
            ),
        ));
    }
    Ok(steps)
}

/// A crown variable's bounds: a circular crowning to vary, a radius range of positive lengths,
/// a start range in [0, B/2) (the flat middle's half-length, as `modification.crowning`).
fn crown_bounds(
    key: &str,
    kind: VariableKind,
    (lo, hi): (f64, f64),
    crowning: Crowning,
    design: &Design,
) -> Result<()> {
    let Crowning::Circular { .. } = crowning else {
        let has = match crowning {
            Crowning::None => "has no crowning",
            _ => "has a logarithmic crowning",
        };
        return Err(Error::invalid(
            key,
            format!(
                "`{}` varies a circular crown, and the spec {has}: give \
                 `modification.crowning: {{kind: circular, radius_mm: ..., start_mm: ...}}` \
                 (its values are the study's start)",
                kind.key()
            ),
        ));
    };
    let half = 0.5 * design.face_width_mm;
    match kind {
        VariableKind::CrownRadius if lo <= 0.0 => Err(Error::invalid(
            key,
            format!(
                "the crown radius's bounds must be positive lengths, got [{}, {}]",
                numeric::input(lo),
                numeric::input(hi)
            ),
        )),
        VariableKind::CrownStart if lo < 0.0 || hi >= half => Err(Error::invalid(
            key,
            format!(
                "the flat middle's half-length must lie in [0, B/2) = [0, {} mm), got bounds \
                 [{}, {}]",
                numeric::input(half),
                numeric::input(lo),
                numeric::input(hi)
            ),
        )),
        _ => Ok(()),
    }
}

/// `constraints.objectives`: objective names with upper bounds (finite), in name order.
fn objective_limits(key: &str, raw: &BTreeMap<String, f64>) -> Result<Vec<(Objective, f64)>> {
    raw.iter()
        .map(|(name, &bound)| {
            let at = format!("{key}.{name}");
            Ok((find_objective(&at, name)?, finite(&at, bound)?))
        })
        .collect()
}

/// An objective read from the face loads needs a scene that resolves them (`face_slices` ≥ 2,
/// or a crown or tilt, which need slices).
fn face_objectives(key: &str, list: &[(Objective, f64)], scene: &Scene) -> Result<()> {
    match list
        .iter()
        .find(|(o, _)| o.quantity.key == quantity::MAX_FACE_LOAD_FACTOR.key)
    {
        Some((o, _)) if !scene.face.is_resolved() => Err(Error::invalid(
            key,
            format!(
                "`{}` is read from the line load along the face, and scene `{}` does not \
                 resolve it: give the scene `face_slices: 2` or more (and a misalignment or a \
                 crowning to study)",
                o.name, scene.name
            ),
        )),
        _ => Ok(()),
    }
}

fn study(
    key: &str,
    index: usize,
    raw: RawStudy,
    scenes: &[Scene],
    (modification, crowning, design): (&Modification, Crowning, &Design),
) -> Result<Study> {
    let scene = scene_index(scenes, &raw.scene, &format!("{key}.scene"))?;
    if let Some(m) = scenes[scene].torsion_refusal("a study") {
        return Err(Error::invalid(format!("{key}.scene"), m));
    }
    refuse_duty(scenes, scene, &format!("{key}.scene"), "a study")?;
    let mut variables = Vec::new();
    let v = &raw.variables;
    for (kind, b) in [
        (VariableKind::Shift, v.shift_mm),
        (VariableKind::Equidistant, v.equidistant_mm),
        (VariableKind::Rotation, v.rotation_deg),
        (VariableKind::CrownRadius, v.crown_radius_mm),
        (VariableKind::CrownStart, v.crown_start_mm),
    ] {
        if let Some(b) = b {
            let at = format!("{key}.variables.{}", kind.key());
            let (lo, hi) = bounds(&at, b)?;
            if kind.of_crown() {
                crown_bounds(&at, kind, (lo, hi), crowning, design)?;
            }
            let scale = if kind == VariableKind::Rotation {
                units::rad(1.0)
            } else {
                1.0
            };
            variables.push(Variable {
                kind,
                lower: lo * scale,
                upper: hi * scale,
            });
        }
    }
    if variables.is_empty() {
        return Err(Error::invalid(
            format!("{key}.variables"),
            "a study needs at least one variable (shift_mm, equidistant_mm, rotation_deg, \
             crown_radius_mm, crown_start_mm)"
                .into(),
        ));
    }
    let mut start = Point {
        modification: *modification,
        crowning,
    };
    if let Some(p) = raw.start {
        for (kind, value) in [
            (VariableKind::Shift, p.shift_mm),
            (VariableKind::Equidistant, p.equidistant_mm),
            (VariableKind::Rotation, p.rotation_deg.map(units::rad)),
            (VariableKind::CrownRadius, p.crown_radius_mm),
            (VariableKind::CrownStart, p.crown_start_mm),
        ] {
            if let Some(x) = value {
                let at = format!("{key}.start.{}", kind.key());
                if kind.of_crown() && !variables.iter().any(|v: &Variable| v.kind == kind) {
                    return Err(Error::invalid(
                        at,
                        format!(
                            "is the start of a variable the study does not vary: give \
                             `variables.{}` bounds, or set `modification.crowning` instead",
                            kind.key()
                        ),
                    ));
                }
                kind.set(&mut start, finite(&at, x)?);
            }
        }
    }
    for var in &variables {
        let x = var.kind.get(&start);
        if !(var.lower..=var.upper).contains(&x) {
            let unit = |x| var.kind.to_spec_unit(x);
            return Err(Error::invalid(
                format!("{key}.start"),
                format!(
                    "the start {} = {} lies outside its bounds [{}, {}] (give a start inside \
                     the bounds; the spec's modification is the start when none is given)",
                    var.kind.key(),
                    unit(x),
                    unit(var.lower),
                    unit(var.upper)
                ),
            ));
        }
    }
    let dims = variables.len();
    let c = &raw.constraints;
    let objective_limits =
        objective_limits(&format!("{key}.constraints.objectives"), &c.objectives)?;
    let objective = objective(&format!("{key}.objective"), raw.objective)?;
    face_objectives(&format!("{key}.objective"), &objective, &scenes[scene])?;
    face_objectives(
        &format!("{key}.constraints.objectives"),
        &objective_limits,
        &scenes[scene],
    )?;
    let tip_clearance_mm = c
        .tip_clearance_mm
        .map(|b| bounds(&format!("{key}.constraints.tip_clearance_mm"), b))
        .transpose()?;
    let min_clearance_mm = c
        .min_clearance_mm
        .map(|x| finite(&format!("{key}.constraints.min_clearance_mm"), x))
        .transpose()?;
    let max_lost_motion_arcsec = c
        .max_lost_motion_arcsec
        .map(|x| positive(&format!("{key}.constraints.max_lost_motion_arcsec"), x))
        .transpose()?;
    let mut references = Vec::new();
    for (j, r) in raw.references.into_iter().enumerate() {
        let at = format!("{key}.references[{j}]");
        let m = modification_at(&at, (r.shift_mm, r.equidistant_mm, r.rotation_deg))?;
        references.push((r.label, m));
    }
    // The global stage's interior and boundary points are points of one Sobol sequence.
    let sobol = |name: &str, value: Option<i64>, default: fn(usize) -> usize| {
        let why = "the length of the global stage's Sobol sequence";
        let value = value.unwrap_or(default(dims) as i64);
        count_capped(&format!("{key}.{name}"), value, 1, MAX_GLOBAL_SAMPLES, why)
    };
    Ok(Study {
        name: raw.name.unwrap_or_else(|| format!("study-{}", index + 1)),
        scene,
        objective,
        variables,
        start: start.modification,
        crowning: start.crowning,
        tip_clearance_mm,
        min_clearance_mm,
        max_lost_motion_arcsec,
        objective_limits,
        references,
        optimum_max_objective: raw
            .optimum_max_objective
            .map(|x| finite(&format!("{key}.optimum_max_objective"), x))
            .transpose()?,
        global_samples: sobol("global_samples", raw.global_samples, default_global_samples)?,
        boundary_samples: sobol(
            "boundary_samples",
            raw.boundary_samples,
            default_boundary_samples,
        )?,
        local_evaluations: count_capped(
            &format!("{key}.local_evaluations"),
            raw.local_evaluations.unwrap_or(200),
            10,
            MAX_LOCAL_EVALUATIONS,
            "the cap on one local run",
        )?,
        verify_grid: verify_grid(
            &format!("{key}.verify_grid"),
            raw.verify_grid.unwrap_or(default_verify_grid(dims) as i64),
            dims,
        )?,
    })
}
