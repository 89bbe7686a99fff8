//! What the design review draws of the load along the face width (MODEL.md "Along the face
//! width"): for each scene whose disc is tilted (by the scene's `misalignment`, by
//! `reducer.deviations.misalignment`, or both, added) or crowned, the line load of the most
//! loaded roller at one crank angle, as the scene runs it and, when tilted, as designed (the
//! same scene at that one angle without either tilt, run through the run path as any scene
//! is, `scene::run_design`, whose failure is the review's). The angle of a tilted
//! scene is its worst (its largest face load factor); that of a crowned, aligned scene the
//! angle of its largest line load (there the factor is largest on the lightest-loaded
//! roller, whose load matters least). mm, N/mm, rad.

use super::scene::{self, RunOptions};
use crate::contact::face_width::slice_centre_mm;
use crate::error::{Error, Result};
use crate::model::face::Misalignment;
use crate::model::place::{Place, Site};
use crate::model::quantity::{MAX_FACE_LOAD_FACTOR, MAX_LINE_LOAD};
use crate::model::results::{FaceLoads, SceneResult};
use crate::model::{Plan, Scene};
use crate::spec::Spec;

/// Which crank angle a profile shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceAngle {
    /// The angle of the scene's largest face load factor (a tilted scene).
    WorstFactor,
    /// The angle of the scene's largest line load (a crowned, aligned scene).
    LargestLineLoad,
}

/// One roller's line load along the face at one crank angle, tilted and as designed.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceProfile {
    /// The scene's index in the spec.
    pub scene: usize,
    pub crank_rad: f64,
    /// Why this angle.
    pub angle: FaceAngle,
    pub roller: usize,
    /// The slice centres z_s, mm from the middle of the face.
    pub z_mm: Vec<f64>,
    /// The line loads of the scene as run (tilted), N/mm.
    pub tilted_n_per_mm: Vec<f64>,
    /// The line loads of the same scene and angle without the tilt, N/mm (none for an aligned
    /// scene: the review then draws the tilted curve alone).
    pub designed_n_per_mm: Option<Vec<f64>>,
}

/// The profiles of every tilted or crowned one-disc scene that resolves the face (several
/// discs: none, their curves are per disc).
pub fn face_profiles(spec: &Spec, results: &[SceneResult]) -> Result<Vec<FaceProfile>> {
    let mut out = Vec::new();
    for (index, (s, r)) in spec.scenes.iter().zip(results).enumerate() {
        // The tilt as run: the scene's plus the one as built (`reducer.deviations`).
        let tilted = crate::model::period::tilted(&spec.design, &s.face);
        if !tilted && s.face.crowning.is_none() {
            continue;
        }
        let Some(disc) = r.only_disc() else {
            continue;
        };
        let Some(face) = disc.loaded.rollers.as_ref().and_then(|c| c.face.as_ref()) else {
            continue;
        };
        let picked = if tilted {
            worst_factor(r, face).map(|p| (FaceAngle::WorstFactor, p))
        } else {
            largest_line_load(r).map(|p| (FaceAngle::LargestLineLoad, p))
        };
        let Some((angle, (k, roller))) = picked else {
            continue;
        };
        let crank_rad = s.crank_rad[k];
        out.push(FaceProfile {
            scene: index,
            crank_rad,
            angle,
            roller,
            z_mm: (0..s.face.slices)
                .map(|j| slice_centre_mm(spec.design.face_width_mm, s.face.slices, j))
                .collect(),
            tilted_n_per_mm: face.at(roller, k).to_vec(),
            designed_n_per_mm: match tilted {
                true => Some(designed_line_loads(spec, s, crank_rad, roller)?),
                false => None,
            },
        });
    }
    Ok(out)
}

/// The angle of the largest face load factor, where the registry found it
/// (`max_face_load_factor`'s place: its first angle on a tie), and the roller carrying the
/// peak line load there in the recorded loads.
fn worst_factor(r: &SceneResult, face: &FaceLoads) -> Option<(usize, usize)> {
    let k = match MAX_FACE_LOAD_FACTOR.scalar(r)?.at {
        Place {
            bin: None,
            disc: None,
            site: Site::Crank(crank),
        } => crank.index,
        _ => return None,
    };
    let peak = |i: usize| face.at(i, k).iter().copied().fold(0.0, f64::max);
    let rollers = 0..face.line_load_n_per_mm.len();
    let roller = rollers.max_by(|&a, &b| peak(a).total_cmp(&peak(b)))?;
    Some((k, roller))
}

/// The angle and roller of the largest line load, where the registry found it
/// (`max_line_load_n_per_mm`'s place). Read from a scene whose own run resolves the face, so
/// that the place is of that run (not a bin's, nor a disc's).
fn largest_line_load(r: &SceneResult) -> Option<(usize, usize)> {
    match MAX_LINE_LOAD.scalar(r)?.at {
        Place {
            bin: None,
            disc: None,
            site: Site::Slice { at, .. },
        } => Some((at.crank.index, at.index)),
        _ => None,
    }
}

/// Roller `roller`'s line loads in `scene` as designed at `crank_rad`, N/mm: neither the
/// scene's tilt nor the one as built, the scene's loaded effects run at that one angle (no duty
/// cycle: the scene's own torque) through the run path (`scene::run_design`, with the spec's
/// options), read from what its sweep recorded.
fn designed_line_loads(
    spec: &Spec,
    scene: &Scene,
    crank_rad: f64,
    roller: usize,
) -> Result<Vec<f64>> {
    let mut design = spec.design.clone();
    design.deviations.misalignment = Misalignment::default();
    let at = Scene {
        crank_rad: vec![crank_rad],
        face: crate::model::Face {
            misalignment: Misalignment::default(),
            ..scene.face
        },
        effects: scene
            .effects
            .iter()
            .copied()
            .filter(|e| e.is_loaded())
            .collect(),
        duty_cycle: None,
        ..scene.clone()
    };
    let plan = Plan::for_scene(&at);
    let options = RunOptions::for_spec(spec);
    let r = scene::run_design(&design, &spec.modification, (&at, &plan), &options)
        .map_err(|e| scene::at_scene(spec, scene, e))?;
    let face = (r.discs.first())
        .and_then(|d| d.loaded.rollers.as_ref())
        .and_then(|c| c.face.as_ref());
    face.filter(|f| roller < f.line_load_n_per_mm.len())
        .map(|f| f.at(roller, 0).to_vec())
        .ok_or_else(|| {
            Error::computation(format!(
                "scene `{}`: the load along the face without the tilt: no line loads of roller \
                 {roller} recorded",
                scene.name
            ))
        })
}
