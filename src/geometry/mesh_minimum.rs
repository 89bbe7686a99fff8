//! The smallest gap over the whole mesh (MODEL.md "Clearance"): a property of the geometry,
//! sought over the whole crank period after which the gaps of all the rollers repeat as a set
//! (`Design::clearance_periods`: one mesh period nominally, longer with a form error or rollers
//! as built), whatever crank angles a scene samples, at a step that bounds the sampling's error.
//!
//! **The bound.** Roller i's gap g_i(φ) is smooth where its closest point on Γ is unique; where
//! that point jumps to another part of the profile g_i is the smaller of two smooth branches,
//! and the smallest gap over the rollers, G = min g_i, is a minimum of smooth branches too. Its
//! corners point up, so at its minimum φ* the branch that attains it is smooth and level (two
//! branches that meet there are both level). A sample φ_s within h/2 of φ* then has
//! G(φ_s) ≤ g(φ_s) ≤ G(φ*) + M·(h/2)²/2 = G(φ*) + h²·M/8 (Taylor, M the largest g″ of that
//! branch between them), and the smallest sample, being a gap, is at least G(φ*): it lies in
//! [G*, G* + h²·M/8]. Samples whose steps are at most h and that span the period but for one
//! step put a sample within h/2 of every crank angle, the period wrapping round.
//!
//! **M** is estimated by the largest second difference of each roller's samples, which is the
//! mean of g″ over ±h (for a harmonic of frequency ω in φ, g″·(1 − (ωh)²/12 + …): 0.04 % low at
//! the mesh frequency ω = np with `FLOOR_STEPS` steps per mesh period); the corners give
//! negative differences and do not count. On the paper's optimum M ≈ 0.4 mm/rad², so a scene
//! at 0.1° bounds the error by 1.5e-4 µm, and `FLOOR_STEPS` (0.375°) by 2.2e-3 µm.

use super::clearance::{self, GapFailure, Mesh, Scope, TIE_MM};
use crate::model::results::{ClearanceSweep, MinClearance, MinCoverage, SampledPeriod};
use crate::model::Design;
use crate::progress::Silent;
use std::f64::consts::TAU;

/// Fewest samples per mesh period (2π/np) from which the second differences are taken as the
/// estimate of M (0.04 % low at the mesh frequency, see the module doc): a period's own
/// sampling starts there, and a scene's own angles stand for the period only at least as fine.
pub const FLOOR_STEPS: usize = 96;

/// Most samples per mesh period: the accuracy ladder's finest rung
/// (`model::accuracy::MAX_FINEST`).
const MOST_STEPS: usize = crate::model::accuracy::MAX_FINEST;

/// Most gap evaluations (rollers × samples) of one period's sampling: the bound on the work of
/// a scene's sweeps (`model::scene::MAX_ROLLER_ANGLES`).
const MOST_EVALUATIONS: usize = crate::model::scene::MAX_ROLLER_ANGLES as usize;

/// Samples swept at once, so that memory stays bounded whatever the period: 64 of the sweep's
/// chunks, enough to keep every thread busy.
const BLOCK: usize = 64 * clearance::CHUNK;

/// What the smallest gap over the mesh must cover, and how accurately.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// Mesh periods in the period of the gaps (`Design::clearance_periods`).
    pub periods: usize,
    /// The error bound sought, mm (the spec's `accuracy.tolerance.clearance_um`).
    pub tolerance_mm: f64,
}

impl Target {
    /// The period of `design`'s gaps, to `tolerance_mm`.
    pub fn new(design: &Design, tolerance_mm: f64) -> Self {
        Target {
            periods: design.clearance_periods(),
            tolerance_mm,
        }
    }

    /// The period, rad.
    pub fn period_rad(&self, mesh: &Mesh) -> f64 {
        mesh_period_rad(mesh) * self.periods as f64
    }
}

/// 2π/np.
fn mesh_period_rad(mesh: &Mesh) -> f64 {
    TAU / mesh.rollers as f64
}

/// The smallest gap over the whole mesh of one mesh, for the clearance sweeps of its discs:
/// the period's own sampling (`sample`, from crank 0 of the mesh, so that every disc and
/// scene of the mesh shares it) is run at most once.
pub struct MeshMinimum<'a> {
    mesh: &'a Mesh,
    target: Target,
    sampled: Option<(MinClearance, SampledPeriod)>,
}

impl<'a> MeshMinimum<'a> {
    /// The smallest gap of `mesh` over its whole period, to `target`.
    pub fn new(mesh: &'a Mesh, target: Target) -> Self {
        MeshMinimum {
            mesh,
            target,
            sampled: None,
        }
    }

    /// The period of the gaps, rad.
    pub fn period_rad(&self) -> f64 {
        self.target.period_rad(self.mesh)
    }

    /// The mesh.
    pub fn mesh(&self) -> &'a Mesh {
        self.mesh
    }

    /// Make `sweep`'s smallest gap (of its gaps at `crank_rad`, the mesh's crank angles: a
    /// disc's crank phase `shift_rad` added to the scene's) the smallest over the whole mesh,
    /// its crank angle the scene's. Its own angles stand for the period when they cover it at
    /// `FLOOR_STEPS` or finer and bound the error to the tolerance (a nominal scene over a
    /// mesh period: nothing more is computed); otherwise the smallest gap is the lower of the
    /// sweep's own and the period's sampling (a tie, within `TIE_MM`, keeps the sweep's own
    /// angle), whose crank angle is brought into [0, period) of the scene's crank.
    pub fn cover(
        &mut self,
        crank_rad: &[f64],
        shift_rad: f64,
        sweep: &mut ClearanceSweep,
    ) -> Result<(), GapFailure> {
        let (mesh, target) = (self.mesh, &self.target);
        sweep.min.crank_rad -= shift_rad;
        if let Some(own) = own_coverage(mesh, target, crank_rad, &sweep.gap_mm) {
            if own.error_bound_mm <= target.tolerance_mm {
                sweep.coverage = MinCoverage::Period(own);
                return Ok(());
            }
        }
        let (min, period) = self.sampled()?;
        if min.gap_mm < sweep.min.gap_mm - TIE_MM {
            sweep.min = self.in_period(min, shift_rad);
        }
        sweep.coverage = MinCoverage::Period(period);
        Ok(())
    }

    /// The period's sampling, run on first use.
    fn sampled(&mut self) -> Result<(MinClearance, SampledPeriod), GapFailure> {
        if let Some(done) = self.sampled {
            return Ok(done);
        }
        let done = sample(self.mesh, &self.target, 0.0)?;
        self.sampled = Some(done);
        Ok(done)
    }

    /// `min` (at a crank angle of the mesh) at the scene's crank angle φ − `shift_rad`, brought
    /// into [0, period): m periods back, the same gap is the one of roller i − m·periods
    /// (`Design::clearance_periods`: φ + 2π/np puts roller i + 1 where roller i was).
    fn in_period(&self, mut min: MinClearance, shift_rad: f64) -> MinClearance {
        let period = self.period_rad();
        let phi = min.crank_rad - shift_rad;
        let mut m = (phi / period).floor() as i64;
        min.crank_rad = (phi - m as f64 * period).max(0.0);
        if min.crank_rad >= period {
            min.crank_rad -= period;
            m += 1;
        }
        let back = m.rem_euclid(self.mesh.rollers as i64) as usize;
        let shift = back * (self.target.periods % self.mesh.rollers) % self.mesh.rollers;
        min.roller = (min.roller + self.mesh.rollers - shift) % self.mesh.rollers;
        min
    }
}

/// The coverage of the period by a sweep's own angles, when they are increasing, no step is
/// coarser than `FLOOR_STEPS` per mesh period, and they span the period but for one step.
fn own_coverage(
    mesh: &Mesh,
    target: &Target,
    crank_rad: &[f64],
    gap_mm: &[Vec<f64>],
) -> Option<SampledPeriod> {
    let (&first, &last) = (crank_rad.first()?, crank_rad.last()?);
    let step = crank_rad
        .windows(2)
        .map(|w| w[1] - w[0])
        .try_fold(0.0_f64, |h, d| (d > 0.0).then_some(h.max(d)))?;
    let period = target.period_rad(mesh);
    // Relative slack for the round-off of angles formed as from + k·step.
    let slack = 1.0 + 1e-9;
    let fine = step * FLOOR_STEPS as f64 <= mesh_period_rad(mesh) * slack;
    let spans = (last - first + step) * slack >= period;
    (step > 0.0 && fine && spans).then(|| SampledPeriod {
        period_rad: period,
        step_rad: step,
        error_bound_mm: bound_mm(step, curvature(crank_rad, gap_mm)),
    })
}

/// h²·M/8 (module doc).
fn bound_mm(step_rad: f64, curvature: f64) -> f64 {
    step_rad * step_rad * curvature / 8.0
}

/// The largest second difference of the gaps \[roller\]\[angle\] at `crank_rad` (divided
/// differences, for uneven steps), mm/rad²; 0 when none is positive.
fn curvature(crank_rad: &[f64], gap_mm: &[Vec<f64>]) -> f64 {
    let mut m = 0.0_f64;
    for gaps in gap_mm {
        for k in 1..crank_rad.len().saturating_sub(1) {
            let (h0, h1) = (
                crank_rad[k] - crank_rad[k - 1],
                crank_rad[k + 1] - crank_rad[k],
            );
            let slopes = (gaps[k + 1] - gaps[k]) / h1 - (gaps[k] - gaps[k - 1]) / h0;
            m = m.max(2.0 * slopes / (h0 + h1));
        }
    }
    m
}

/// The smallest gap over the period sampled from `start_rad`, and the sampling: `FLOOR_STEPS`
/// per mesh period, refined by powers of two until the bound meets the tolerance or the
/// samples reach `MOST_STEPS` per mesh period or `MOST_EVALUATIONS` (the bound is then what
/// it is, and said).
pub fn sample(
    mesh: &Mesh,
    target: &Target,
    start_rad: f64,
) -> Result<(MinClearance, SampledPeriod), GapFailure> {
    let most = most_steps(mesh, target);
    let mut steps = FLOOR_STEPS.min(most);
    loop {
        let (min, period) = sample_at(mesh, target, start_rad, steps)?;
        let bound = period.error_bound_mm;
        if bound <= target.tolerance_mm || steps >= most {
            return Ok((min, period));
        }
        // The next rung whose bound, at the curvature seen, meets the tolerance.
        let mut next = 2 * steps;
        while next < most && bound * (steps as f64 / next as f64).powi(2) > target.tolerance_mm {
            next *= 2;
        }
        steps = next.min(most);
    }
}

/// The finest sampling allowed, in steps per mesh period: `FLOOR_STEPS`·2^k up to
/// `MOST_STEPS` within `MOST_EVALUATIONS`, halved below the floor when even that is too much
/// (at least one).
fn most_steps(mesh: &Mesh, target: &Target) -> usize {
    let per_step = (mesh.rollers * target.periods).max(1);
    let allowed = (MOST_EVALUATIONS / per_step).max(1);
    let mut steps = FLOOR_STEPS;
    while steps > 1 && steps > allowed {
        steps /= 2;
    }
    while steps * 2 <= MOST_STEPS && steps * 2 <= allowed {
        steps *= 2;
    }
    steps
}

/// The period sampled at `steps` per mesh period from `start_rad`, in blocks of `BLOCK`
/// samples; each block is swept with one more sample on either side, so that the second
/// difference is taken at every sample.
fn sample_at(
    mesh: &Mesh,
    target: &Target,
    start_rad: f64,
    steps: usize,
) -> Result<(MinClearance, SampledPeriod), GapFailure> {
    let h = mesh_period_rad(mesh) / steps as f64;
    let count = steps * target.periods;
    let mut best: Option<MinClearance> = None;
    let mut m = 0.0_f64;
    for from in (0..count).step_by(BLOCK) {
        let to = (from + BLOCK).min(count);
        // Samples from − 1 ..= to: the gaps repeat with the period, so the samples either side
        // of it are gaps of the same set (and outside the period's range, never the minimum).
        let crank: Vec<f64> = (from as i64 - 1..=to as i64)
            .map(|k| start_rad + k as f64 * h)
            .collect();
        let swept = clearance::sweep(mesh, &crank, Scope::Gaps, &Silent)?;
        m = m.max(curvature(&crank, &swept.gap_mm));
        // The angles but the first and the last (those of the neighbouring blocks).
        let inside = 1..crank.len().saturating_sub(1);
        if let Some(low) = clearance::lowest(&crank, &swept.gap_mm, inside, None) {
            if best.is_none_or(|b| low.gap_mm < b.gap_mm - TIE_MM) {
                best = Some(low);
            }
        }
    }
    let none = MinClearance {
        gap_mm: f64::INFINITY,
        roller: 0,
        crank_rad: start_rad,
        tooth_phase: 0.0,
    };
    let min = clearance::on_tooth(mesh, best.unwrap_or(none))?;
    let period = SampledPeriod {
        period_rad: target.period_rad(mesh),
        step_rad: h,
        error_bound_mm: bound_mm(h, m),
    };
    Ok((min, period))
}
