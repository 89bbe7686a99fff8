//! Sensitivities of the limited quantities to the toleranced deviations: ∂q/∂p by central
//! differences on the exact engine about the nominal reducer, the linear stack-up
//! σ_q = sqrt(Σ (∂q/∂p·σ_p)²), and each kind's share of it (the Pareto of which tolerance to
//! tighten first).
//!
//! A limited quantity is a max or min over rollers and crank angles: the linear estimate holds
//! only while the worst roller and angle stay the same over the band; where they change, q is
//! not differentiable and the Monte Carlo spread is the answer.

use super::ToleranceStudy;
use crate::error::Result;
use crate::model::results::is_unbounded;
use crate::model::tolerances::Kind;

/// Step of the central differences, mm (0.1 µm). The engine solves to 1e-9 relative: a force
/// of ~10³ N carries ~10⁻⁶ N of noise, a gap ~10⁻¹⁴ mm; over 2h that is 5·10⁻³ N/mm against
/// derivatives of ~10⁴–10⁵ N/mm (contact stiffness), 10⁻¹⁰ against O(1) for gaps. Truncation
/// is q'''·h²/6: over the mm scale of the geometry about 10⁻⁸ relative. And h stays well inside
/// a µm band, so the worst roller and angle rarely change within ±h.
pub const STEP_MM: f64 = 1e-4;

/// The derivatives of every limited quantity (rows, the study's limits) by every drawn
/// parameter (columns, the study's parameters), at the nominal reducer.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensitivity {
    /// `derivative[l][p]` = ∂q_l/∂p, in the quantity's unit per mm; `None` where q has no
    /// finite bound on either side (`UNBOUNDED_LIFE_H`: a life or safety without load or
    /// damage), which has no derivative.
    pub derivative: Vec<Vec<Option<f64>>>,
    /// σ_p of each parameter, mm.
    pub sigma_mm: Vec<f64>,
}

impl Sensitivity {
    /// The linear stack-up σ of limit l: sqrt(Σ_p (∂q/∂p·σ_p)²); `None` without every
    /// derivative.
    pub fn linear_sigma(&self, l: usize) -> Option<f64> {
        self.derivative[l]
            .iter()
            .zip(&self.sigma_mm)
            .map(|(d, s)| d.map(|d| (d * s).powi(2)))
            .sum::<Option<f64>>()
            .map(f64::sqrt)
    }

    /// The variance contribution of each kind to limit l, largest first: (kind, Σ over its
    /// parts of (∂q/∂p·σ_p)², share of the total).
    /// Empty without every derivative.
    pub fn pareto(&self, study: &ToleranceStudy, l: usize) -> Vec<(Kind, f64, f64)> {
        let Some(derivative) = self.derivative[l]
            .iter()
            .copied()
            .collect::<Option<Vec<f64>>>()
        else {
            return Vec::new();
        };
        let mut by_kind: Vec<(Kind, f64)> = Vec::new();
        for ((p, d), s) in study.params.iter().zip(derivative).zip(&self.sigma_mm) {
            let v = (d * s).powi(2);
            match by_kind.iter_mut().find(|(k, _)| *k == p.kind) {
                Some((_, sum)) => *sum += v,
                None => by_kind.push((p.kind, v)),
            }
        }
        let total: f64 = by_kind.iter().map(|(_, v)| v).sum();
        let mut ranked: Vec<_> = by_kind
            .into_iter()
            .map(|(k, v)| (k, v, if total > 0.0 { v / total } else { 0.0 }))
            .collect();
        ranked.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        ranked
    }
}

/// ∂q/∂p of one parameter: (q(+h) − q(−h)) / 2h, every other parameter nominal; `None` for a
/// quantity unbounded at either side.
pub fn derivatives(study: &ToleranceStudy, param: usize, step_mm: f64) -> Result<Vec<Option<f64>>> {
    let at = |h: f64| {
        let mut values = vec![0.0; study.params.len()];
        values[param] = h;
        let name = study.params[param].name(study.spec.design.discs);
        study
            .evaluate(&values, &format!("sensitivity to {name} = {h} mm"))
            .map(|(v, _)| v)
    };
    let (plus, minus) = (at(step_mm)?, at(-step_mm)?);
    Ok(plus
        .iter()
        .zip(&minus)
        .map(|(&p, &m)| {
            let bounded = !is_unbounded(p) && !is_unbounded(m);
            bounded.then(|| (p - m) / (2.0 * step_mm))
        })
        .collect())
}

/// Every derivative of the study, the parameters in parallel.
pub fn run(
    study: &ToleranceStudy,
    progress: &dyn crate::progress::Progress,
) -> Result<Sensitivity> {
    use rayon::prelude::*;
    let n = study.params.len();
    let columns: Vec<Result<Vec<Option<f64>>>> = (0..n)
        .into_par_iter()
        .map(|p| {
            let d = derivatives(study, p, STEP_MM);
            progress.advance(1);
            d
        })
        .collect();
    let columns: Vec<Vec<Option<f64>>> = columns.into_iter().collect::<Result<_>>()?;
    let derivative = (0..study.limits.len())
        .map(|l| columns.iter().map(|c| c[l]).collect())
        .collect();
    let sigma_mm = study
        .params
        .iter()
        .map(|p| study.tolerances.sigma_mm(p.kind))
        .collect();
    Ok(Sensitivity {
        derivative,
        sigma_mm,
    })
}
