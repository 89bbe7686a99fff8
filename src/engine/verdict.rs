//! Limits → checks → verdicts. A limit applies to every scene that computes its quantity.

use super::limit::{excess, passes};
use crate::error::{Error, Result};
pub use crate::model::quantity::Bound;

use super::summary::SceneSummary;
use crate::model::Plan;
use crate::model::{Limit, Limits};
use crate::spec::Spec;

/// What a check compares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CheckKind {
    /// A `limits` entry: the value is the scene's extreme of the quantity.
    Limit,
    /// A `golden` entry: the value is the worst |deviation| from the golden curve, the limit
    /// the tolerance band at that point.
    Golden,
}

/// One evaluated limit (or golden curve) in one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// `scene/limit_key`, or `scene/golden:quantity`.
    pub id: String,
    pub kind: CheckKind,
    pub value: f64,
    pub limit: f64,
    /// Unit of value and limit ("" when dimensionless).
    pub unit: &'static str,
    pub bound: Bound,
    pub passed: bool,
    /// Where the value occurs or what it rests on, as data (`report::table::evidence` puts it
    /// in words).
    pub at: Evidence,
}

/// Where a check's value occurs, or what it rests on.
#[derive(Debug, Clone, PartialEq)]
pub enum Evidence {
    /// Where the registry's extreme occurs (`Extreme::at`: roller 3 at crank angle 12).
    Place(crate::model::place::Place),
    /// A golden curve's worst point: where, the golden and the current value, the golden file.
    Golden {
        worst: crate::engine::golden::Point,
        path: std::path::PathBuf,
    },
    /// An optimum's tightest constraint, by name; `None` without constraints.
    Tightest(Option<String>),
    /// An optimum's variables: each key and its value in the spec's unit.
    Optimum(Vec<(&'static str, f64)>),
    /// The accuracy scene's crank resolution.
    Resolution(Box<crate::engine::resolution::Resolution>),
    /// A tolerance study: samples that fail some limit, of how many, and the Clopper–Pearson
    /// interval of the failure rate at `confidence`; `measured` when the spec has a measured
    /// disc (the study still draws from the drawing).
    FailureRate {
        failures: u64,
        samples: u64,
        confidence: f64,
        interval: (f64, f64),
        measured: bool,
        /// The limit on the rate, for a rate within it that the samples cannot show.
        max_failure_rate: f64,
    },
}

impl Check {
    /// The scene part of the id.
    pub fn scene(&self) -> &str {
        self.id.split_once('/').map_or("", |(s, _)| s)
    }

    /// The check part of the id (limit key or `golden:quantity`).
    pub fn name(&self) -> &str {
        self.id.split_once('/').map_or(&self.id, |(_, n)| n)
    }

    /// How far beyond the limit the value lies, relative to |limit| (to 1 when the limit is 0):
    /// positive outside, negative inside. Sorts failures worst first.
    pub fn excess(&self) -> f64 {
        excess(self.value, self.limit, self.bound)
    }

    /// The check of a golden comparison.
    pub fn from_golden(g: &crate::engine::golden::GoldenResult) -> Check {
        let w = &g.comparison.worst;
        Check {
            id: format!(
                "{}/golden:{}{}",
                g.golden.scene,
                g.golden.quantity.key,
                g.golden.disc_suffix()
            ),
            kind: CheckKind::Golden,
            value: w.deviation,
            limit: w.band,
            unit: g.golden.quantity.unit,
            bound: Bound::Max,
            passed: g.comparison.passed,
            at: Evidence::Golden {
                worst: w.clone(),
                path: g.golden.path.clone(),
            },
        }
    }
}

/// The limits that a scene with this plan evaluates, in their order.
pub fn limits_for<'a>(limits: &'a Limits, plan: &Plan) -> Vec<&'a Limit> {
    limits
        .entries
        .iter()
        .filter(|l| plan.computes_quantity(l.def.quantity))
        .collect()
}

/// Evaluate the spec's limits on the summaries of its scenes (`engine::summary`: each scene's
/// registry scalars, computed once). A limit applies to every scene whose plan computes its
/// quantity; a value missing from such a scene is an error, never a skipped check (a planning
/// fault must not pass a limit silently).
pub fn evaluate(spec: &Spec, summaries: &[SceneSummary]) -> Result<Vec<Check>> {
    let mut checks = Vec::new();
    for r in summaries {
        let scene = spec.scenes.iter().find(|s| s.name == r.scene);
        let plan = scene.map(Plan::for_scene);
        // The quantities along the face width are those of a scene that resolves the face.
        let face = scene.is_some_and(|s| spec.design.deviations.face(&s.face).is_resolved());
        for l in &spec.limits.entries {
            let q = l.def.quantity;
            if plan.as_ref().is_some_and(|p| !p.computes_quantity(q)) {
                continue;
            }
            let Some(e) = r.scalar(q) else {
                let expected = face || !crate::model::quantity::NEEDS_FACE.contains(&q);
                if expected && plan.is_some() {
                    return Err(Error::computation(format!(
                        "scene `{}` computes `{}` but its {} is missing: no check of `limits.{}` \
                         can pass without it",
                        r.scene,
                        q.effect.name(),
                        q.label,
                        l.def.key
                    )));
                }
                continue;
            };
            checks.push(Check {
                id: format!("{}/{}", r.scene, l.def.key),
                kind: CheckKind::Limit,
                unit: q.unit,
                value: e.value,
                limit: l.value,
                bound: l.def.bound,
                passed: passes(e.value, l.value, l.def.bound),
                at: Evidence::Place(e.at.clone()),
            });
        }
    }
    Ok(checks)
}

/// Checks on optimisation studies: the optimum satisfies every constraint (value: the smallest
/// margin, ≥ 0), and, when a limit is set, its objective is within `optimum_max_objective`.
pub fn optimisation(spec: &Spec, results: &[crate::engine::optimise::StudyResult]) -> Vec<Check> {
    let mut checks = Vec::new();
    for (study, r) in spec.studies.iter().zip(results) {
        let o = &r.optimum;
        // The tightest constraint relative to its bound; its margin in its own unit.
        let tightest = o.tightest();
        let at = Evidence::Tightest(tightest.map(|m| m.name.clone()));
        checks.push(Check {
            kind: CheckKind::Limit,
            unit: tightest.map_or("mm", |m| m.unit),
            id: format!("optimise/{}/constraints", r.name),
            // No margin when the optimum's evaluation failed: the most negative finite value
            // (the JSON carries only finite numbers), and the check fails with it.
            value: if o.failure.is_some() {
                f64::MIN
            } else {
                tightest.map_or(f64::MAX, |m| m.margin())
            },
            limit: 0.0,
            bound: Bound::Min,
            passed: o.feasible(),
            at,
        });
        if let Some(limit) = study
            .optimum_max_objective
            .or(spec.limits.optimum_max_objective)
        {
            let unit = match study.objective.as_slice() {
                [(o, _)] => o.quantity.unit,
                _ => "",
            };
            checks.push(Check {
                kind: CheckKind::Limit,
                unit,
                id: format!("optimise/{}/objective", r.name),
                value: o.objective,
                limit,
                bound: Bound::Max,
                passed: passes(o.objective, limit, Bound::Max),
                at: Evidence::Optimum(
                    (study.variables.iter())
                        .map(|v| (v.kind.key(), v.kind.spec_value(&o.point)))
                        .collect(),
                ),
            });
        }
    }
    checks
}

/// The check of `limits.accuracy_resolved: true`: the accuracy scene's crank steps per mesh
/// period (value) against the steps its ladder needs to meet the tolerances (limit).
pub fn resolution(r: &crate::engine::resolution::Resolution) -> Check {
    let needed = r.needed_steps() as f64;
    Check {
        id: format!("{}/accuracy_resolved", r.scene),
        kind: CheckKind::Limit,
        value: r.scene_steps,
        // Resolved also when the coarsest rung meets every tolerance: the bound is then that rung.
        limit: if r.resolved() {
            needed.min(r.scene_steps)
        } else {
            needed
        },
        unit: "steps/period",
        bound: Bound::Min,
        passed: r.resolved(),
        at: Evidence::Resolution(Box::new(r.clone())),
    }
}

#[cfg(test)]
mod tests {
    use super::evaluate;
    use crate::engine::scene::{self, Writes};
    use crate::engine::summary::summarise;
    use crate::model::Plan;

    /// A lost-motion limit on a clearance scene: with the scene planned as the spec asks (the
    /// limit reads the backlash detail) it is checked; with a plan that leaves the backlash
    /// out (a planning fault) the run is an error, not a limit quietly skipped.
    #[test]
    fn a_limit_whose_value_is_missing_is_an_error() {
        let text = std::fs::read_to_string("specs/reducer.yaml")
            .unwrap()
            .replace("limits:\n", "limits:\n  max_lost_motion_arcsec: 100000.0\n");
        let spec = crate::spec::parse("lost.yaml", &text).unwrap();
        let s = &spec.scenes[0];
        let planned = scene::run(
            &spec,
            s,
            &scene::plan(&spec, s, Writes::default()),
            &Default::default(),
        )
        .unwrap();
        let checks = evaluate(&spec, &summarise(&[planned])).unwrap();
        assert!(checks
            .iter()
            .any(|c| c.id.ends_with("/max_lost_motion_arcsec")));
        let bare = scene::run(&spec, s, &Plan::for_scene(s), &Default::default()).unwrap();
        let e = evaluate(&spec, &summarise(&[bare])).unwrap_err();
        assert!(e.to_string().contains("max_lost_motion_arcsec"), "{e}");
    }
}
