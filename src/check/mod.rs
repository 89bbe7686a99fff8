//! Limits → checks → verdicts. A limit applies to every scene that computes its quantity.

use crate::error::{Error, ErrorKind, Result};
use crate::scene::{Effect, Plan, SceneResult};
use crate::spec::{Limits, Spec};

/// Direction of a limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// value ≤ limit passes.
    Max,
    /// value ≥ limit passes.
    Min,
}

/// One evaluated limit in one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// `scene/limit_key`.
    pub id: String,
    pub value: f64,
    pub limit: f64,
    pub bound: Bound,
    pub passed: bool,
    /// Where the value occurs (roller, crank angle, ...), for the reader.
    pub at: String,
}

struct LimitDef {
    key: &'static str,
    bound: Bound,
    effect: Effect,
    get: fn(&Limits) -> Option<f64>,
    value: fn(&SceneResult) -> Option<(f64, String)>,
}

const LIMITS: &[LimitDef] = &[LimitDef {
    key: "min_clearance_mm",
    bound: Bound::Min,
    effect: Effect::Clearance,
    get: |l| l.min_clearance_mm,
    value: |r| {
        r.clearance.as_ref().map(|c| {
            (
                c.min.gap_mm,
                format!(
                    "roller {} at crank {:.2}°, tooth phase {:.3} (0 root, 0.5 tip)",
                    c.min.roller,
                    c.min.crank_rad.to_degrees(),
                    c.min.tooth_phase
                ),
            )
        })
    },
}];

/// Keys of the limits that a scene with this plan evaluates.
pub fn limits_for(limits: &Limits, plan: &Plan) -> Vec<&'static str> {
    LIMITS
        .iter()
        .filter(|d| (d.get)(limits).is_some() && plan.has(d.effect))
        .map(|d| d.key)
        .collect()
}

/// Every limit must be evaluated by at least one scene.
pub fn validate(spec: &Spec) -> Result<()> {
    for d in LIMITS {
        if (d.get)(&spec.limits).is_none() {
            continue;
        }
        let covered = spec.scenes.iter().any(|s| Plan::for_scene(s).has(d.effect));
        if !covered {
            return Err(Error::new(
                ErrorKind::InvalidValue,
                format!(
                    "no scene computes this limit's quantity; add the effect `{}` to a scene",
                    d.effect.name()
                ),
            )
            .at_key(format!("limits.{}", d.key)));
        }
    }
    Ok(())
}

/// Evaluate the spec's limits on the results of its scenes.
pub fn evaluate(limits: &Limits, results: &[SceneResult]) -> Vec<Check> {
    let mut checks = Vec::new();
    for r in results {
        for d in LIMITS {
            let (Some(limit), Some((value, at))) = ((d.get)(limits), (d.value)(r)) else {
                continue;
            };
            let passed = match d.bound {
                Bound::Max => value <= limit,
                Bound::Min => value >= limit,
            };
            checks.push(Check {
                id: format!("{}/{}", r.name, d.key),
                value,
                limit,
                bound: d.bound,
                passed,
                at,
            });
        }
    }
    checks
}
