//! The lean first-order sweep: first-order geometry, the paper's linear law, a rigid bearing.
//!
//! The same closed forms as the general solve (`Rollers::first_order_terms`,
//! `Pins::first_order_at`, `solve::piecewise_linear_root_near`, MODEL.md "First order"), but
//! computing only what the curves record: per angle the lags, the forces, Hertz pressure and
//! half-width of the rollers in contact, the bearing force and the residual of Eqs. 12–14. No
//! per-roller state (normal, contact point, locus parameter) is built for a roller out of
//! contact. An angle the closed form cannot settle by itself (zero torque, where the answer is
//! the touching limit T → 0⁺; a root whose balance steps over the torque by round-off, as at
//! 1e-6 N·m) is left to the general `sweep::solve_into`, which handles both.
//!
//! Per roller i at crank φ (u_i its unit direction, e_φ = (cos φ, sin φ)):
//!   cos φi = u_i·e_φ, sin φi = e_φ × u_i, (g_i, l_i, S_i) from `first_order::Coefficients`,
//!   F_i = k·max(0, l_i·β − g_i), force on the disc −F_i·n_i with n_i = (u_i − K1·e_φ)/S_i,
//!   acting at Rp·u_i − r_rp·n_i;
//!   curvature at the contact from cos(nc·t_i) = cos(φi + nc·β) = cos φi·cos ncβ − sin φi·sin ncβ
//!   (t_i = 2πi/np + φ/nc − β, the locus parameter).
//! Per pin j (w_j its unit direction, ψ = −φ/nc + β the disc rotation):
//!   a_j = rw·(R(ψ)·w_j) × (−e_φ), gap c − βo·a_j, force F_j·(−e_φ) at the hole wall
//!   O + rw·R(ψ)·w_j − R_h·e_φ.

use super::pins::Pins;
use super::rollers::Rollers;
use super::solve::piecewise_linear_root_near;
use super::sweep::{BalanceSums, Model};
use crate::contact::law;
use crate::geometry::{cross, rotate, sin_cos, Vec2};
use crate::spec::{ContactLaw, GeometryMode};
use std::f64::consts::PI;

/// The closed-form sweep of one model, when the model is one it applies to.
#[derive(Debug)]
pub struct FirstOrderSweep<'a> {
    model: &'a Model,
    rollers: &'a Rollers,
    pins: Option<(&'a Pins, f64)>,
    /// Linear stiffness of a roller contact, N/mm.
    roller_stiffness: f64,
    /// E*/(π·L) and 4/(π·L·E*): p0 = sqrt(F·(1/R*)·E*/(πL)), b = sqrt(F·R*·4/(πLE*)).
    pressure_factor: f64,
    width_factor: f64,
}

/// The per-roller and per-pin entries the curves record at one angle, written in place.
#[derive(Debug)]
pub struct Row<'a> {
    pub roller_force_n: &'a mut [f64],
    pub pressure_mpa: &'a mut [f64],
    pub half_width_mm: &'a mut [f64],
    pub pin_force_n: &'a mut [f64],
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
}

/// Scratch space reused over a chunk of angles.
#[derive(Debug, Default)]
pub struct Scratch {
    /// (g, l) of every roller.
    terms: Vec<(f64, f64)>,
    /// (c, a) of every pin.
    pin_terms: Vec<(f64, f64)>,
    /// (cos φi, sin φi, S_i) of every roller.
    phases: Vec<(f64, f64, f64)>,
    events: Vec<(f64, f64, f64)>,
}

impl<'a> FirstOrderSweep<'a> {
    /// The lean sweep of `model`, or `None` when the model needs the general solve: exact
    /// geometry, the logarithmic law, a compliant bearing, or no rollers.
    pub fn new(model: &'a Model) -> Option<Self> {
        let r = model.rollers.as_ref()?;
        let applies = r.geometry == GeometryMode::FirstOrder
            && r.law == ContactLaw::PaperLinear
            && model.bearing_stiffness_n_per_mm.is_none();
        if !applies {
            return None;
        }
        let pins = match &model.pins {
            Some(p) => Some((p, p.linear_stiffness()?)),
            None => None,
        };
        let c = &r.materials;
        Some(FirstOrderSweep {
            model,
            rollers: r,
            pins,
            roller_stiffness: law::paper_linear_stiffness(c),
            pressure_factor: c.contact_modulus_mpa / (PI * c.length_mm),
            width_factor: 4.0 / (PI * c.length_mm * c.contact_modulus_mpa),
        })
    }

    /// Solve crank φ (e_φ its direction) from the guesses of the lags, writing `row`. `None`
    /// leaves the angle to the general solve (see the module documentation); `row` is then
    /// partly written.
    pub fn solve(
        &self,
        crank_rad: f64,
        e_phi: Vec2,
        (guess_lag, guess_output): (f64, f64),
        scratch: &mut Scratch,
        row: &mut Row<'_>,
    ) -> Option<Summary> {
        if self.model.torque_nmm == 0.0 {
            return None;
        }
        let mut sums = BalanceSums::default();
        let Row {
            roller_force_n,
            pressure_mpa,
            half_width_mm,
            pin_force_n,
        } = row;
        let (roller_force_n, pin_force_n) = (&mut **roller_force_n, &mut **pin_force_n);
        let (lag, contacts) =
            self.rollers_at(e_phi, guess_lag, scratch, &mut sums, roller_force_n)?;
        self.hertz(lag, scratch, roller_force_n, pressure_mpa, half_width_mm);
        let mut output_lag = 0.0;
        if let Some((p, k)) = self.pins {
            let psi = -crank_rad / self.model.teeth as f64 + lag;
            let guess = guess_output;
            output_lag =
                self.pins_at(p, k, (e_phi, psi), guess, scratch, &mut sums, pin_force_n)?;
        }
        let mut summary = Summary {
            lag_rad: lag,
            output_lag_rad: output_lag,
            contacts,
            ..Summary::default()
        };
        if self.model.bearing {
            summary.bearing_n = -sums.net_force();
            let centre = e_phi * self.model.eccentricity_mm;
            summary.residual = sums.relative(self.model, centre, summary.bearing_n);
        }
        let finite = lag.is_finite() && output_lag.is_finite() && summary.residual.is_finite();
        finite.then_some(summary)
    }

    /// β with Σ F·l = T and the roller forces into `force_n`, those in contact added to
    /// `sums`; with the number of contacts. `None` when the root is not settled to the solver
    /// tolerance.
    fn rollers_at(
        &self,
        e_phi: Vec2,
        guess: f64,
        scratch: &mut Scratch,
        sums: &mut BalanceSums,
        force_n: &mut [f64],
    ) -> Option<(f64, usize)> {
        let r = self.rollers;
        let k = self.roller_stiffness;
        let n = r.units.len();
        scratch.terms.resize(n, (0.0, 0.0));
        scratch.phases.resize(n, (0.0, 0.0, 0.0));
        // Terms first, in a loop without branches (the compiler can vectorise it), then the
        // active set at the guess.
        let rollers = r
            .units
            .iter()
            .zip(&mut scratch.terms)
            .zip(&mut scratch.phases);
        for ((u, term), phase) in rollers {
            let (c, s) = (u.dot(&e_phi), cross(e_phi, *u));
            let (g, l, big_s) = r.first_order.with_s(c, s);
            (*term, *phase) = ((g, l), (c, s, big_s));
        }
        let lag = self.settle(k, guess, &scratch.terms, &mut scratch.events, force_n)?;
        let rrp = r.design.roller_radius_mm;
        let mut contacts = 0;
        for (i, &force) in force_n.iter().enumerate() {
            if force > 0.0 {
                contacts += 1;
                let normal = (r.units[i] - r.first_order.k1 * e_phi) / scratch.phases[i].2;
                let point = r.centres[i] - rrp * normal;
                sums.roller(point, -force * normal, force * scratch.terms[i].1);
            }
        }
        Some((lag, contacts))
    }

    /// Hertz peak pressure and half-width of every roller (`contact::hertz_line`, zero out of
    /// contact), with 1/R* = max(κ + 1/r_rp, 1/Rp) as in `Rollers::line_contact` and κ the
    /// curvature at the roller's locus parameter.
    fn hertz(
        &self,
        lag: f64,
        scratch: &Scratch,
        force_n: &[f64],
        pressure_mpa: &mut [f64],
        half_width_mm: &mut [f64],
    ) {
        let r = self.rollers;
        let profile = &r.mesh.profile;
        let (sin_nc_lag, cos_nc_lag) = sin_cos(self.model.teeth as f64 * lag);
        let d = &r.design;
        let (min_inv_r, roller_inv_r) = (1.0 / d.roller_circle_radius_mm, 1.0 / d.roller_radius_mm);
        for (i, &force) in force_n.iter().enumerate() {
            if force <= 0.0 {
                (pressure_mpa[i], half_width_mm[i]) = (0.0, 0.0);
                continue;
            }
            let (c, s, _) = scratch.phases[i];
            let locus = profile.locus_curvature_at(c * cos_nc_lag - s * sin_nc_lag);
            let kappa = locus / (1.0 - profile.offset_mm * locus);
            let inv_r = (kappa + roller_inv_r).max(min_inv_r);
            pressure_mpa[i] = (force * inv_r * self.pressure_factor).sqrt();
            half_width_mm[i] = (force / inv_r * self.width_factor).sqrt();
        }
    }

    /// βo with Σ F·a = T at disc rotation ψ, the pin forces into `force_n` and those in
    /// contact into `sums`.
    #[allow(clippy::too_many_arguments)]
    fn pins_at(
        &self,
        p: &Pins,
        k: f64,
        (e_phi, psi): (Vec2, f64),
        guess: f64,
        scratch: &mut Scratch,
        sums: &mut BalanceSums,
        force_n: &mut [f64],
    ) -> Option<f64> {
        let (s, c) = psi.sin_cos();
        let direction = -e_phi;
        scratch.pin_terms.resize(p.base.len(), (0.0, 0.0));
        for (w, term) in p.base.iter().zip(&mut scratch.pin_terms) {
            let arm = cross(rotate(*w, c, s) * p.circle_radius_mm, direction);
            *term = (p.clearance_mm, arm);
        }
        let terms = &scratch.pin_terms;
        let lag = self.settle(k, guess, terms, &mut scratch.events, force_n)?;
        let wall = e_phi * p.eccentricity_mm + direction * p.hole_radius_mm;
        for ((w, &force), &(_, a)) in p.base.iter().zip(&*force_n).zip(terms) {
            if force > 0.0 {
                let point = wall + rotate(*w, c, s) * p.circle_radius_mm;
                sums.pin(point, force * direction, force * a);
            }
        }
        Some(lag)
    }
}

/// The active set (terms with l·x > g, as a bit mask) at one lag and its sums A = Σ k·l² and
/// B = Σ k·l·g over it, as in `solve::piecewise_linear_root_near`.
#[derive(Debug, Default, Clone, Copy)]
struct Segment {
    /// Bit i for term i; terms beyond the 64th are not tracked (`settle` then falls back).
    mask: u64,
    a: f64,
    b: f64,
}

impl Segment {
    #[inline]
    fn add(&mut self, i: usize, k: f64, (g, l): (f64, f64), x: f64) {
        if active(g, l, x) {
            self.mask |= 1 << (i % 64);
            self.a += k * l * l;
            self.b += k * l * g;
        }
    }
}

impl FirstOrderSweep<'_> {
    /// The root of the linear balance Σ k·max(0, l·x − g)·l = T and the forces there, into
    /// `force_n`. The first Newton step from the guess's segment, x = (T + B)/A, is the root
    /// when the active set at x is the guess's (the first step of `piecewise_linear_root_near`,
    /// checked in the pass that computes the forces); otherwise `piecewise_linear_root_near`
    /// decides. `None` also when the forces miss the torque by more than the solver tolerance,
    /// |Σ F·l − T| > rel_tol·max(|T|, Σ |F·l|) (the round-off of a tiny torque, left to the
    /// general solve's straddle).
    fn settle(
        &self,
        k: f64,
        guess: f64,
        terms: &[(f64, f64)],
        events: &mut Vec<(f64, f64, f64)>,
        force_n: &mut [f64],
    ) -> Option<f64> {
        let (torque, rel_tol) = (self.model.torque_nmm, self.model.settings.rel_tol);
        let settled = |(moment, scale): (f64, f64)| {
            (moment - torque).abs() <= rel_tol * torque.abs().max(scale)
        };
        let mut at_guess = Segment::default();
        for (i, &term) in terms.iter().enumerate() {
            at_guess.add(i, k, term, guess);
        }
        if terms.len() <= 64 && at_guess.a > 0.0 {
            let x = (torque + at_guess.b) / at_guess.a;
            let (moment, scale, mask) = linear_forces(k, terms, x, force_n);
            if mask == at_guess.mask {
                return settled((moment, scale)).then_some(x);
            }
        }
        let x = piecewise_linear_root_near(k, terms, torque, guess, events)?;
        let (moment, scale, _) = linear_forces(k, terms, x, force_n);
        settled((moment, scale)).then_some(x)
    }
}

/// Whether a term (g, l) is in contact at x, as `solve::piecewise_linear_root_near` decides it.
#[inline]
fn active(g: f64, l: f64, x: f64) -> bool {
    l != 0.0 && l * x > g
}

/// Linear-law forces k·max(0, l·x − g) of the terms (g, l) at x into `force_n`; returns the
/// moment Σ F·l, its scale Σ |F·l| and the mask of the active set at x (`Segment`).
fn linear_forces(k: f64, terms: &[(f64, f64)], x: f64, force_n: &mut [f64]) -> (f64, f64, u64) {
    let (mut moment, mut scale, mut mask) = (0.0, 0.0, 0u64);
    for (i, (&(g, l), f)) in terms.iter().zip(force_n).enumerate() {
        let gap = g - l * x;
        *f = if gap < 0.0 { -gap * k } else { 0.0 };
        moment += *f * l;
        scale += (*f * l).abs();
        mask |= u64::from(active(g, l, x)) << (i % 64);
    }
    (moment, scale, mask)
}
