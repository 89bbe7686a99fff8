//! What the design review draws of the load along the face width (MODEL.md "Along the face
//! width"): for each scene whose disc is tilted (by the scene's `misalignment`, by
//! `reducer.deviations.misalignment`, or both, added) or crowned, the line load of the most
//! loaded roller at one crank angle, as the scene runs it and, when tilted, as designed (the
//! same scene and angle without either tilt, solved by the same model). The angle of a tilted
//! scene is its worst (its largest face load factor); that of a crowned, aligned scene the
//! angle of its largest line load (there the factor is largest on the lightest-loaded
//! roller, whose load matters least). mm, N/mm, rad.

use super::scene;
use crate::contact::face_width::slice_centre_mm;
use crate::equilibrium::angle::solve_angle;
use crate::equilibrium::loaded::AngleSolution;
use crate::equilibrium::solve::Settings;
use crate::error::Result;
use crate::model::face::Misalignment;
use crate::model::results::{FaceLoads, SceneResult};
use crate::model::{Design, Plan, Scene};
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
    /// scene, or when the solve without the tilt fails: the review then draws the tilted curve
    /// alone).
    pub designed_n_per_mm: Option<Vec<f64>>,
}

/// The profiles of every tilted or crowned one-disc scene that resolves the face (several
/// discs: none, their curves are per disc).
pub fn face_profiles(spec: &Spec, results: &[SceneResult]) -> Result<Vec<FaceProfile>> {
    let mut out = Vec::new();
    for (index, (s, r)) in spec.scenes.iter().zip(results).enumerate() {
        // The tilt as run: the scene's plus the one as built (`reducer.deviations`).
        let tilted = !spec.design.deviations.face(&s.face).misalignment.is_zero();
        if (!tilted && s.face.crowning.is_none()) || !r.discs.is_empty() {
            continue;
        }
        let Some(face) = r.loaded.rollers.as_ref().and_then(|c| c.face.as_ref()) else {
            continue;
        };
        let picked = if tilted {
            worst_factor(face).map(|p| (FaceAngle::WorstFactor, p))
        } else {
            largest_line_load(face).map(|p| (FaceAngle::LargestLineLoad, p))
        };
        let Some((angle, (k, roller))) = picked else {
            continue;
        };
        let crank_rad = s.crank_rad[k];
        // Designed: neither the scene's tilt nor the one as built.
        let mut untilted = spec.design.clone();
        untilted.deviations.misalignment = Misalignment::default();
        let designed = Scene {
            face: crate::model::Face {
                misalignment: Misalignment::default(),
                ..s.face
            },
            ..s.clone()
        };
        out.push(FaceProfile {
            scene: index,
            crank_rad,
            angle,
            roller,
            z_mm: (0..s.face.slices)
                .map(|j| slice_centre_mm(spec.design.face_width_mm, s.face.slices, j))
                .collect(),
            tilted_n_per_mm: face.at(roller, k).to_vec(),
            designed_n_per_mm: tilted
                .then(|| line_loads_at(spec, &untilted, &designed, crank_rad, roller))
                .flatten(),
        });
    }
    Ok(out)
}

/// The angle of the largest face load factor and the roller carrying the peak line load there.
fn worst_factor(face: &FaceLoads) -> Option<(usize, usize)> {
    let factors = face.face_load_factor.iter().enumerate();
    let (k, _) = factors.max_by(|a, b| a.1.total_cmp(b.1))?;
    let peak = |i: usize| face.at(i, k).iter().copied().fold(0.0, f64::max);
    let rollers = 0..face.line_load_n_per_mm.len();
    let roller = rollers.max_by(|&a, &b| peak(a).total_cmp(&peak(b)))?;
    Some((k, roller))
}

/// The angle and roller of the largest line load (`max_line_load_n_per_mm`'s).
fn largest_line_load(face: &FaceLoads) -> Option<(usize, usize)> {
    face.face_load_factor.first()?;
    let (_, roller, k, _) = face.peak_line_load();
    Some((k, roller))
}

/// Roller `roller`'s line loads in `scene` at `crank_rad`, solved as the scene's sweep is.
fn line_loads_at(
    spec: &Spec,
    design: &Design,
    scene: &Scene,
    crank_rad: f64,
    roller: usize,
) -> Option<Vec<f64>> {
    let plan = Plan::for_scene(scene);
    let model = scene::loaded_model(
        design,
        &spec.modification,
        scene,
        &plan,
        &Settings::default(),
    );
    let sol = solve_angle(&model, crank_rad, &AngleSolution::default()).ok()?;
    let rollers = model.rollers.as_ref()?;
    let mut q = vec![0.0; rollers.slices()];
    rollers.line_loads(sol.rollers.get(roller)?, &mut q);
    Some(q)
}
