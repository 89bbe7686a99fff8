//! What the design review draws of the load along the face width (MODEL.md "Along the face
//! width"): for each scene whose disc is tilted (by the scene's `misalignment`, by
//! `reducer.deviations.misalignment`, or both, added), the line load of the most loaded roller at the
//! scene's worst crank angle (its largest face load factor), tilted as the scene runs it and as
//! designed (the same scene and angle without either tilt, solved by the same model).
//! mm, N/mm, rad.

use super::scene;
use crate::contact::face_width::slice_centre_mm;
use crate::equilibrium::angle::solve_angle;
use crate::equilibrium::loaded::AngleSolution;
use crate::equilibrium::solve::Settings;
use crate::error::Result;
use crate::model::face::Misalignment;
use crate::model::results::SceneResult;
use crate::model::{Design, Plan, Scene};
use crate::spec::Spec;

/// One roller's line load along the face at one crank angle, tilted and as designed.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceProfile {
    /// The scene's index in the spec.
    pub scene: usize,
    pub crank_rad: f64,
    pub roller: usize,
    /// The slice centres z_s, mm from the middle of the face.
    pub z_mm: Vec<f64>,
    /// The line loads of the scene as run (tilted), N/mm.
    pub tilted_n_per_mm: Vec<f64>,
    /// The line loads of the same scene and angle without the tilt, N/mm (none when the solve
    /// without it fails: the review then draws the tilted curve alone).
    pub designed_n_per_mm: Option<Vec<f64>>,
}

/// The profiles of every tilted one-disc scene that resolves the face (several discs: none,
/// their curves are per disc).
pub fn face_profiles(spec: &Spec, results: &[SceneResult]) -> Result<Vec<FaceProfile>> {
    let mut out = Vec::new();
    for (index, (s, r)) in spec.scenes.iter().zip(results).enumerate() {
        // The tilt as run: the scene's plus the one as built (`reducer.deviations`).
        if spec.design.deviations.face(&s.face).misalignment.is_zero() || !r.discs.is_empty() {
            continue;
        }
        let Some(face) = r.loaded.rollers.as_ref().and_then(|c| c.face.as_ref()) else {
            continue;
        };
        let Some((k, _)) = face
            .face_load_factor
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
        else {
            continue;
        };
        // The roller that carries the peak line load at that angle.
        let peak = |i: usize| face.at(i, k).iter().copied().fold(0.0, f64::max);
        let Some(roller) =
            (0..face.line_load_n_per_mm.len()).max_by(|&a, &b| peak(a).total_cmp(&peak(b)))
        else {
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
            roller,
            z_mm: (0..s.face.slices)
                .map(|j| slice_centre_mm(spec.design.face_width_mm, s.face.slices, j))
                .collect(),
            tilted_n_per_mm: face.at(roller, k).to_vec(),
            designed_n_per_mm: line_loads_at(spec, &untilted, &designed, crank_rad, roller),
        });
    }
    Ok(out)
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
