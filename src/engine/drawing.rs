//! What the design review draws of the disc at one crank angle φ, computed here so that the
//! drawing shows what `check` computed and the report only draws:
//!
//! - the disc in its pose of MODEL.md: centre e·(cos φ, sin φ) + u, turned by ψ = −φ/nc + β,
//!   with β (and u, βo) those of the first scene with roller contact at φ, solved by the same
//!   model as that scene's sweep (`scene::loaded_model`), else the ideal pose;
//! - its profile as a polyline, its holes, the pins at the output lag βo, the rollers;
//! - the forces on the disc at φ in that scene: each loaded roller at its contact point, each
//!   loaded pin at its contact on the hole wall, the crank bearing at the disc centre;
//! - the roller with the smallest gap at φ at the ideal (unloaded) pose, the exact gap of the
//!   clearance sweep, and the geometry of a true-scale close-up of that gap.
//!
//! Fixed frame, mm, N, rad.

use super::scene;
use crate::equilibrium::angle::solve_angle;
use crate::equilibrium::discs::{solve_coupled, CoupledWork, Discs};
use crate::equilibrium::loaded::AngleSolution;
use crate::equilibrium::solve::Settings;
use crate::error::{Error, Result};
use crate::geometry::clearance::{Mesh, Pose, RollerGap};
use crate::geometry::{polyline, rotate, unit, Vec2};
use crate::model::results::SceneResult;
use crate::model::Plan;
use crate::spec::Spec;
use std::f64::consts::{FRAC_PI_2, TAU};

/// The disc, rollers and pins at one crank angle, with the forces of the first loaded scene
/// and the tightest roller.
#[derive(Debug, Clone, PartialEq)]
pub struct Disc {
    pub crank_rad: f64,
    /// Disc centre O_c, fixed frame.
    pub centre: Vec2,
    /// ψ = −φ/nc + β.
    pub rotation_rad: f64,
    /// The modified profile at this pose, a closed polyline (the closing chord implied).
    pub profile: Vec<Vec2>,
    /// Centres of the output-pin holes, in the disc, at this pose.
    pub holes: Vec<Vec2>,
    pub hole_radius_mm: f64,
    /// Centres of the output pins, at the output lag βo.
    pub pins: Vec<Vec2>,
    pub pin_radius_mm: f64,
    /// Centres of the rollers (fixed in the housing).
    pub rollers: Vec<Vec2>,
    pub roller_radius_mm: f64,
    pub roller_circle_radius_mm: f64,
    /// The loaded equilibrium at φ, when a scene computes roller contact.
    pub loaded: Option<Loaded>,
    /// The roller with the smallest gap at φ (ideal pose), and its close-up.
    pub tightest: CloseUp,
}

/// The equilibrium of the first loaded scene at the drawing's crank angle.
#[derive(Debug, Clone, PartialEq)]
pub struct Loaded {
    pub scene: String,
    /// The disc shown, with several discs (disc 0, at crank phase 0).
    pub disc: Option<usize>,
    /// β.
    pub lag_rad: f64,
    /// βo (0 when the pins are not modelled).
    pub output_lag_rad: f64,
    /// Every force on the disc that is not zero.
    pub forces: Vec<Force>,
}

/// What a force acts from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    Roller(usize),
    Pin(usize),
    Bearing,
}

/// A force on the disc and where it acts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Force {
    pub part: Part,
    /// The contact point (rollers, pins) or the disc centre (bearing).
    pub point: Vec2,
    pub force_n: Vec2,
}

/// A roller's gap seen close up: a local frame with the closest point of the profile at the
/// origin and the profile's outward normal along +y, at the ideal pose.
#[derive(Debug, Clone, PartialEq)]
pub struct CloseUp {
    pub roller: usize,
    /// Signed normal gap (negative: interference).
    pub gap_mm: f64,
    /// Position on the tooth: 0 root, 0.5 tip.
    pub tooth_phase: f64,
    /// The disc's flank within `FLANK_MM` (along the profile, at least) of the contact.
    pub flank: Vec<Vec2>,
    /// The roller's centre.
    pub roller_centre: Vec2,
    pub roller_radius_mm: f64,
}

/// How far along the profile the close-up's flank reaches on each side of the contact, mm:
/// past the widest close-up the report draws (3 mm across).
pub const FLANK_MM: f64 = 3.0;

/// Points of the close-up's flank.
const FLANK_POINTS: usize = 1201;

/// The crank angle the drawing uses by default: where the smallest gap of the first one-disc
/// scene that computes clearance occurs, else 0.
pub fn default_crank_rad(results: &[SceneResult]) -> f64 {
    results
        .iter()
        .find_map(|r| r.only_disc()?.clearance.as_ref())
        .map_or(0.0, |c| c.min.crank_rad)
}

/// The drawing at `crank_rad`: the pose, forces and tightest roller as the module says.
/// The profile's chords stay within (Rp + Rrp)/2000 of the curve: a sixth of a pixel on a
/// drawing of the whole disc 600 pixels across.
pub fn disc(spec: &Spec, crank_rad: f64) -> Result<Disc> {
    let d = &spec.design;
    let mesh = Mesh::new(d, &spec.modification);
    let loaded = loaded_at(spec, crank_rad)?;
    let pose = match &loaded {
        Some((_, sol)) => Pose::new(crank_rad, sol.lag_rad.unwrap_or(0.0), sol.centre_offset_mm),
        None => Pose::ideal(crank_rad),
    };
    let centre = mesh.disc_centre(&pose);
    let psi = mesh.disc_rotation(&pose);
    let (s, c) = psi.sin_cos();
    let tolerance = (d.roller_circle_radius_mm + d.roller_radius_mm) / 2000.0;
    let profile = polyline::polyline(&mesh.profile, tolerance)
        .iter()
        .map(|p| centre + rotate(p.point, c, s))
        .collect();
    let on_pin_circle = |angle: f64| unit(angle) * d.pins.circle_radius_mm;
    let m = d.pins.count;
    let gamma = |j: usize| TAU * j as f64 / m as f64 + psi;
    let output_lag = loaded
        .as_ref()
        .and_then(|(_, sol)| sol.output_lag_rad)
        .unwrap_or(0.0);
    Ok(Disc {
        crank_rad,
        centre,
        rotation_rad: psi,
        profile,
        holes: (0..m).map(|j| centre + on_pin_circle(gamma(j))).collect(),
        hole_radius_mm: d.hole_radius_mm(),
        pins: (0..m)
            .map(|j| on_pin_circle(gamma(j) + output_lag))
            .collect(),
        pin_radius_mm: d.pins.pin_radius_mm,
        rollers: (0..d.rollers).map(|i| mesh.roller_centre(i)).collect(),
        roller_radius_mm: d.roller_radius_mm,
        roller_circle_radius_mm: d.roller_circle_radius_mm,
        loaded: loaded.map(|((scene, disc), sol)| Loaded {
            scene,
            disc,
            lag_rad: pose.lag_rad,
            output_lag_rad: output_lag,
            forces: forces(&sol, centre),
        }),
        tightest: close_up(&mesh, crank_rad)?,
    })
}

/// ((scene name, the disc shown with several discs), its solution at the crank angle).
type LoadedAt = ((String, Option<usize>), AngleSolution);

/// The first scene with roller contact (not a duty cycle's, which has no one torque), solved
/// at `crank_rad`.
fn loaded_at(spec: &Spec, crank_rad: f64) -> Result<Option<LoadedAt>> {
    let Some(scene) = spec.scenes.iter().find(|s| s.loaded_once()) else {
        return Ok(None);
    };
    let plan = Plan::for_scene(scene);
    let model = scene::loaded_model(
        &spec.design,
        &spec.modification,
        scene,
        &plan,
        &Settings::default(),
    );
    let failed = |f| scene::solve_failed(scene, crank_rad, &f);
    if spec.design.discs == 1 {
        let sol = solve_angle(&model, crank_rad, &AngleSolution::default()).map_err(failed)?;
        return Ok(Some(((scene.name.clone(), None), sol)));
    }
    // Several discs: disc 0 (at crank phase 0) with its share of the torque, from the coupled
    // balance the sweep solves, every roller evaluated exactly.
    let discs = Discs::new(&model, spec.design.discs);
    let mut work = CoupledWork::new(&discs);
    work.works.iter_mut().for_each(|w| w.exact_final = true);
    solve_coupled(&discs, crank_rad, &mut work).map_err(failed)?;
    let sol = work.works.swap_remove(0).sol;
    Ok(Some(((scene.name.clone(), Some(0)), sol)))
}

/// The forces on the disc that are not zero: rollers, pins, bearing.
fn forces(sol: &AngleSolution, centre: Vec2) -> Vec<Force> {
    let rollers = sol.rollers.iter().enumerate().map(|(i, r)| Force {
        part: Part::Roller(i),
        point: r.point,
        force_n: r.force_vector(),
    });
    let pins = sol.pins.iter().enumerate().map(|(j, p)| Force {
        part: Part::Pin(j),
        point: p.point,
        force_n: p.force_vector(),
    });
    let bearing = sol.bearing_force_n.map(|f| Force {
        part: Part::Bearing,
        point: centre,
        force_n: f,
    });
    rollers
        .chain(pins)
        .chain(bearing)
        .filter(|f| f.force_n.norm() > 0.0)
        .collect()
}

/// The roller with the smallest gap at the ideal pose at `crank_rad`, and its close-up.
fn close_up(mesh: &Mesh, crank_rad: f64) -> Result<CloseUp> {
    let pose = Pose::ideal(crank_rad);
    let mut tightest: Option<(usize, RollerGap)> = None;
    for i in 0..mesh.rollers {
        let g = mesh
            .roller_gap(i, &pose, None)
            .map_err(|f| Error::computation(format!("the disc drawing: {f}")))?;
        if tightest.as_ref().is_none_or(|(_, t)| g.gap_mm < t.gap_mm) {
            tightest = Some((i, g));
        }
    }
    let (i, g) = tightest.ok_or_else(|| Error::computation("the disc drawing: no rollers"))?;
    // Turn the disc frame so that the contact normal points up.
    let turn = g.normal.y.atan2(g.normal.x) - FRAC_PI_2;
    let (s, c) = (-turn).sin_cos();
    let local = |p: Vec2| rotate(p - g.point, c, s);
    let speed = mesh.profile.tangent(g.t).norm().max(1e-9);
    // Twice the parameter span of FLANK_MM at the contact's speed: the speed varies along it.
    let span = 2.0 * FLANK_MM / speed;
    let step = 2.0 * span / (FLANK_POINTS - 1) as f64;
    let tooth = TAU / mesh.teeth as f64;
    Ok(CloseUp {
        roller: i,
        gap_mm: g.gap_mm,
        tooth_phase: g.t.rem_euclid(tooth) / tooth,
        flank: (0..FLANK_POINTS)
            .map(|k| local(mesh.profile.point(g.t - span + step * k as f64)))
            .collect(),
        roller_centre: local(mesh.roller_in_disc(i, &pose)),
        roller_radius_mm: mesh.roller_radius(i),
    })
}
