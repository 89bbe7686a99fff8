//! Torsion under a locked input: the torsion curve and the catalogue figures (MODEL.md
//! "Several discs, torsion, bearing life").
//!
//! At each crank angle φ of the scene the input is held and the output is loaded by T over the
//! loop −Trated → +Trated → −Trated; the torsion angle is the reducer's output lag γ(T) (with
//! one disc γ = β + βo, the loaded TE at that torque). The figures are those the major makers
//! of precision reducers state in their catalogues (Nabtesco's RV catalogues and Sumitomo's
//! Fine Cyclo catalogues draw the same hysteresis curve and read from it):
//!
//! - **lost motion**: the torsion angle between the loop's points at ±3 % of the rated torque,
//!   on its centre line: γ(+3 %) − γ(−3 %);
//! - **backlash**: the dead band at zero torque, γ(0⁺) − γ(0⁻);
//! - **torsional rigidity**: the secant slope b/a between 50 % and 100 % of the rated torque,
//!   ΔT/Δγ with ΔT = Trated/2, in each direction; the figure is the smaller one (N·m/arcmin).
//!
//! The catalogue loop is a hysteresis loop because real reducers have friction. Without
//! `reducer.friction` this model is quasi-static and frictionless: the loading and unloading
//! branches coincide and the hysteresis loss is zero. With it (`friction_loop`) every contact's
//! Coulomb friction resists the disc's turn (`equilibrium::torsion`): the loading
//! branch (−Trated → +Trated, σ = +1) and the unloading one (back, σ = −1) part, and
//! - **hysteresis loss** = the width at T = 0 of the loop the disc traverses (`Traversed`),
//!   falling minus rising half, the mean of its values at 0⁺ and 0⁻: the branches' width
//!   (2·M_f/K to first order, M_f the friction moment at zero torque) while M_f ≤ Trated/2;
//!   beyond, the disc held after each reversal never reaches the branches at T = 0, and the
//!   width is that of the held segments, 2·(Trated − M_f)/K (without preload zero: at either
//!   edge of the dead band no contact is loaded, so none carries friction — MODEL.md);
//! - the lost motion and backlash are read on the loop's **centre line**, the mean of the two
//!   branches at the same torque (the catalogue's definition), the rigidity on the branch
//!   that loads in its direction (+50 → +100 % loading, −50 → −100 % unloading);
//! - the loop's **area** ∮ T dγ, of the same traversed loop, is the energy friction takes per
//!   cycle;
//! - the curve is that loop: after each reversal the disc sticks until the torque has changed
//!   enough for the other branch to reach it (its own lag β is held, Masing's rule for
//!   Coulomb friction, while what is in series, the pins and the structure, keeps twisting
//!   with the torque and stores and returns its energy), which the branches in full sliding
//!   alone would not show.
//!
//! The figures come from their own solves at exactly ±3 %, ±50 %, ±100 % of the rated torque
//! (the loop's samples need not land on them), and the one-sided limits T → 0± from solves at
//! ±`ZERO_SIDE`·Trated. That limit is chosen over the exact touching lag because the same
//! solve serves every model (rigid or compliant bearing, exact or first-order geometry, both
//! contact laws, pins with hole clearance, preload) with no special case. Its error is the
//! elastic twist over ±1e-6·Trated, 2e-6·Trated/k₀ with k₀ the stiffness at zero torque (one
//! roller contact at least): for the paper's design at 20 N·m, 7e-5 arcsec (measured against
//! the clearance effect's unloaded lost motion), far below any figure's printed resolution
//! (0.01 arcmin = 0.6 arcsec). 1e-6 rather than smaller: at 1e-9·Trated the compliant bearing's
//! solve no longer converges (its force merit at 2e-8 N·m stalls at 1e-6).

use crate::equilibrium::discs::{CoupledWork, Discs};
use crate::equilibrium::solve::SolveFailure;
use crate::equilibrium::torsion::{branches, solve_point, BranchPoint};
use crate::model::results::{TorsionCompliances, TorsionCurves, TorsionFigures};
use crate::model::TorqueSweep;
use crate::progress::Progress;
use rayon::prelude::*;

/// The fraction of the rated torque at which lost motion is read (±3 %).
pub const LOST_MOTION_AT: f64 = 0.03;

/// The one-sided limits T → 0± are solved at ±this fraction of the rated torque.
pub const ZERO_SIDE: f64 = 1e-6;

/// The torques of the figures' own solves, as fractions of the rated torque, in the order they
/// are solved (one monotone path, each warm-started from the last): γ at these is the input of
/// `figures`.
pub const FIGURE_TORQUES: [f64; 8] = [
    -1.0,
    -0.5,
    -LOST_MOTION_AT,
    -ZERO_SIDE,
    ZERO_SIDE,
    LOST_MOTION_AT,
    0.5,
    1.0,
];

/// The catalogue figures from γ (rad) at the torques `FIGURE_TORQUES`·`rated_nmm`: lost
/// motion γ(+3 %) − γ(−3 %), backlash γ(0⁺) − γ(0⁻), rigidity (Trated/2)/(γ(±100 %) − γ(±50 %))
/// each way (N·mm/rad). A pure function, so that it can be checked on curves known by hand.
/// An error when the curve does not rise between 50 % and 100 % (no finite rigidity).
pub fn figures(rated_nmm: f64, gamma: &[f64; 8]) -> Result<TorsionFigures, String> {
    let [m100, m50, m3, m0, p0, p3, p50, p100] = *gamma;
    let half = 0.5 * rated_nmm;
    let secant = |a: f64, b: f64, which: &str| {
        let twist = b - a;
        if twist > 0.0 && (half / twist).is_finite() {
            Ok(half / twist)
        } else {
            Err(format!(
                "the torsion curve does not rise between 50 % and 100 % of the rated torque \
                 ({which}: {twist:e} rad), so it has no torsional rigidity"
            ))
        }
    };
    Ok(TorsionFigures {
        lost_motion_rad: p3 - m3,
        backlash_rad: p0 - m0,
        rigidity_nmm_per_rad: (secant(p50, p100, "forward")?, secant(m100, m50, "reverse")?),
        hysteresis_rad: 0.0,
        loop_energy_nmm: 0.0,
    })
}

/// A solve of the torsion loop that failed: where, and why.
#[derive(Debug, Clone)]
pub struct TorsionFailure {
    pub crank_rad: f64,
    /// The torque of the failed solve, N·mm.
    pub torque_nmm: f64,
    pub failure: String,
}

/// The torsion curve over the loop and the figures at one locked crank angle: the torsion
/// angle γ(T) + c_s·T, γ the loaded model's output lag and c_s (`structure_rad_per_nmm`,
/// rad/(N·mm)) the rest of the reducer's torsional compliance, in series (a spring in series
/// twists by its own compliance times the torque it carries, the whole T). With the discs'
/// friction, when they carry it: `friction_loop`.
pub fn at_angle(
    discs: &Discs,
    sweep: &TorqueSweep,
    torques_nmm: &[f64],
    crank_rad: f64,
    structure_rad_per_nmm: f64,
) -> Result<(Vec<f64>, [f64; 8], TorsionFigures), TorsionFailure> {
    if discs.models.iter().any(|m| m.coupling.is_some()) {
        return friction_loop(discs, sweep, torques_nmm, crank_rad, structure_rad_per_nmm);
    }
    let mut discs = discs.clone();
    let mut work = CoupledWork::new(&discs);
    let fail = |torque_nmm, failure| TorsionFailure {
        crank_rad,
        torque_nmm,
        failure,
    };
    let mut solve = |t: f64, work: &mut CoupledWork| {
        solve_point(&mut discs, crank_rad, t, work)
            .map(|g| g + structure_rad_per_nmm * t)
            .map_err(|f| fail(t, solve_failed(f)))
    };
    // The loop; at T = 0 the rising branch (m = steps) comes from below and holds γ(0⁻), the
    // falling one γ(0⁺), so the dead band is a vertical step of the loop.
    let zero = ZERO_SIDE * sweep.rated_nmm;
    let mut curve = Vec::with_capacity(torques_nmm.len());
    for (m, &t) in torques_nmm.iter().enumerate() {
        let t = if t != 0.0 {
            t
        } else if m <= 2 * sweep.steps {
            -zero
        } else {
            zero
        };
        curve.push(solve(t, &mut work)?);
    }
    let mut gamma = [0.0; 8];
    for (g, f) in gamma.iter_mut().zip(FIGURE_TORQUES) {
        *g = solve(f * sweep.rated_nmm, &mut work)?;
    }
    let figures = figures(sweep.rated_nmm, &gamma).map_err(|m| fail(sweep.rated_nmm, m))?;
    Ok((curve, gamma, figures))
}

/// The loop with friction at one locked crank angle: the loading branch (σ = +1) from
/// −Trated up to +Trated, then the unloading branch (σ = −1) back down, each one monotone path
/// through the loop's torques (its zero as 0⁻ and 0⁺) and the figures', every point
/// warm-started from the last. The figures (lost motion and backlash on the centre line, the
/// rigidity on the branch loading its way); the hysteresis and the loop's energy are read off
/// the loop the disc traverses (`Traversed`), the one the curve draws.
fn friction_loop(
    discs: &Discs,
    sweep: &TorqueSweep,
    torques_nmm: &[f64],
    crank_rad: f64,
    structure_rad_per_nmm: f64,
) -> Result<(Vec<f64>, [f64; 8], TorsionFigures), TorsionFailure> {
    let rated = sweep.rated_nmm;
    let zero = ZERO_SIDE * rated;
    // The branches' torques, ascending.
    let mut up: Vec<f64> = torques_nmm
        .iter()
        .flat_map(|&t| if t == 0.0 { vec![-zero, zero] } else { vec![t] })
        .chain(FIGURE_TORQUES.iter().map(|f| f * rated))
        .collect();
    up.sort_by(f64::total_cmp);
    up.dedup();
    let fail = |torque_nmm, failure| TorsionFailure {
        crank_rad,
        torque_nmm,
        failure,
    };
    let (loading, unloading) = branches(discs, crank_rad, &up, structure_rad_per_nmm)
        .map_err(|(t, f)| fail(t, solve_failed(f)))?;
    let traversed = Traversed::new(&up, loading, unloading)
        .map_err(|(top, bottom)| fail(rated, held_throughout(top, bottom)))?;
    let curve = torques_nmm
        .iter()
        .enumerate()
        .map(|(m, &t)| {
            if m <= 2 * sweep.steps {
                traversed.rising(if t == 0.0 { -zero } else { t })
            } else {
                traversed.falling(if t == 0.0 { zero } else { t })
            }
        })
        .collect();
    // The figures' γ: lost motion and backlash on the centre line; the rigidity on the branch
    // that loads in its direction (loading from +50 % to +100 %, unloading from −50 % to
    // −100 %), as a catalogue measures it and where the drawn loop runs.
    let mut read = [0.0; 8];
    for (i, f) in FIGURE_TORQUES.into_iter().enumerate() {
        let (l, u) = traversed.branches(f * rated);
        read[i] = if f.abs() < 0.5 {
            0.5 * (l + u)
        } else if f > 0.0 {
            l
        } else {
            u
        };
    }
    let mut figures = figures(rated, &read).map_err(|m| fail(rated, m))?;
    figures.hysteresis_rad = traversed.width_at_zero(zero);
    figures.loop_energy_nmm = traversed.area();
    Ok((curve, read, figures))
}

/// The loop the disc traverses (Masing's rule for Coulomb friction): after the reversal at
/// +Trated the discs hold their lag β_top = β_loading(+Trated) until the unloading branch's β
/// comes down to it, after the one at −Trated they hold β_bottom = β_unloading(−Trated) until
/// the loading branch's β rises to it; while held, γ = β_held + the series' twist at that
/// torque (taken from the branch the torque moves along: exact for frictionless pins, whose
/// deflection is a function of the torque; with pins' friction, their deflection on that
/// branch, the pins' own sticking not modelled: at a reversal the loop steps from one
/// branch's deflection to the other's). The stick test and the held segments read the discs' lag β, not γ: a twist in
/// series neither holds the discs nor lets them go. The curve, the hysteresis and the energy
/// are all read from here.
struct Traversed<'a> {
    /// The branches' torques, ascending, N·mm.
    up: &'a [f64],
    loading: Vec<BranchPoint>,
    unloading: Vec<BranchPoint>,
    /// β_loading(+Trated) and β_unloading(−Trated), rad.
    top_rad: f64,
    bottom_rad: f64,
}

impl<'a> Traversed<'a> {
    /// The loop over `up` from its branches in full sliding; `Err((β_top, β_bottom))` when
    /// friction holds the discs over the whole loop (β_bottom ≥ β_top: the friction moment is
    /// at least the rated torque, and after the first reversal the discs never slide again).
    fn new(
        up: &'a [f64],
        loading: Vec<BranchPoint>,
        unloading: Vec<BranchPoint>,
    ) -> Result<Self, (f64, f64)> {
        let top_rad = loading[loading.len() - 1].disc_rad;
        let bottom_rad = unloading[0].disc_rad;
        if bottom_rad >= top_rad {
            return Err((top_rad, bottom_rad));
        }
        Ok(Traversed {
            up,
            loading,
            unloading,
            top_rad,
            bottom_rad,
        })
    }

    /// The index in `up` of the torque `t` (N·mm; every torque read is one of them).
    fn index(&self, t: f64) -> usize {
        let i = self
            .up
            .binary_search_by(|x| x.total_cmp(&t))
            .unwrap_or_else(|i| i);
        i.min(self.up.len() - 1)
    }

    /// γ (rad) of the loading and the unloading branch in full sliding at `t`.
    fn branches(&self, t: f64) -> (f64, f64) {
        let i = self.index(t);
        (self.loading[i].torsion_rad, self.unloading[i].torsion_rad)
    }

    /// γ (rad) on the rising half of the loop at `t`: the loading branch once its β has risen
    /// to β_bottom, held there before; at −Trated itself, where the falling half left it.
    fn rising(&self, t: f64) -> f64 {
        match self.index(t) {
            0 => self.held_falling(0),
            i => self.held_rising(i),
        }
    }

    /// γ (rad) on the falling half of the loop at `t`: the unloading branch once its β has
    /// come down to β_top, held there before; at +Trated itself, where the rising half left it.
    fn falling(&self, t: f64) -> f64 {
        match self.index(t) {
            i if i == self.up.len() - 1 => self.held_rising(i),
            i => self.held_falling(i),
        }
    }

    /// γ (rad) at `up[i]` after the reversal at −Trated: β held at β_bottom until the loading
    /// branch's β reaches it.
    fn held_rising(&self, i: usize) -> f64 {
        let p = self.loading[i];
        if p.disc_rad >= self.bottom_rad {
            p.torsion_rad
        } else {
            self.bottom_rad + p.series_rad()
        }
    }

    /// γ (rad) at `up[i]` after the reversal at +Trated: β held at β_top until the unloading
    /// branch's β comes down to it.
    fn held_falling(&self, i: usize) -> f64 {
        let p = self.unloading[i];
        if p.disc_rad <= self.top_rad {
            p.torsion_rad
        } else {
            self.top_rad + p.series_rad()
        }
    }

    /// The loop's width γ_falling − γ_rising (rad) at `t`.
    fn width(&self, t: f64) -> f64 {
        self.falling(t) - self.rising(t)
    }

    /// The hysteresis loss (rad): the loop's width at T = 0, the mean of its values at 0⁻ and
    /// 0⁺ (±`zero_nmm`, each side of a dead band).
    fn width_at_zero(&self, zero_nmm: f64) -> f64 {
        0.5 * (self.width(-zero_nmm) + self.width(zero_nmm))
    }

    /// The loop's area ∮ T dγ = ∫ (γ_falling − γ_rising) dT over −Trated…Trated (N·mm = mJ):
    /// the energy friction takes per cycle, by trapezoids over `up`.
    fn area(&self) -> f64 {
        (self.up.windows(2))
            .map(|w| 0.5 * (self.width(w[0]) + self.width(w[1])) * (w[1] - w[0]))
            .sum()
    }
}

/// The message of a solve of the loop that failed.
fn solve_failed(f: SolveFailure) -> String {
    format!("equilibrium solve failed: {f}")
}

/// The message of a loop whose friction never lets the disc slide: the disc's own lag on the
/// unloading branch at −Trated (`bottom`, rad) is not below its lag on the loading branch at
/// +Trated (`top`), so after the first reversal the disc stays where it is over the whole loop.
fn held_throughout(top: f64, bottom: f64) -> String {
    format!(
        "friction holds the disc over the whole torsion loop: the disc's own lag on the \
         unloading branch at −rated (β = {} arcmin) is not below its lag on the loading branch \
         at +rated (β = {} arcmin), so the friction moment exceeds the rated torque and the \
         disc never slides back; the loop has no catalogue figures. Raise \
         torque_sweep.rated_nm, or lower μ or the preload",
        crate::numeric::number(crate::units::arcmin(bottom)),
        crate::numeric::number(crate::units::arcmin(top)),
    )
}

/// The torsion curves and figures at every crank angle of a scene (in parallel, each angle on
/// its own: results do not depend on the thread count), telling `progress` of each angle done.
/// A failure names the first crank angle (in the scene's order) that failed. `compliances`
/// says what the loaded model `discs` includes, and gives the structure's compliance that
/// `at_angle` adds.
pub fn run(
    discs: &Discs,
    sweep: &TorqueSweep,
    crank_rad: &[f64],
    compliances: TorsionCompliances,
    progress: &dyn Progress,
) -> Result<TorsionCurves, TorsionFailure> {
    let torque_nmm = sweep.torques_nmm();
    let structure = compliances.structure_rad_per_nmm;
    let per_angle: Vec<_> = crank_rad
        .par_iter()
        .map(|&c| {
            let done = at_angle(discs, sweep, &torque_nmm, c, structure);
            progress.advance(1);
            done
        })
        .collect();
    let mut out = TorsionCurves {
        torque_nmm,
        torsion_rad: Vec::with_capacity(crank_rad.len()),
        figures: Vec::with_capacity(crank_rad.len()),
        figure_torsion_rad: Vec::with_capacity(crank_rad.len()),
        friction: discs.models.iter().any(|m| m.coupling.is_some()),
        compliances,
    };
    for angle in per_angle {
        let (curve, gamma, figures) = angle?;
        out.torsion_rad.push(curve);
        out.figure_torsion_rad.push(gamma);
        out.figures.push(figures);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The loop's torques: −rated up to +rated and back, exact zeros in the middle of each
    /// branch, `4·steps + 1` points.
    #[test]
    fn the_loop_goes_up_and_back_down() {
        let t = TorqueSweep {
            rated_nmm: 2.0,
            steps: 2,
        }
        .torques_nmm();
        assert_eq!(t, [-2.0, -1.0, 0.0, 1.0, 2.0, 1.0, 0.0, -1.0, -2.0]);
    }
}
