//! Is a scene's own crank resolution fine enough for the tolerances of its spec's accuracy
//! ladder? `check` asks this of the ladder's scene whenever the spec has an `accuracy:`
//! section, so that a run never passes while its own accuracy table calls it too coarse.
//!
//! The steps rungs of the ladder (12, 24, … crank steps per mesh period, nested in the finest,
//! [`engine::accuracy`](crate::engine::accuracy)) are compared with the reference at the finest. The scene is
//! **unresolved** when the coarsest rung already misses a tolerance (so resolution matters at
//! all) and the scene's steps per mesh period are fewer than those of the coarsest rung from
//! which on every steps rung meets the tolerances (the reference's, when none coarser does).
//! Without the full ladder (`check` without `--report`), the reference and the steps rungs up
//! to the first one that decides are run, untimed.

use super::accuracy::{self, Ladder, LadderQuantity, LadderTolerances, Layout, Outputs};
use crate::engine::scene;
use crate::error::Result;
use crate::model::Plan;
use crate::spec::Spec;

/// A steps rung of the ladder and the tolerances it misses.
#[derive(Debug, Clone, PartialEq)]
pub struct StepsRung {
    /// Crank steps per mesh period.
    pub steps: usize,
    /// (quantity, |rung − reference| in its unit) of every quantity over its tolerance.
    pub misses: Vec<(LadderQuantity, f64)>,
}

/// The verdict on a scene's crank resolution.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolution {
    pub scene: String,
    /// The scene's crank steps per mesh period (its crank angles over the periods its range
    /// covers; need not be 12·2^k).
    pub scene_steps: f64,
    /// Steps per mesh period of the reference.
    pub finest: usize,
    pub tolerances: LadderTolerances,
    /// The steps rungs compared, coarse to fine (the reference left out).
    pub rungs: Vec<StepsRung>,
}

impl Resolution {
    /// The verdict on the scene of `layout` (its own crank angles, the ladder's finest steps
    /// and tolerances) from the steps rungs `rungs`.
    fn of(layout: &Layout, rungs: Vec<StepsRung>) -> Resolution {
        Resolution {
            scene: layout.scene.clone(),
            scene_steps: layout.steps_per_period(layout.angles_own),
            finest: layout.finest,
            tolerances: layout.tolerances,
            rungs,
        }
    }

    /// Steps per mesh period from which on every steps rung meets the tolerances (the finest
    /// when the rung below it misses).
    pub fn needed_steps(&self) -> usize {
        (self.rungs.iter().rev())
            .take_while(|r| r.misses.is_empty())
            .last()
            .map_or(self.finest, |r| r.steps)
    }

    /// Fine enough: the coarsest rung meets every tolerance, or the scene is at least as fine
    /// as `needed_steps`.
    pub fn resolved(&self) -> bool {
        self.rungs.first().is_none_or(|r| r.misses.is_empty())
            || self.scene_steps >= self.needed_steps() as f64
    }

    /// The finest rung at most as fine as the scene (else the coarsest), with what it misses:
    /// the evidence that the scene is too coarse.
    pub fn evidence(&self) -> Option<&StepsRung> {
        self.rungs
            .iter()
            .rev()
            .find(|r| r.steps as f64 <= self.scene_steps && !r.misses.is_empty())
            .or_else(|| self.rungs.iter().find(|r| !r.misses.is_empty()))
    }
}

/// The resolution verdict from a ladder already run (the design review's).
pub fn of_ladder(ladder: &Ladder) -> Resolution {
    let rungs = ladder
        .steps_rungs()
        .filter(|r| !r.is_reference)
        .map(|r| StepsRung {
            steps: r.steps_per_period.round() as usize,
            misses: accuracy::misses(&r.errors, &ladder.layout.tolerances),
        })
        .collect();
    Resolution::of(&ladder.layout, rungs)
}

/// The resolution verdict of the spec's accuracy scene, running the reference and the steps
/// rungs from the coarsest up to the first that meets every tolerance at or above the scene's
/// resolution.
pub fn run(spec: &Spec, scene_index: usize, options: &accuracy::Options) -> Result<Resolution> {
    let scene = &spec.scenes[scene_index];
    let layout = accuracy::layout(spec, scene, options);
    let outputs = |steps: usize| -> Result<Outputs> {
        let mut s = scene.clone();
        s.crank_rad = layout.crank_rad(steps);
        Ok(Outputs::of(
            &scene::run(spec, &s, &Plan::for_scene(&s), &Default::default())?,
            layout.face,
        ))
    };
    let reference = outputs(options.finest)?;
    let mut resolution = Resolution::of(&layout, Vec::new());
    let mut steps = accuracy::COARSEST;
    while steps < options.finest {
        let rung = rung(&layout, &reference, steps, outputs(steps)?);
        let met = rung.misses.is_empty();
        resolution.rungs.push(rung);
        // A rung that meets decides when it is the coarsest (resolution does not matter) or
        // at least as fine as the scene; one that misses never does: the rung that meets
        // above it is the resolution the warning names.
        if met && (steps == accuracy::COARSEST || steps as f64 >= resolution.scene_steps) {
            break;
        }
        steps *= 2;
    }
    Ok(resolution)
}

fn rung(layout: &Layout, reference: &Outputs, steps: usize, outputs: Outputs) -> StepsRung {
    let ratio = layout.angles(layout.finest) / layout.angles(steps);
    let (errors, _) = accuracy::errors(reference, &outputs, ratio, layout.periodic);
    StepsRung {
        steps,
        misses: accuracy::misses(&errors, &layout.tolerances),
    }
}
