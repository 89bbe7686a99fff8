//! The lean first-order sweep: first-order geometry, the paper's linear law, a rigid bearing.
//!
//! The same closed forms as the general solve (`Rollers::first_order_terms`,
//! `Pins::first_order_at`, `solve::piecewise_linear_root_near`, MODEL.md "First order"), but
//! computing only what the curves record: per angle the lags, the forces, Hertz pressure and
//! half-width of the rollers in contact, the bearing force and the residual of Eqs. 12–14. No
//! per-roller state (normal, contact point, locus parameter) is built for a roller out of
//! contact. An angle the closed form cannot settle by itself (zero torque, where the answer is
//! the touching limit T → 0⁺; a root whose balance steps over the torque by round-off, as at
//! 1e-6 N·m) is left to the general `angle::solve_into`, which handles both.
//!
//! Per roller i at crank φ (u_i its unit direction, e_φ = (cos φ, sin φ)):
//!   cos φi = u_i·e_φ, sin φi = e_φ × u_i, (g_i, l_i, 1/S_i) from `first_order::Coefficients`,
//!   F_i = k·max(0, l_i·β − g_i), force on the disc −F_i·n_i with n_i = (u_i − K1·e_φ)/S_i,
//!   acting at Rp·u_i − r_rp·n_i;
//!   curvature at the contact from cos(nc·t_i) = cos(φi + nc·(β + Δδ)) (t_i = 2πi/np + φ/nc −
//!   β − Δδ, the contact's locus parameter; `Mesh::foot_guess`).
//! Per pin j (w_j its unit direction, ψ = −φ/nc + β the disc rotation):
//!   a_j = rw·(R(ψ)·w_j) × (−e_φ), gap c − βo·a_j, force F_j·(−e_φ) at the hole wall
//!   O + rw·R(ψ)·w_j − R_h·e_φ.
//!
//! The root of each linear balance is first sought on the active set of the last angle the
//! kernel settled: with A = Σ k·l² and B = Σ k·l·g over that set, x = (T + B)/A is the root when
//! the set of contacts at x is that set (the balance is then A·x − B = T exactly on it). It
//! usually is from one crank step to the next; when it is not, `piecewise_linear_root_near`
//! starts from the warm-start guess.
//!
//! Most rollers are far from contact at any angle. After the first angle of a chunk settles,
//! `screen` proves from bounds on the closing's rates (`Coefficients::closing_rate_bounds`)
//! which rollers stay out of contact over the chunk's remaining angles and over lags near the
//! one just found; only the others are evaluated while the lag stays in that range (checked at
//! every angle, else the angle is solved again on every roller and the next angle that settles
//! screens again, up to `SCREENS` times a chunk).

use super::loaded::Model;
use super::pins::Pins;
use super::residual::BalanceSums;
use super::rollers::Rollers;
use super::solve::piecewise_linear_root_near;
use crate::contact::hertz_line::HertzFactors;
use crate::geometry::{sin_cos, unit, NearbySinCos, Vec2};
use crate::model::{ContactLaw, GeometryMode};

/// The closed-form sweep of one model, when the model is one it applies to.
#[derive(Debug)]
pub struct FirstOrderSweep<'a> {
    model: &'a Model,
    /// The torque the rollers and pins balance, N·mm: the model's, or a disc's share of it
    /// (`set_torque`, several discs).
    torque_nmm: f64,
    rollers: &'a Rollers,
    pins: Option<(&'a Pins, f64)>,
    /// The Hertz pressure and width factors of the rollers' contacts ([`contact::hertz_line`](crate::contact::hertz_line)).
    hertz: HertzFactors,
    /// The roller directions u_i and the pin directions w_j as x and y columns, so that the
    /// per-angle loops over them vectorise.
    roller_units: Columns,
    pin_units: Columns,
    /// The gap of every pin at zero output lag: the hole clearance c, mm.
    pin_gaps: Vec<f64>,
}

/// x and y components of a set of unit vectors.
#[derive(Debug, Default)]
struct Columns {
    x: Vec<f64>,
    y: Vec<f64>,
}

impl Columns {
    fn of(v: &[Vec2]) -> Self {
        Columns {
            x: v.iter().map(|u| u.x).collect(),
            y: v.iter().map(|u| u.y).collect(),
        }
    }
}

/// The per-roller and per-pin entries the curves record at one angle, written in place: entry
/// `k` of column i (roller or pin i) of each. Only the entries of rollers and pins in contact
/// are written: the others must be zero already (a sweep's columns start at zero, and each
/// entry belongs to one angle).
#[derive(Debug)]
pub struct Row<'r, 'c> {
    pub k: usize,
    pub roller_force_n: &'r mut [&'c mut [f64]],
    pub pressure_mpa: &'r mut [&'c mut [f64]],
    pub half_width_mm: &'r mut [&'c mut [f64]],
    pub pin_force_n: &'r mut [&'c mut [f64]],
}

/// The rest of what the curves record at one angle (engine units; `bearing_n` is zero when
/// the bearing is not modelled).
#[derive(Debug, Clone, Copy, Default)]
pub struct Summary {
    pub lag_rad: f64,
    pub output_lag_rad: f64,
    pub contacts: usize,
    pub bearing_n: Vec2,
    pub residual: f64,
    /// d(β + βo)/dT at the solution, rad/(N·mm): 1/Σk·l² over the rollers in contact plus
    /// 1/Σk·a² over the pins in contact (each balance is linear on its contact set; the pins'
    /// arms turning with β is left out, a change of the arms by ~β·a ≪ a). Infinite without
    /// a contact. What several discs' Newton on their shares weighs each disc by.
    pub compliance_rad_per_nmm: f64,
}

/// Most rollers and pins the kernel takes: it keeps an active set as a bit mask.
const MAX_TERMS: usize = 64;

/// Scratch space reused over the chunks a worker takes (`restart` between them), and the state
/// carried from one angle to the next: the active sets of the last angle settled, the disc
/// rotation's reference, the screen. Fixed-size columns, so that the loops over them vectorise
/// without aliasing checks.
#[derive(Debug)]
pub struct Scratch {
    /// Per roller: cos φi, sin φi, 1/S_i, g_i, l_i.
    cos: [f64; MAX_TERMS],
    sin: [f64; MAX_TERMS],
    inverse_s: [f64; MAX_TERMS],
    gap: [f64; MAX_TERMS],
    arm: [f64; MAX_TERMS],
    /// Per pin: the arm a_j.
    pin_arm: [f64; MAX_TERMS],
    /// Forces of the rollers and of the pins at the root, N.
    force: [f64; MAX_TERMS],
    pin_force: [f64; MAX_TERMS],
    root: RootScratch,
    /// Contacts (bit i: term i has a negative gap) of the rollers and the pins at the last
    /// angle this kernel settled; empty before the first and after a fall-back.
    last: (u64, u64),
    /// sin and cos of the disc rotation ψ, which moves little from one angle to the next.
    disc_rotation: NearbySinCos,
    /// The rollers that may touch over the angles ahead, when screened (`FirstOrderSweep::screen`).
    screen: Option<Screen>,
    /// Screens still allowed in this sequence of angles (a screen that keeps failing its lag
    /// check is not worth rebuilding at every angle).
    screens_left: u32,
}

/// Rollers proven out of contact over a range of crank angles and lags: the others
/// (`candidates`) are the only ones evaluated while the lag stays within `lag_reach` of
/// `lag_rad`.
#[derive(Debug, Clone, Copy)]
struct Screen {
    candidates: u64,
    lag_rad: f64,
    lag_reach: f64,
}

/// Screens per sequence of angles (`Scratch::restart`).
const SCREENS: u32 = 4;

/// The range of lags a screen holds for: this share of the lag it was built at, plus a floor.
/// A choice of reach only (wider keeps more rollers in, narrower rebuilds sooner): every
/// angle checks that its lag is in range.
const SCREEN_LAG_SHARE: f64 = 0.05;
const SCREEN_LAG_FLOOR_RAD: f64 = 1e-6;

/// The least closing, mm, a roller must provably keep to be left out: far above the
/// round-off of a closing (~1e-15 mm), so that the roller would be out of contact in the
/// computed closing too.
const SCREEN_MARGIN_MM: f64 = 1e-9;

impl Default for Scratch {
    fn default() -> Self {
        let zeros = [0.0; MAX_TERMS];
        Scratch {
            cos: zeros,
            sin: zeros,
            inverse_s: zeros,
            gap: zeros,
            arm: zeros,
            pin_arm: zeros,
            force: zeros,
            pin_force: zeros,
            root: RootScratch::default(),
            last: (0, 0),
            disc_rotation: NearbySinCos::default(),
            screen: None,
            screens_left: SCREENS,
        }
    }
}

/// (g, l) pairs and breakpoints for `piecewise_linear_root_near`.
#[derive(Debug, Default)]
struct RootScratch {
    terms: Vec<(f64, f64)>,
    events: Vec<(f64, f64, f64)>,
}

impl Scratch {
    /// Forget the last active sets (the next angle starts from its warm-start guess).
    pub fn forget(&mut self) {
        self.last = (0, 0);
        self.screen = None;
    }

    /// Whether the rollers are screened (`FirstOrderSweep::screen`).
    pub fn screened(&self) -> bool {
        self.screen.is_some()
    }

    /// Start a new sequence of angles: forget the active sets and the disc rotation's
    /// reference, so that what follows does not depend on what came before (the columns are
    /// always written before they are read).
    pub fn restart(&mut self) {
        self.forget();
        self.disc_rotation = NearbySinCos::default();
        self.screens_left = SCREENS;
    }
}

/// A linear balance Σ k·max(0, l·x − g)·l = T over terms (g, l) given as columns, and the
/// column its forces are written to.
struct Balance<'s> {
    stiffness: f64,
    gap: &'s [f64],
    arm: &'s [f64],
    force: &'s mut [f64],
    /// The terms that may be in contact (bit i); the others are out of contact, with zero
    /// force already in `force`.
    candidates: u64,
}

impl<'a> FirstOrderSweep<'a> {
    /// Whether the lean sweep applies to `model` (`new` builds it): first-order geometry, the
    /// paper's linear law, a rigid bearing, rollers, and at most 64 rollers and pins with a
    /// linear stiffness; a uniform face (a crowned or tilted one's stiffness varies); no
    /// friction losses to record (`Model::losses`: they need each contact's point, which the
    /// kernel does not keep).
    pub fn applies(model: &Model) -> bool {
        let Some(r) = model.rollers.as_ref() else {
            return false;
        };
        let pins_apply = model.pins.as_ref().is_none_or(|p| {
            p.base.len() <= MAX_TERMS && p.linear_stiffness().is_some() && !p.couples_discs()
        });
        r.geometry == GeometryMode::FirstOrder
            && r.law == ContactLaw::PaperLinear
            && r.face().is_none()
            && model.bearing_stiffness_n_per_mm.is_none()
            && model.coupled().is_none()
            && model.losses.is_none()
            && r.units.len() <= MAX_TERMS
            && pins_apply
    }

    /// The lean sweep of `model`, or `None` when the model needs the general solve: exact
    /// geometry, the logarithmic law, a compliant bearing, no rollers, or more than 64 rollers
    /// or pins (the kernel keeps an active set as a bit mask).
    pub fn new(model: &'a Model) -> Option<Self> {
        if !Self::applies(model) {
            return None;
        }
        let r = model.rollers.as_ref()?;
        let pins = match &model.pins {
            Some(p) => Some((p, p.linear_stiffness()?)),
            None => None,
        };
        Some(FirstOrderSweep {
            model,
            torque_nmm: model.torque_nmm,
            rollers: r,
            pins,
            hertz: HertzFactors::of(&r.materials),
            roller_units: Columns::of(&r.units),
            pin_units: pins.map_or_else(Columns::default, |(p, _)| Columns::of(&p.base)),
            pin_gaps: pins.map_or_else(Vec::new, |(p, _)| vec![p.clearance_mm; p.base.len()]),
        })
    }

    /// Balance `torque_nmm` (a disc's share) instead of the model's torque from now on.
    pub fn set_torque(&mut self, torque_nmm: f64) {
        self.torque_nmm = torque_nmm;
    }

    /// Solve crank φ, with (cos φ, sin φ) given, writing `row`. `guess` gives the warm-start
    /// lags (β, βo) when the last angle's active sets do not settle this one. `None` leaves
    /// the angle to the general solve (see the module documentation); `row` is then partly
    /// written and `scratch` has forgotten its active sets. (The direction comes as a pair of
    /// numbers, which are passed in registers: a `Vec2` goes through memory, where loading
    /// both halves at once stalls on the two stores that wrote them.)
    pub fn solve(
        &self,
        crank_rad: f64,
        (cos, sin): (f64, f64),
        guess: impl Fn() -> (f64, f64),
        scratch: &mut Scratch,
        row: &mut Row<'_, '_>,
    ) -> Option<Summary> {
        let e_phi = Vec2::new(cos, sin);
        let summary = self.try_solve(crank_rad, e_phi, guess, scratch, row);
        if summary.is_none() {
            scratch.forget();
        }
        summary
    }

    fn try_solve(
        &self,
        crank_rad: f64,
        e_phi: Vec2,
        guess: impl Fn() -> (f64, f64),
        scratch: &mut Scratch,
        row: &mut Row<'_, '_>,
    ) -> Option<Summary> {
        if self.torque_nmm == 0.0 {
            return None;
        }
        let mut sums = BalanceSums::default();
        let (lag, mask, roller_stiffness) = self.rollers_at(e_phi, &guess, scratch)?;
        scratch.last.0 = mask;
        self.roller_contacts(e_phi, lag, mask, scratch, row, &mut sums);
        let mut output_lag = 0.0;
        let mut compliance = 1.0 / roller_stiffness;
        if let Some((p, k)) = self.pins {
            let psi = -crank_rad / self.model.teeth as f64 + lag;
            let pins = self.pins_at(p, k, (e_phi, psi), &guess, scratch, row, &mut sums)?;
            output_lag = pins.0;
            compliance += 1.0 / pins.1;
        }
        let mut summary = Summary {
            lag_rad: lag,
            output_lag_rad: output_lag,
            contacts: mask.count_ones() as usize,
            compliance_rad_per_nmm: compliance,
            ..Summary::default()
        };
        if self.model.bearing {
            // The contacts' and the disc's centrifugal reaction (`Effect::Inertia`).
            let centrifugal = self.model.centrifugal_n(e_phi);
            summary.bearing_n = -sums.net_force() - centrifugal;
            let centre = e_phi * self.model.eccentricity_mm;
            summary.residual = sums.relative(self.model, centre, summary.bearing_n + centrifugal);
        }
        let finite = lag.is_finite() && output_lag.is_finite() && summary.residual.is_finite();
        finite.then_some(summary)
    }

    /// The rollers' lag, contacts and balance slope Σk·l² (`settle`): on the screened
    /// candidates while a screen holds (and the lag stays in its range), else on every roller.
    fn rollers_at(
        &self,
        e_phi: Vec2,
        guess: &impl Fn() -> (f64, f64),
        scratch: &mut Scratch,
    ) -> Option<(f64, u64, f64)> {
        let n = self.roller_units.x.len();
        if let Some(screen) = scratch.screen {
            self.candidate_terms(e_phi, screen.candidates, scratch);
            let settled = self.settle_rollers(screen.candidates, guess, scratch);
            if let Some(settled) = settled {
                if (settled.0 - screen.lag_rad).abs() <= screen.lag_reach {
                    return Some(settled);
                }
            }
            // No root among the candidates, or one outside the lags the screen holds for:
            // every roller, from the start.
            scratch.screen = None;
        }
        self.roller_terms(e_phi, scratch);
        self.settle_rollers(all(n), guess, scratch)
    }

    #[inline(always)]
    fn settle_rollers(
        &self,
        candidates: u64,
        guess: &impl Fn() -> (f64, f64),
        scratch: &mut Scratch,
    ) -> Option<(f64, u64, f64)> {
        let n = self.roller_units.x.len();
        self.settle(
            Balance {
                stiffness: self.rollers.linear_stiffness(),
                gap: &scratch.gap[..n],
                arm: &scratch.arm[..n],
                force: &mut scratch.force[..n],
                candidates,
            },
            scratch.last.0,
            || guess().0,
            &mut scratch.root,
        )
    }

    /// `roller_terms` for the rollers in `candidates` only.
    fn candidate_terms(&self, e_phi: Vec2, candidates: u64, scratch: &mut Scratch) {
        for i in bits(candidates) {
            self.roller_term(i, e_phi, scratch);
        }
    }

    /// Screen the rollers for the crank angles ahead (`crank_ahead`, after an angle that
    /// settled at `lag_rad`): a roller whose closing h = g − l·β provably stays positive over
    /// those angles and over lags within `lag_reach` of `lag_rad` is left out until the lag
    /// leaves that range. With φm the middle of the angles and r their reach from it, h at
    /// (φm, `lag_rad`) less |∂h/∂φ|·r (bounded at `lag_rad`, over the window's least S) and
    /// |∂h/∂β|·`lag_reach` (`first_order::Coefficients::closing_rate_bounds`, the two legs of
    /// the mean value theorem) must exceed `SCREEN_MARGIN_MM`. Rollers left out get g = MAX,
    /// l = 0 and zero force, which every later step reads as out of contact.
    pub fn screen(&self, crank_ahead: &[f64], lag_rad: f64, scratch: &mut Scratch) {
        if scratch.screens_left == 0 || crank_ahead.is_empty() {
            return;
        }
        scratch.screens_left -= 1;
        let (lo, hi) = crate::numeric::extent(crank_ahead.iter().copied());
        let middle = 0.5 * (lo + hi);
        let reach = (hi - middle).max(middle - lo);
        self.roller_terms(unit(middle), scratch);
        let lag_reach = SCREEN_LAG_SHARE * lag_rad.abs() + SCREEN_LAG_FLOOR_RAD;
        let coefficients = &self.rollers.first_order;
        let n = self.roller_units.x.len();
        let mut candidates = 0u64;
        for i in 0..n {
            let closing = scratch.gap[i] - scratch.arm[i] * lag_rad;
            let least_s = coefficients.least_s_within((scratch.cos[i], scratch.sin[i]), reach);
            let (per_crank, per_lag) = coefficients.closing_rate_bounds(least_s, lag_rad);
            let lowest = closing - per_crank * reach - per_lag * lag_reach;
            if lowest > SCREEN_MARGIN_MM {
                (scratch.gap[i], scratch.arm[i], scratch.force[i]) = (f64::MAX, 0.0, 0.0);
            } else {
                candidates |= 1 << i;
            }
        }
        scratch.screen = (candidates != all(n)).then_some(Screen {
            candidates,
            lag_rad,
            lag_reach,
        });
    }

    /// cos φi, sin φi, 1/S_i, g_i and l_i of every roller into `scratch`, in one loop over
    /// columns (no branches, so it vectorises).
    fn roller_terms(&self, e_phi: Vec2, scratch: &mut Scratch) {
        for i in 0..self.roller_units.x.len() {
            self.roller_term(i, e_phi, scratch);
        }
    }

    /// cos φi, sin φi, 1/S_i, g_i and l_i of roller i into `scratch`.
    #[inline(always)]
    fn roller_term(&self, i: usize, e_phi: Vec2, scratch: &mut Scratch) {
        let u = &self.roller_units;
        let (c, s) = (
            u.x[i] * e_phi.x + u.y[i] * e_phi.y,
            e_phi.x * u.y[i] - e_phi.y * u.x[i],
        );
        let (g, l, inverse_s) = self.rollers.first_order.with_inverse_s(c, s);
        scratch.cos[i] = c;
        scratch.sin[i] = s;
        scratch.inverse_s[i] = inverse_s;
        scratch.gap[i] = g;
        scratch.arm[i] = l;
    }

    /// The rollers in `mask` (in contact at lag β, forces in `scratch.force`): their forces
    /// into `row` and `sums`, and their Hertz peak pressure and half-width into `row`
    /// ([`contact::hertz_line`](crate::contact::hertz_line); the entries of rollers out of contact stay zero), with
    /// 1/R* = max(κ + 1/r_rp, 1/Rp) as in `Rollers::line_contact` and κ the disc curvature at
    /// the roller's locus parameter.
    #[inline(always)]
    fn roller_contacts(
        &self,
        e_phi: Vec2,
        lag: f64,
        mask: u64,
        scratch: &Scratch,
        row: &mut Row<'_, '_>,
        sums: &mut BalanceSums,
    ) {
        let r = self.rollers;
        let profile = &r.mesh.profile;
        // The profile rotation Δδ turns the contact like a lag (`Mesh::foot_guess`).
        let (sin_nc_lag, cos_nc_lag) =
            sin_cos(self.model.teeth as f64 * (lag + profile.rotation_rad));
        let d = &r.design;
        let k1_e = r.first_order.k1 * e_phi;
        let k = row.k;
        for i in bits(mask) {
            let force = scratch.force[i];
            row.roller_force_n[i][k] = force;
            let normal = (r.units[i] - k1_e) * scratch.inverse_s[i];
            let point = r.centres[i] - d.roller_radius_mm * normal;
            sums.roller(point, force, -force * normal, force * scratch.arm[i]);
            let (c, s) = (scratch.cos[i], scratch.sin[i]);
            let kappa = profile.curvature_at(c * cos_nc_lag - s * sin_nc_lag);
            let h = self.hertz.at(force, r.inverse_effective_radius(kappa));
            row.pressure_mpa[i][k] = h.peak_pressure_mpa;
            row.half_width_mm[i][k] = h.half_width_mm;
        }
    }

    /// βo with Σ F·a = T at disc rotation ψ and the pins' stiffness Σk·a² over those in
    /// contact (N·mm/rad), the pin forces into `row` and those in contact into `sums`.
    #[allow(clippy::too_many_arguments)]
    fn pins_at(
        &self,
        p: &Pins,
        k: f64,
        (e_phi, psi): (Vec2, f64),
        guess: &impl Fn() -> (f64, f64),
        scratch: &mut Scratch,
        row: &mut Row<'_, '_>,
        sums: &mut BalanceSums,
    ) -> Option<(f64, f64)> {
        let (s, c) = scratch.disc_rotation.sin_cos(psi);
        let w = &self.pin_units;
        let m = w.x.len();
        let rw = p.circle_radius_mm;
        // a_j = (rw·R(ψ)·w_j) × (−e_φ) = rw·(x_j·P + y_j·Q) with w_j = (x_j, y_j),
        // P = sin ψ·e_x − cos ψ·e_y and Q = cos ψ·e_x + sin ψ·e_y.
        let (sp, sq) = (s * e_phi.x - c * e_phi.y, c * e_phi.x + s * e_phi.y);
        for ((arm, &x), &y) in scratch.pin_arm[..m].iter_mut().zip(&w.x).zip(&w.y) {
            *arm = (x * sp + y * sq) * rw;
        }
        let (lag, mask, stiffness) = self.settle(
            Balance {
                stiffness: k,
                gap: &self.pin_gaps,
                arm: &scratch.pin_arm[..m],
                force: &mut scratch.pin_force[..m],
                candidates: all(m),
            },
            scratch.last.1,
            || guess().1,
            &mut scratch.root,
        )?;
        scratch.last.1 = mask;
        let direction = -e_phi;
        let wall = e_phi * p.eccentricity_mm + direction * p.hole_radius_mm;
        for j in bits(mask) {
            let force = scratch.pin_force[j];
            row.pin_force_n[j][row.k] = force;
            let point = wall + Vec2::new(c * w.x[j] - s * w.y[j], s * w.x[j] + c * w.y[j]) * rw;
            sums.pin(point, force, force * direction, force * scratch.pin_arm[j]);
        }
        Some((lag, stiffness))
    }

    /// The root x of the linear balance and the forces there into its force column,
    /// with the set of contacts at x and the balance's slope there, Σk·l² over that set. First the Newton step on the active set `last` (see the
    /// module documentation), then `piecewise_linear_root_near` from `guess`. `None` when the
    /// forces miss the torque by more than the solver tolerance,
    /// |Σ F·l − T| > rel_tol·max(|T|, Σ |F·l|) (the round-off of a tiny torque, left to the
    /// general solve's straddle).
    fn settle(
        &self,
        balance: Balance<'_>,
        last: u64,
        guess: impl FnOnce() -> f64,
        root: &mut RootScratch,
    ) -> Option<(f64, u64, f64)> {
        let (torque, rel_tol) = (self.torque_nmm, self.model.settings.rel_tol);
        let settled = |(moment, scale): (f64, f64)| {
            (moment - torque).abs() <= rel_tol * torque.abs().max(scale)
        };
        let Balance {
            stiffness: k,
            gap,
            arm,
            force,
            candidates,
        } = balance;
        let (mut a, mut b) = (0.0, 0.0);
        for i in bits(last) {
            a += k * arm[i] * arm[i];
            b += k * arm[i] * gap[i];
        }
        if a > 0.0 {
            let x = (torque + b) / a;
            let (moment, scale, mask) = linear_forces(k, (gap, arm), x, force, candidates);
            if mask == last {
                return settled((moment, scale)).then_some((x, mask, a));
            }
        }
        root.terms.clear();
        root.terms
            .extend(gap.iter().zip(arm).map(|(&g, &l)| (g, l)));
        let x = piecewise_linear_root_near(k, &root.terms, torque, guess(), &mut root.events)?;
        let (moment, scale, mask) = linear_forces(k, (gap, arm), x, force, candidates);
        let slope = bits(mask).map(|i| k * arm[i] * arm[i]).sum();
        settled((moment, scale)).then_some((x, mask, slope))
    }
}

/// Linear-law forces k·max(0, l·x − g) of the `candidates` among the terms (g, l) at x into
/// `force` (the others keep their zero force); returns the moment Σ F·l, its scale Σ |F·l| and
/// the contacts (bit i: g − l·x < 0).
#[inline(always)]
fn linear_forces(
    k: f64,
    (gap, arm): (&[f64], &[f64]),
    x: f64,
    force: &mut [f64],
    candidates: u64,
) -> (f64, f64, u64) {
    let mut mask = 0u64;
    if candidates == all(gap.len()) {
        for (i, ((&g, &l), f)) in gap.iter().zip(arm).zip(force.iter_mut()).enumerate() {
            let closing = g - l * x;
            *f = if closing < 0.0 { -closing * k } else { 0.0 };
            mask |= u64::from(closing < 0.0) << i;
        }
    } else {
        for i in bits(candidates) {
            let closing = gap[i] - arm[i] * x;
            force[i] = if closing < 0.0 { -closing * k } else { 0.0 };
            mask |= u64::from(closing < 0.0) << i;
        }
    }
    // The sums over the contacts only (in index order): the other terms would add exact zeros.
    let (mut moment, mut scale) = (0.0, 0.0);
    for i in bits(mask) {
        let m = force[i] * arm[i];
        moment += m;
        scale += m.abs();
    }
    (moment, scale, mask)
}

/// The mask of n terms (n ≤ 64).
fn all(n: usize) -> u64 {
    if n >= 64 {
        u64::MAX
    } else {
        (1 << n) - 1
    }
}

/// The set bits of a mask, lowest first.
#[inline]
fn bits(mut mask: u64) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        let i = mask.trailing_zeros() as usize;
        mask &= mask.wrapping_sub(1);
        (i < 64).then_some(i)
    })
}

#[cfg(test)]
mod tests {
    use super::{all, bits, FirstOrderSweep, Scratch};
    use crate::equilibrium::loaded::Model;
    use crate::model::{ContactLaw, GeometryMode, Modification};
    use crate::spec::{self};
    use proptest::prelude::*;

    /// Each column as a slice (a row of one angle for `Row`).
    fn slices(columns: &mut [Vec<f64>]) -> Vec<&mut [f64]> {
        columns.iter_mut().map(|v| v.as_mut_slice()).collect()
    }

    /// An angle whose candidates have no root, or whose root falls outside the lags the screen
    /// holds for, is solved on every roller: a screen built at the opposite lag (which keeps
    /// the wrong flanks) and one that leaves out a contact (so that the root of the others lies
    /// beyond its range) change nothing.
    #[test]
    fn an_angle_the_screen_does_not_hold_for_is_solved_on_every_roller() {
        let s = spec::load("specs/paper.yaml").unwrap();
        let mut scene = s.scenes.iter().find(|c| c.name == "rated").unwrap().clone();
        scene.geometry = GeometryMode::FirstOrder;
        let model = Model::new(
            &s.design,
            &s.modification,
            &scene,
            &crate::model::Plan::of("rated", &[crate::model::Effect::Bearing]),
        );
        let kernel = FirstOrderSweep::new(&model).unwrap();
        let n = kernel.rollers.units.len();
        let column = || vec![vec![0.0]; n];
        for k in 0..12 {
            let phi = 0.05 * k as f64;
            let e = crate::geometry::unit(phi);
            let solve = |scratch: &mut Scratch| {
                let (mut f, mut p, mut w) = (column(), column(), column());
                let mut pf = vec![vec![0.0]; kernel.pin_units.x.len()];
                let mut row = super::Row {
                    k: 0,
                    roller_force_n: &mut slices(&mut f),
                    pressure_mpa: &mut slices(&mut p),
                    half_width_mm: &mut slices(&mut w),
                    pin_force_n: &mut slices(&mut pf),
                };
                let summary = kernel
                    .solve(phi, (e.x, e.y), || (0.0, 0.0), scratch, &mut row)
                    .unwrap();
                (summary.lag_rad, summary.output_lag_rad, f)
            };
            let fresh = solve(&mut Scratch::default());
            let mut screened = Scratch::default();
            kernel.screen(&[phi], -fresh.0, &mut screened);
            assert!(screened.screened(), "the opposite lag leaves rollers out");
            assert_eq!(solve(&mut screened), fresh, "crank {phi}, opposite lag");
            // A screen that leaves out all contacts but the first, held for a lag range too
            // narrow for the root the remaining contact gives.
            let contacts: Vec<usize> = (0..n).filter(|&i| fresh.2[i][0] > 0.0).collect();
            assert!(contacts.len() >= 2, "crank {phi}: {contacts:?}");
            let mut narrow = Scratch::default();
            let mut left_out = 0u64;
            for &i in &contacts[1..] {
                (narrow.gap[i], narrow.arm[i], narrow.force[i]) = (f64::MAX, 0.0, 0.0);
                left_out |= 1 << i;
            }
            narrow.screen = Some(super::Screen {
                candidates: all(n) & !left_out,
                lag_rad: fresh.0,
                lag_reach: 1e-12,
            });
            assert_eq!(solve(&mut narrow), fresh, "crank {phi}, narrow screen");
        }
    }

    proptest! {
        /// A screen only leaves out rollers that stay out of contact: at every crank angle it
        /// was built for and at both ends of its range of lags, the closing g − l·β of
        /// each roller left out (the same first-order closed form the kernel evaluates) is
        /// positive. Random modifications, lags, step sizes and chunk lengths.
        #[test]
        fn screened_out_rollers_stay_out_of_contact(
            shift in -0.3f64..0.3,
            equidistant in -0.3f64..0.3,
            rotation in -0.002f64..0.002,
            lag in -0.02f64..0.02,
            start in -3.2f64..3.2,
            step in 1e-5f64..0.02,
            angles in 1usize..64,
        ) {
            let s = spec::load("specs/paper.yaml").unwrap();
            let mut scene = s.scenes.iter().find(|c| c.name == "rated").unwrap().clone();
            scene.geometry = GeometryMode::FirstOrder;
            scene.contact_law = ContactLaw::PaperLinear;
            let modification = Modification { shift_mm: shift, equidistant_mm: equidistant, rotation_rad: rotation };
            let model = Model::new(&s.design, &modification, &scene, &crate::model::Plan::of("rated", &[crate::model::Effect::Bearing]));
            let kernel = FirstOrderSweep::new(&model).unwrap();
            let crank: Vec<f64> = (0..angles).map(|k| start + step * k as f64).collect();
            let mut scratch = Scratch::default();
            kernel.screen(&crank, lag, &mut scratch);
            // Cases where no roller can be left out say nothing about the screen: drawn again.
            prop_assume!(scratch.screen.is_some());
            let Some(screen) = scratch.screen else { return Ok(()) };
            let r = kernel.rollers;
            let left_out = all(r.units.len()) & !screen.candidates;
            for &phi in &crank {
                let e = crate::geometry::unit(phi);
                for i in bits(left_out) {
                    let u = r.units[i];
                    let (g, l) = r.first_order.at(u.dot(&e), crate::geometry::cross(e, u));
                    // The closing is linear in the lag: its ends are the worst.
                    for x in [lag - screen.lag_reach, lag + screen.lag_reach] {
                        prop_assert!(g - l * x > 0.0, "roller {i} at {phi}, lag {x}: {}", g - l * x);
                    }
                }
            }
        }
    }
}
