//! Limits → checks → verdicts. A limit applies to every scene that computes its quantity.

use crate::error::{Error, ErrorKind, Result};
use crate::model::results::SceneResult;
use crate::model::Limits;
use crate::model::{Effect, Plan};
use crate::numeric::{extremes, fluctuation, max_entry};
use crate::spec::Spec;
use crate::units;

/// Direction of a limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// value ≤ limit passes.
    Max,
    /// value ≥ limit passes.
    Min,
}

/// Comparison tolerance of limits and constraints: 1e-12 of max(1, |limit|). It absorbs the
/// binary representation of decimal inputs (0.150 − 0.135 is 0.01499999999999999 in f64) and
/// the ~1e-14 mm round-off of the exact gap, and is a picometre on a millimetre limit.
pub fn tolerance(limit: f64) -> f64 {
    1e-12 * limit.abs().max(1.0)
}

/// Does `value` satisfy `limit` in the direction `bound` (within `tolerance`)?
pub fn passes(value: f64, limit: f64, bound: Bound) -> bool {
    match bound {
        Bound::Max => value <= limit + tolerance(limit),
        Bound::Min => value >= limit - tolerance(limit),
    }
}

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
    /// Where the value occurs (roller, crank angle, ...), for the reader.
    pub at: String,
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
        let scale = if self.limit != 0.0 {
            self.limit.abs()
        } else {
            1.0
        };
        let beyond = match self.bound {
            Bound::Max => self.value - self.limit,
            Bound::Min => self.limit - self.value,
        };
        if beyond.is_nan() {
            f64::INFINITY
        } else {
            beyond / scale
        }
    }

    /// The check of a golden comparison.
    pub fn from_golden(g: &crate::engine::golden::GoldenResult) -> Check {
        let w = &g.comparison.worst;
        let num = crate::numeric::number;
        Check {
            id: format!("{}/golden:{}", g.golden.scene, g.golden.quantity),
            kind: CheckKind::Golden,
            value: w.deviation,
            limit: w.band,
            unit: g.unit,
            bound: Bound::Max,
            passed: g.comparison.passed,
            at: format!(
                "worst at {}: golden {}, now {} ({})",
                w.place(),
                num(w.golden),
                num(w.value),
                g.golden.path.display()
            ),
        }
    }
}

/// Unit of a limit, from its key's suffix.
fn unit_of(key: &str) -> &'static str {
    for (suffix, unit) in [
        ("_mm", "mm"),
        ("_n", "N"),
        ("_mpa", "MPa"),
        ("_arcsec", "arcsec"),
    ] {
        if key.ends_with(suffix) {
            return unit;
        }
    }
    ""
}

struct LimitDef {
    key: &'static str,
    bound: Bound,
    effect: Effect,
    get: fn(&Limits) -> Option<f64>,
    value: fn(&SceneResult) -> Option<(f64, String)>,
}

fn at_angle(r: &SceneResult, k: usize) -> f64 {
    units::deg(r.crank_rad.get(k).copied().unwrap_or(0.0))
}

fn max_over(r: &SceneResult, rows: &[Vec<f64>], what: &str) -> (f64, String) {
    let (v, i, k) = max_entry(rows);
    (v, format!("{what} {i} at crank {:.2}°", at_angle(r, k)))
}

const LIMITS: &[LimitDef] = &[
    LimitDef {
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
                        units::deg(c.min.crank_rad),
                        c.min.tooth_phase
                    ),
                )
            })
        },
    },
    LimitDef {
        key: "max_roller_force_n",
        bound: Bound::Max,
        effect: Effect::RollerContact,
        get: |l| l.max_roller_force_n,
        value: |r| {
            r.loaded
                .rollers
                .as_ref()
                .map(|c| max_over(r, &c.force_n, "roller"))
        },
    },
    LimitDef {
        key: "max_contact_pressure_mpa",
        bound: Bound::Max,
        effect: Effect::RollerContact,
        get: |l| l.max_contact_pressure_mpa,
        value: |r| {
            r.loaded
                .rollers
                .as_ref()
                .map(|c| max_over(r, &c.pressure_mpa, "roller"))
        },
    },
    LimitDef {
        key: "min_rollers_in_contact",
        bound: Bound::Min,
        effect: Effect::RollerContact,
        get: |l| l.min_rollers_in_contact.map(|n| n as f64),
        value: |r| {
            r.loaded.rollers.as_ref().map(|c| {
                let counts: Vec<f64> = c.contacts.iter().map(|&n| n as f64).collect();
                let ((lo, k), _) = extremes(&counts);
                (lo, format!("crank {:.2}°", at_angle(r, k)))
            })
        },
    },
    LimitDef {
        key: "max_te_fluctuation_arcsec",
        bound: Bound::Max,
        effect: Effect::RollerContact,
        get: |l| l.max_te_fluctuation_arcsec,
        value: |r| {
            r.loaded.transmission.as_ref().map(|t| {
                let ((_, lo), (_, hi)) = extremes(&t.te_rad);
                (
                    units::arcsec(fluctuation(&t.te_rad)),
                    format!(
                        "min at {:.2}°, max at {:.2}°",
                        at_angle(r, lo),
                        at_angle(r, hi)
                    ),
                )
            })
        },
    },
    LimitDef {
        key: "max_ratio_fluctuation",
        bound: Bound::Max,
        effect: Effect::RollerContact,
        get: |l| l.max_ratio_fluctuation,
        value: |r| {
            let ratio = r.loaded.transmission.as_ref()?.ratio.as_ref()?;
            let ((_, lo), (_, hi)) = extremes(ratio);
            Some((
                fluctuation(ratio),
                format!(
                    "min at {:.2}°, max at {:.2}°",
                    at_angle(r, lo),
                    at_angle(r, hi)
                ),
            ))
        },
    },
    LimitDef {
        key: "max_pin_force_n",
        bound: Bound::Max,
        effect: Effect::OutputPins,
        get: |l| l.max_pin_force_n,
        value: |r| {
            r.loaded
                .pins
                .as_ref()
                .map(|c| max_over(r, &c.force_n, "pin"))
        },
    },
    LimitDef {
        key: "max_bearing_force_n",
        bound: Bound::Max,
        effect: Effect::Bearing,
        get: |l| l.max_bearing_force_n,
        value: |r| {
            r.loaded.bearing.as_ref().map(|b| {
                let (_, (v, k)) = extremes(&b.force_n);
                (v, format!("crank {:.2}°", at_angle(r, k)))
            })
        },
    },
];

/// Keys of the limits that a scene with this plan evaluates.
pub fn limits_for(limits: &Limits, plan: &Plan) -> Vec<&'static str> {
    LIMITS
        .iter()
        .filter(|d| (d.get)(limits).is_some() && plan.has(d.effect))
        .map(|d| d.key)
        .collect()
}

/// Every limit must be evaluated by at least one scene, and every golden's scene must compute
/// its quantity.
pub fn validate(spec: &Spec) -> Result<()> {
    for g in &spec.golden {
        let q = crate::model::quantity::find(g.quantity).expect("validated quantity");
        let scene = spec.scenes.iter().find(|s| s.name == g.scene);
        if scene.is_some_and(|s| !Plan::for_scene(s).has(q.effect)) {
            return Err(Error::new(
                ErrorKind::InvalidValue,
                format!(
                    "scene `{}` does not compute `{}`; add the effect `{}` to the scene",
                    g.scene,
                    g.quantity,
                    q.effect.name()
                ),
            )
            .at_key(format!("{}.quantity", g.key)));
        }
    }
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
            let passed = passes(value, limit, d.bound);
            checks.push(Check {
                id: format!("{}/{}", r.name, d.key),
                kind: CheckKind::Limit,
                unit: unit_of(d.key),
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

/// Checks on optimisation studies: the optimum satisfies every constraint (value: the smallest
/// margin, ≥ 0), and, when a limit is set, its objective is within `optimum_max_objective`.
pub fn optimisation(spec: &Spec, results: &[crate::engine::optimise::StudyResult]) -> Vec<Check> {
    let mut checks = Vec::new();
    for (study, r) in spec.studies.iter().zip(results) {
        let o = &r.optimum;
        let at = o
            .margins
            .iter()
            .min_by(|a, b| a.margin.total_cmp(&b.margin))
            .map_or(String::new(), |m| format!("tightest: {}", m.name));
        checks.push(Check {
            kind: CheckKind::Limit,
            // Every constraint (tip clearance band, whole-mesh clearance) is a length.
            unit: "mm",
            id: format!("optimise/{}/constraints", r.name),
            value: if o.failure.is_some() {
                f64::NEG_INFINITY
            } else {
                o.worst_margin().min(f64::MAX)
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
                [(o, _)] => o.unit(),
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
                at: study
                    .variables
                    .iter()
                    .map(|v| {
                        format!(
                            "{} {:.5}",
                            v.kind.key(),
                            v.kind.to_spec_unit(v.kind.get(&o.modification))
                        )
                    })
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
    }
    checks
}
