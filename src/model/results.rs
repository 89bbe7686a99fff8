//! What the engine computes for a scene: plain data, engine units (mm, N, MPa, rad), arrays
//! `[angle]` or `[roller|pin][angle]`. A quantity that was not computed is `None`. The quantity
//! registry (`model::quantity`) reads these in the output units of its keys.

use super::friction::{FrictionModel, PathLosses};
use super::power_flow::PowerFlow;
use crate::numeric::max_entry;

/// Where the smallest gap of a sweep occurs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MinClearance {
    /// The smallest gap of the sweep, mm (negative: interference).
    pub gap_mm: f64,
    /// The roller it occurs at (index i, at angle 2πi/np).
    pub roller: usize,
    /// The crank angle φ it occurs at, rad (the first, when several tie): one of the scene's,
    /// or, over the whole mesh, of the samples of its period, which start at the scene's first.
    pub crank_rad: f64,
    /// Position on the tooth: 0 at the root, 0.5 at the tip, (0, 0.5) one flank, (0.5, 1) the other.
    pub tooth_phase: f64,
}

/// Over which crank angles the smallest gap of a clearance sweep was sought.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MinCoverage {
    /// The sweep's own crank angles only, this many (`geometry::clearance::sweep` alone).
    Angles(usize),
    /// A whole crank period of the gaps (`Design::clearance_period_rad`), sampled finely
    /// enough to bound the error (`geometry::mesh_minimum`): the smallest gap over the mesh.
    Period(SampledPeriod),
}

/// A whole crank period of the gaps as sampled for their smallest (`geometry::mesh_minimum`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledPeriod {
    /// The period after which the gaps of all the rollers repeat as a set, rad.
    pub period_rad: f64,
    /// The largest step between the samples that cover it, rad.
    pub step_rad: f64,
    /// How far above the true smallest gap the smallest sample may lie, mm: h²·M/8 with h the
    /// step and M the largest second difference of the sampled gaps (an estimate of max g″).
    pub error_bound_mm: f64,
}

/// Clearance of every roller over a crank sweep at the ideal pose (β = 0).
/// Arrays are indexed `[roller][angle]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ClearanceSweep {
    /// Gap of each roller, mm: the signed distance from its centre to the disc profile Γ minus
    /// its radius; positive clearance, negative interference (MODEL.md "Clearance").
    pub gap_mm: Vec<Vec<f64>>,
    /// The smallest gap, and where: over the sweep's angles, or over the whole mesh
    /// (`coverage`).
    pub min: MinClearance,
    /// Over which crank angles `min` was sought.
    pub coverage: MinCoverage,
    /// `None` when nothing read it (`Detail::Backlash` not planned).
    pub backlash: Option<BacklashCurves>,
}

/// Backlash over a crank sweep, from the closing lag of every roller: lags in rad, `[angle]`.
#[derive(Debug, Clone, PartialEq)]
pub struct BacklashCurves {
    /// Unloaded TE: the smallest closing lag among rollers closed by a positive lag (the load
    /// direction of a positive output torque). Negative under interference (preload).
    pub forward_rad: Vec<f64>,
    /// The same for the reverse direction, as a magnitude (−β of the nearest closing roller).
    pub reverse_rad: Vec<f64>,
    /// Lost motion: backlash + reverse backlash.
    pub lost_motion_rad: Vec<f64>,
}

/// Roller contact over the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct RollerCurves {
    /// β: lag of the disc behind −φ/nc, rad (positive opposes the motion).
    pub lag_rad: Vec<f64>,
    /// Contact force of each roller on the disc, N, `[roller][angle]`: its magnitude, along the
    /// disc's inward normal; 0 out of contact.
    pub force_n: Vec<Vec<f64>>,
    /// Hertz peak pressure p0 = sqrt(F·E*/(π·L·R*)) of each roller's contact, MPa,
    /// `[roller][angle]` (whatever the contact law; 0 out of contact).
    pub pressure_mpa: Vec<Vec<f64>>,
    /// Hertz half-width b = sqrt(4·F·R*/(π·L·E*)) of each roller's contact, mm,
    /// `[roller][angle]` (0 out of contact).
    pub half_width_mm: Vec<Vec<f64>>,
    /// How many rollers carry a force at each angle, `[angle]`.
    pub contacts: Vec<usize>,
    /// The line loads along the face width, when the scene resolves them (`face_slices` > 1,
    /// or a crowned or tilted face; MODEL.md "Along the face width").
    pub face: Option<FaceLoads>,
}

/// The rollers' loads along the face width over the sweep (MODEL.md "Along the face width").
#[derive(Debug, Clone, PartialEq)]
pub struct FaceLoads {
    /// The line load of each roller in each slice s (centred at z_s = −B/2 + (s + ½)·B/n),
    /// N/mm, `[roller][angle·slices + slice]` (`at`): the slice's force/(B/n) (slice 0 at
    /// z = −B/2, the end of negative z); 0 out of contact.
    pub line_load_n_per_mm: Vec<Vec<f64>>,
    /// Slices per angle of `line_load_n_per_mm`.
    pub slices: usize,
    /// The face load factor of each angle, `[angle]`: the peak line load over rollers and
    /// slices divided by the mean line load F_i/B of the roller that carries it (1 on a
    /// uniform face; 0 where no roller carries a force).
    pub face_load_factor: Vec<f64>,
}

impl FaceLoads {
    /// Roller `roller`'s line loads at angle `angle`, N/mm, slice by slice.
    pub fn at(&self, roller: usize, angle: usize) -> &[f64] {
        &self.line_load_n_per_mm[roller][angle * self.slices..(angle + 1) * self.slices]
    }

    /// Roller `roller`'s line loads, angle by angle.
    pub fn angles(&self, roller: usize) -> std::slice::ChunksExact<'_, f64> {
        self.line_load_n_per_mm[roller].chunks_exact(self.slices)
    }

    /// The largest line load over rollers, angles and slices, N/mm, and where: (value, roller,
    /// angle, slice), the first in that order; (0, 0, 0, 0) when nothing is loaded.
    pub fn peak_line_load(&self) -> (f64, usize, usize, usize) {
        match max_entry(&self.line_load_n_per_mm) {
            (q, i, j) if q > 0.0 => (q, i, j / self.slices, j % self.slices),
            _ => (0.0, 0, 0, 0),
        }
    }
}

/// Output pins over the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct PinCurves {
    /// βo: lag of the output behind the disc, rad.
    pub output_lag_rad: Vec<f64>,
    /// Contact force of each output pin on the disc, N, `[pin][angle]`: its magnitude; 0 where
    /// the pin does not touch its hole.
    pub force_n: Vec<Vec<f64>>,
    /// The direction of each pin's force, `[pin][angle]`: the angle of the force on the pin
    /// (the hole's push, −F·û) from the eccentric direction e_φ, counter-clockwise, rad. 0 in
    /// the first-order geometry (û = −e_φ) and where the pin carries no force; of the order
    /// of rw·βo/e in the exact geometry (the output lag turns the pin about its hole).
    pub direction_rad: Vec<Vec<f64>>,
}

/// Crank bearing over the sweep: force magnitude, its angle ε from the eccentric direction
/// (counter-clockwise), and the relative residual of the paper's Eqs. 12–14.
#[derive(Debug, Clone, PartialEq)]
pub struct BearingCurves {
    /// |Fb|, the magnitude of the crank bearing's force on the disc, N, `[angle]`.
    pub force_n: Vec<f64>,
    /// ε, the angle of Fb from the eccentric direction (cos φ, sin φ), counter-clockwise
    /// positive, rad, `[angle]`.
    pub angle_rad: Vec<f64>,
    /// The largest relative residual of the force and moment balances (the paper's
    /// Eqs. 12–14) at each angle, dimensionless (`equilibrium::residual`).
    pub residual: Vec<f64>,
    /// Disc-centre displacement magnitude (compliant bearing; zeros when rigid), mm.
    pub deflection_mm: Vec<f64>,
}

/// Loaded transmission error δ = β + βo (rad; βo = 0 when the pins are not modelled) and the
/// ratio κ = dφ/dφout = 1/(1/nc − dδ/dφ), by central differences (periodic when the sweep
/// covers whole mesh periods, second-order one-sided at the ends otherwise).
#[derive(Debug, Clone, PartialEq)]
pub struct Transmission {
    /// δ, rad, `[angle]`; with several discs the common output lag γ (MODEL.md "Several discs").
    pub te_rad: Vec<f64>,
    /// κ, dimensionless, `[angle]`; `None` for fewer than three crank angles.
    pub ratio: Option<Vec<f64>>,
}

/// One disc's loaded curves over the scene's crank angles, each `None` when its effect was not
/// computed (the reducer's curves over all discs are `ReducerResult`'s).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LoadedSweep {
    /// The disc's share of the output torque, N·mm `[angle]`: in a disc of several only.
    pub torque_nmm: Option<Vec<f64>>,
    /// The rollers' lag, forces and contacts (`Effect::RollerContact`).
    pub rollers: Option<RollerCurves>,
    /// The output pins' lag and forces (`Effect::OutputPins`).
    pub pins: Option<PinCurves>,
    /// The crank bearing's force and the balance residuals (`Effect::Bearing`).
    pub bearing: Option<BearingCurves>,
    /// The friction losses of the disc's contacts at each angle, per unit input speed,
    /// N·mm/rad `[angle]` (the input's drag aside: that is the reducer's), from each angle's
    /// solution as the sweep solved it: recorded for the effect `efficiency` only
    /// (`loaded::Model::losses`).
    pub losses: Option<Vec<PathLosses>>,
    /// The disc's share of the input torque at each angle, N·mm `[angle]`, from the crank's
    /// balance (`Coupling::input_torque`): recorded with `losses` for the coupled friction
    /// model only.
    pub input_torque_nmm: Option<Vec<f64>>,
    /// A disc's contact fatigue and crank bearing's static safety (`Effect::Strength`).
    pub strength: Option<super::strength::DiscStrength>,
}

/// The catalogue figures of a torsion curve γ(T) at one locked crank angle (MODEL.md "Several
/// discs, torsion, bearing life"; the makers' definitions, see `engine::torsion::figures`).
/// Angles in rad, torques in N·mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsionFigures {
    /// γ(+3 %) − γ(−3 %) of the rated torque.
    pub lost_motion_rad: f64,
    /// γ(0⁺) − γ(0⁻): the dead band at zero torque (0 under preload).
    pub backlash_rad: f64,
    /// Secant stiffness between 50 % and 100 % of rated, N·mm/rad: (forward, reverse).
    pub rigidity_nmm_per_rad: (f64, f64),
    /// Hysteresis loss: the width at T = 0 of the loop the disc traverses (the drawn curve),
    /// its falling half minus its rising half, the mean of its values at 0⁺ and 0⁻ (each side
    /// of a dead band), rad; 0 without friction.
    pub hysteresis_rad: f64,
    /// The traversed loop's area ∮ T dγ = ∫ (γ_falling − γ_rising) dT over −Trated…Trated: the
    /// energy friction takes per cycle of the loop, N·mm (= mJ); 0 without friction.
    pub loop_energy_nmm: f64,
}

impl TorsionFigures {
    /// The torsional rigidity figure: the smaller of the two directions.
    pub fn rigidity(&self) -> f64 {
        self.rigidity_nmm_per_rad.0.min(self.rigidity_nmm_per_rad.1)
    }
}

/// Torsion under a locked input: at each crank angle of the scene, the reducer's output lag γ
/// (the torsion angle, rad, sign of T) over the torque loop, and the catalogue figures. The
/// model is quasi-static: without friction the loading and unloading branches coincide and the
/// hysteresis loss is zero; with `reducer.friction` every contact's friction resists the
/// disc's turn and the branches part (`engine::torsion`).
#[derive(Debug, Clone, PartialEq)]
pub struct TorsionCurves {
    /// The loop's torques T_m, N·mm (`TorqueSweep::torques_nmm`).
    pub torque_nmm: Vec<f64>,
    /// γ `[crank][m]`, rad. At T = 0 the rising branch holds γ(0⁻), the falling branch γ(0⁺).
    /// With friction the rising points lie on the loading branch, the falling ones on the
    /// unloading branch, each held where the disc sticks after the loop's reversal.
    pub torsion_rad: Vec<Vec<f64>>,
    /// The figures `[crank]`.
    pub figures: Vec<TorsionFigures>,
    /// γ of the figures' own solves `[crank][i]`, rad, at the torques
    /// `engine::torsion::FIGURE_TORQUES[i]`·rated (−100, −50, −3 %, 0⁻, 0⁺, +3, +50, +100 %):
    /// with friction, at ±3 % and 0± on the loop's centre line (the mean of its two branches),
    /// at ±50 % and ±100 % on the branch loading that way (unloading below zero).
    pub figure_torsion_rad: Vec<[f64; 8]>,
    /// `reducer.friction` is given: the loop is solved with friction in the balance and the
    /// figures carry its hysteresis.
    pub friction: bool,
    /// What the torsion angle is made of: the contact law and the compliances modelled or
    /// given, which every text about the rigidity must say.
    pub compliances: TorsionCompliances,
}

impl TorsionCurves {
    /// The smallest hysteresis width the loop resolves at locked angle `k`, rad: the lag
    /// change of one torque step of the loop at the reducer's torsional rigidity, ΔT/K (ΔT =
    /// rated/steps, the step between the loop's torques, N·mm; K = `TorsionFigures::rigidity`,
    /// N·mm/rad). Coulomb friction holds the disc after a reversal until the torque has changed
    /// by 2·M_f = K·width (README "Torsion under a locked input"): a narrower loop is held for
    /// less than one step, which the loop's samples cannot show. Without preload the width at
    /// T = 0 is zero (no contact is loaded at either edge of the dead band) and what is
    /// computed is friction at the one-sided torques ±1e-6·rated, some 1e-8 arcmin, far below
    /// this (0.0077 arcmin on the paper's design at 20 N·m, 20 steps). 0 where the loop has no
    /// step or no stiffness (nothing is hidden then).
    pub fn hysteresis_resolution_rad(&self, k: usize) -> f64 {
        let step_nmm = crate::numeric::step(&self.torque_nmm).abs();
        let rigidity = self.figures.get(k).map_or(0.0, TorsionFigures::rigidity);
        if step_nmm > 0.0 && rigidity.is_finite() && rigidity > 0.0 {
            step_nmm / rigidity
        } else {
            0.0
        }
    }
}

/// The compliances in a torsion curve: the loaded model's (computed) and the structure's
/// (given). The torsion angle is γ(T) + c_s·T, γ the loaded model's output lag and c_s the
/// structure's compliance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsionCompliances {
    /// The contacts' force–approach law.
    pub contact_law: crate::model::ContactLaw,
    /// The geometry of the contacts (exact or first order).
    pub geometry: crate::model::GeometryMode,
    /// The output pins' contacts are modelled (`output_pins` in the scene).
    pub pin_contacts: bool,
    /// The crank bearing's radial stiffness, N/mm, when compliant; none: rigid (or not
    /// modelled).
    pub bearing_stiffness_n_per_mm: Option<f64>,
    /// The pins bend (`reducer.output_pins.support`), with the pin contacts modelled.
    pub pin_bending: Option<crate::model::PinSupport>,
    /// c_s, the rest of the reducer's torsional compliance, given, rad/(N·mm) (0: none).
    pub structure_rad_per_nmm: f64,
}

/// The rating life written for a bearing whose life has no finite bound: no load (P = 0 N,
/// nothing wears it), or a life beyond the largest double (C/P above ~1e92 with p = 10/3).
/// JSON carries no infinity, so the largest finite double, 1.7976931348623157e308 h, stands
/// for it: it passes every `min_bearing_life_h`, and every output that shows it says
/// "unbounded" beside it (`BearingLife::is_unbounded`).
pub const UNBOUNDED_LIFE_H: f64 = f64::MAX;

/// Whether `x` is the engine's "no finite bound" (`UNBOUNDED_LIFE_H`), not a number to sum,
/// difference or draw.
pub fn is_unbounded(x: f64) -> bool {
    x == UNBOUNDED_LIFE_H
}

/// A life or safety `x` as the engine writes it: `UNBOUNDED_LIFE_H` where it has no finite
/// bound (∞ from no damage or no load, or beyond the largest double), else `x`.
pub fn bounded(x: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        UNBOUNDED_LIFE_H
    }
}

/// Rating life of the crank bearing over a scene's sweep (ISO 281 with a varying load).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BearingLife {
    /// P = (mean of Fb^p over the loaded period)^(1/p), N.
    pub equivalent_load_n: f64,
    /// L10h, hours; `None` without an input speed; `UNBOUNDED_LIFE_H` when it has no finite
    /// bound (P = 0, or beyond the largest double).
    pub life_h: Option<f64>,
}

impl BearingLife {
    /// Whether the life is unbounded (`UNBOUNDED_LIFE_H`): no load, or beyond every double.
    pub fn is_unbounded(&self) -> bool {
        self.life_h.is_some_and(is_unbounded)
    }
}

/// Friction losses, efficiency and heat over a scene's crank angles (`Effect::Efficiency`,
/// MODEL.md "Friction, efficiency and heat"). Losses are per unit input speed, N·mm/rad (the
/// power at ω = 1 rad/s, N·mm/s): the scene's are the reducer's (every disc's contacts and the
/// input's drag once), a disc's its own contacts' (no drag).
#[derive(Debug, Clone, PartialEq)]
pub struct EfficiencyCurves {
    /// The model whose forces the losses are computed from.
    pub model: FrictionModel,
    /// Each path's loss at each crank angle, N·mm/rad, `[angle]`.
    pub loss_nmm: Vec<PathLosses>,
    /// Their means over the crank angles, N·mm/rad.
    pub mean_loss_nmm: PathLosses,
    /// ω, the input speed, rad/s (`input_speed_rpm`·2π/60), when the scene has one: the losses
    /// in watts are `mean_loss_nmm`·ω·1e-3.
    pub input_speed_rad_s: Option<f64>,
    /// The reducer's figures; `None` in a disc's curves.
    pub reducer: Option<ReducerEfficiency>,
}

/// The reducer's efficiency, input torque and temperature over a scene (MODEL.md "Friction,
/// efficiency and heat").
#[derive(Debug, Clone, PartialEq)]
pub struct ReducerEfficiency {
    /// The side that drives, from the sign of T, and P per unit input speed, |T|/nc, N·mm/rad
    /// (T the scene's output torque): the power through the output flange, leaving it with the
    /// input driving, entering with the output.
    pub flow: PowerFlow,
    /// η(φ) of the power that flows at each crank angle, `[angle]` (`model::power_flow`):
    /// P/(P + loss(φ)) with the input driving, (P − loss(φ))/P with the output.
    pub efficiency: Vec<f64>,
    /// The same at the mean loss: the mean of the losses, not of η; ≤ 0 where the output
    /// drives and the mean loss takes all it brings (the reducer self-locks).
    pub mean_efficiency: f64,
    /// Whether the output drives and the mean loss takes all the power it brings: the scene
    /// self-locks (`model::power_flow::PowerFlow::self_locks`).
    pub self_locks: bool,
    /// The input torque at each crank angle, N·mm, `[angle]`: the loss model's T/nc + loss,
    /// the coupled model's from the crank's balance (with its ripple).
    pub input_torque_nmm: Vec<f64>,
    /// The crank angles (rad) where the output drives (T < 0) and the input must still push
    /// (T_in ≥ 0): the friction holds the reducer, it self-locks there; empty when T ≥ 0.
    pub self_locking_crank_rad: Vec<f64>,
    /// The steady temperature ambient + P/(h·A), °C, with `reducer.thermal` and a speed.
    pub temperature_c: Option<f64>,
}

impl EfficiencyCurves {
    /// The mean power lost on each path, W, with a speed: `mean_loss_nmm`·ω·1e-3.
    pub fn power_loss_w(&self) -> Option<PathLosses> {
        self.input_speed_rad_s
            .map(|w| self.mean_loss_nmm.scaled(crate::units::w(w)))
    }
}

/// The mean efficiency of a scene solved again at other output torques (the review's curve,
/// `engine::efficiency::torque_curve`).
#[derive(Debug, Clone, PartialEq)]
pub struct TorqueCurve {
    /// The output torques, N·mm, rising.
    pub torque_nmm: Vec<f64>,
    /// The mean efficiency at each.
    pub mean_efficiency: Vec<f64>,
}

/// Everything computed for one scene, the same shape for any number of discs: the reducer's
/// curves over all its discs, and each disc's own results (one disc is `discs.len() == 1`).
/// A quantity that was not computed is `None`.
#[derive(Debug, Clone)]
pub struct SceneResult {
    /// The scene's name.
    pub name: String,
    /// The scene's crank angles φ, rad (`Scene::crank_rad`).
    pub crank_rad: Vec<f64>,
    /// The reducer's curves over all its discs (all `None` in a duty-cycle scene).
    pub reducer: ReducerResult,
    /// Each disc's results, disc k at the crank phase 2πk/N (MODEL.md "Several discs"), at
    /// the scene's crank angles: at least one in a run scene; none in a duty-cycle scene
    /// (each bin has its own).
    pub discs: Vec<DiscResult>,
    /// A duty-cycle scene's bins and what the cycle gives (`engine::duty_cycle`); the scene's
    /// own curves are then empty (each bin has its own), and a scalar of the registry is the
    /// worst over the bins (`Quantity::scalar`). `None` for an ordinary scene.
    pub duty: Option<Box<DutyCycle>>,
}

impl SceneResult {
    /// The disc of a one-disc scene, whose curves are written and drawn as the scene's own;
    /// `None` with several discs (each is named, `disc k`) or none (a duty cycle). With
    /// `names_discs`, what the results' presentation asks of the number of discs.
    pub fn only_disc(&self) -> Option<&DiscResult> {
        match self.discs.as_slice() {
            [one] => Some(one),
            _ => None,
        }
    }

    /// Whether the discs are named (`disc k`) in what is said of them: with several discs.
    pub fn names_discs(&self) -> bool {
        self.discs.len() > 1
    }
}

/// The reducer's results over all its discs (MODEL.md "Several discs"): what no single disc has.
#[derive(Debug, Clone, Default)]
pub struct ReducerResult {
    /// TE and ratio, with the rollers modelled: with several discs from the common output lag
    /// γ (`equilibrium::discs_sweep`).
    pub transmission: Option<Transmission>,
    /// The output pins' stresses (`Effect::Strength` with a pin support): every disc's force
    /// on each pin.
    pub pin_stress: Option<super::strength::PinStress>,
    /// Friction losses, efficiency and heat (`Effect::Efficiency`): every disc's contacts and
    /// the input's drag, with the reducer's figures (`EfficiencyCurves::reducer`).
    pub efficiency: Option<EfficiencyCurves>,
    /// A torsion scene's curves and figures (`Effect::Torsion`).
    pub torsion: Option<TorsionCurves>,
}

/// One disc's results over the scene's crank angles.
#[derive(Debug, Clone)]
pub struct DiscResult {
    /// The unloaded gaps at the ideal pose (`Effect::Clearance`).
    pub clearance: Option<ClearanceSweep>,
    /// The loaded curves (none computed: every part `None`).
    pub loaded: LoadedSweep,
    /// The crank bearing's rating life, when the design has a `crank_bearing` and the scene
    /// computes the bearing force over whole loaded periods.
    pub bearing_life: Option<BearingLife>,
    /// The friction losses of the disc's own contacts (no drag, no reducer figures), with
    /// several discs; `None` for one disc (its losses are the reducer's but for the drag).
    pub efficiency: Option<EfficiencyCurves>,
}

/// A duty cycle's results (`engine::duty_cycle`, ISO 281 with the Palmgren–Miner rule).
#[derive(Debug, Clone)]
pub struct DutyCycle {
    /// Each bin as given and its run as a loaded scene, in the spec's order.
    pub bins: Vec<DutyBinResult>,
    /// T_eq = (Σ sᵢ·nᵢ·|Tᵢ|³ / Σ sᵢ·nᵢ)^(1/3), N·mm: the root-mean-cube output torque weighted
    /// by the revolutions each bin turns (sᵢ the time share, nᵢ the input speed).
    pub equivalent_torque_nmm: f64,
    /// n_m = Σ sᵢ·nᵢ, rpm: the time-weighted mean input speed.
    pub mean_speed_rpm: f64,
    /// Each disc's crank bearing under the cycle (one entry per disc), when the design has a
    /// `crank_bearing` and the crank range spans whole loaded periods; else empty.
    pub life: Vec<BearingLife>,
    /// Σ sᵢ·Dᵢ / Σ sᵢ·Eᵢ: the mean efficiency weighted by energy, with `efficiency` (Dᵢ and
    /// Eᵢ the bin's energy delivered and entering as its power flows, `engine::duty_cycle`).
    pub mean_efficiency: Option<f64>,
    /// Each disc's and its rollers' contact fatigue under the cycle (`engine::duty_fatigue`),
    /// with an S–N law and whole periods in every bin; else empty.
    pub contact_fatigue: Vec<super::strength::DutyFatigue>,
}

/// One bin of a duty cycle and its run.
#[derive(Debug, Clone)]
pub struct DutyBinResult {
    /// The bin as given.
    pub bin: crate::model::DutyBin,
    /// The scene run at the bin's torque and speed (named `<scene> bin i`).
    pub result: SceneResult,
}

impl DutyCycle {
    /// sᵢ·nᵢ / Σ sⱼ·nⱼ: the share of the cycle's revolutions that bin `b` turns.
    pub fn revolution_share(&self, b: &DutyBinResult) -> f64 {
        b.bin.revolution_weight_rpm() / self.mean_speed_rpm
    }

    /// The reducer's life under the cycle: the shortest of its discs' (each disc has its own
    /// crank bearing), with the disc; `None` when not rated.
    pub fn shortest_life(&self) -> Option<(usize, BearingLife)> {
        self.life
            .iter()
            .copied()
            .enumerate()
            .filter(|(_, b)| b.life_h.is_some())
            .min_by(|a, b| a.1.life_h.partial_cmp(&b.1.life_h).unwrap())
    }
}
