//! The coupled friction model's coefficients (`Coupling`, plain data that the loaded model
//! carries as `loaded::Model::coupling`) and the forces, arms and energy built on them (MODEL.md
//! "Friction, efficiency and heat"): every contact of the disc carries, besides its normal
//! force F, a Coulomb force along its tangent against its sliding, inside the disc's balance;
//! the input torque then follows from the crank's balance.
//!
//! Sliding directions are those of the rigid-body kinematics at the nominal ratio (`friction::sliding`),
//! independent of the forces, so each tangential force is linear in its contact's normal force:
//! - ring roller i: f_t = −c_r·F_i·s_i·t_i at the contact C_i, t = ẑ × n, s_i the sign of the
//!   disc's sliding v_disc(C_i)·t_i; c_r = μ (fixed rollers) or μ·r_b/Rrp (rotating rollers:
//!   the roller is a free body rolling on the disc, whose pin's friction moment μ·F·r_b it
//!   balances with a tangential force μ·F·r_b/Rrp at the disc). Its moment about the disc
//!   centre O_d is −c_r·F_i·s_i·(C_i − O_d)·n_i, so the roller's arm l_i becomes
//!   l̃_i = l_i + c_r·s_i·(C_i − O_d)·n_i (moment on the disc −F_i·l̃_i).
//! - output pin j: the hole slides over its pin at e·Ω along τ = ẑ × e_φ = (−sin φ, cos φ);
//!   f_t = −c_p·F_j·τ at the hole contact X_j, c_p = μ (fixed) or μ·r_bore/r_pin (free
//!   sleeves). The output torque T is the flange's: the pins' normal forces about the disc
//!   centre (the paper's balance Σ F_j·a_j, unchanged) plus their friction forces about the
//!   axis, so P_out = T·ω/nc holds for the friction's part exactly: the pin's arm becomes
//!   ã_j = a_j − c_p·X_j·e_φ (cross(X, τ) = X·e_φ).
//! - crank bearing: friction moment M_b = μ_b·|Fb|·d/2 on the disc, counter-clockwise (the disc
//!   turns at −Ω relative to the crank), the opposite on the crank.
//!
//! Disc balance about O_d: −Σ F_i·l̃_i + (T − O_d × Σ f_t,j) + M_b = 0, i.e. the rollers balance
//!   Σ F_i·l̃_i − c_b·|Fb| = T + c_p·(Σ F_j)·(O_d × τ),   c_b = μ_b·d/2,
//! with Fb = −(Σ roller forces + Σ pin forces, friction included): the bearing's |Fb| couples the
//! rollers to the pins' total force. Input torque from the crank's balance about the axis
//! (the bearing pushes the crank's eccentric E = (e + de)·e_φ with −Fb and the moment −M_b):
//!   T_in = E × Fb + M_b.
//! Energy (the disc's virtual power under the rigid field v_disc, the crank's under its
//! rotation, the flange's under its): P_in = P_out + Σ losses + W_n + W_b + W_p, with W_n the
//! work of the normal forces on the relative normal velocities of their contacts under the
//! nominal kinematics (zero when every contact normal passes through the pitch point and every
//! pin force is along −e_φ: the first-order geometry; of the order of the lag otherwise, the
//! TE ripple's work), W_b the bearing's offset term Fb·(ω ẑ × E − v_disc(O_d)) (zero with the
//! rigid bearing on the nominal orbit) and W_p the pins' normal forces' moment about the axis
//! beyond the paper's, (ω/nc)·Σ F_j·(O_d × û_j) (zero when every pin force is along −e_φ).
//! `energy` evaluates them.
//!
//! Units: mm, N, N·mm, rad; powers per unit input speed (N·mm per rad of crank).

use super::angle_solution::AngleSolution;
use super::friction::sliding::{self, disc_speed_ratio, disc_velocity, relative_crank_speed_ratio};
use super::pins::PinState;
use super::rollers::RollerState;
use super::solve::rel;
use crate::geometry::{angle_from, cross, unit, z_cross, Vec2};
use crate::model::{Design, Friction};

/// The friction of the coupled balance, per unit normal force (`Friction` reduced to what the
/// balance needs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coupling {
    /// c_r: the rollers' tangential force per unit normal force at the disc: μ (fixed), μ·r_b/Rrp
    /// (rotating).
    pub roller: f64,
    /// c_p: the pins' tangential force per unit normal force at the hole: μ (fixed pins),
    /// μ·r_bore/r_pin (free sleeves).
    pub pin: f64,
    /// c_b = μ_b·d/2: the crank bearing's friction moment per unit bearing force, mm.
    pub bearing_arm_mm: f64,
    /// The crank's eccentricity as built, e + de, mm (the kinematics' orbit).
    pub eccentricity_mm: f64,
    /// nc, the disc's teeth.
    pub teeth: usize,
    /// How the contacts slide: the running reducer's kinematics, or a torsion loop's turn.
    pub sliding: Sliding,
}

/// How the contacts slide, which sets every friction force's direction (MODEL.md "Friction,
/// efficiency and heat").
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sliding {
    /// The input turns at the nominal ratio: the rigid-body kinematics (`friction::sliding`).
    Running,
    /// Torsion under a locked input: the disc turns about its own centre O_d by dβ of the sign
    /// `sigma` (+1 on the loading branch, −1 unloading), the flange about the axis by
    /// dβ + dβo with dβo = `pin_ratio`·dβ (the pins' deflection per unit turn of the disc,
    /// ≥ 0; it sets the pins' sliding directions).
    Torsion { sigma: f64, pin_ratio: f64 },
}

impl Coupling {
    /// The coupling of `friction` on `design`; a path not given has no friction.
    pub fn new(friction: &Friction, design: &Design) -> Self {
        let roller =
            (friction.rollers).map_or(0.0, |f| f.mode.slip_scaled(f.mu, design.roller_radius_mm));
        let pin = (friction.output_pins)
            .map_or(0.0, |f| f.mode.slip_scaled(f.mu, design.pins.pin_radius_mm));
        Coupling {
            roller,
            pin,
            bearing_arm_mm: friction
                .crank_bearing
                .map_or(0.0, |b| b.mu * 0.5 * b.bore_diameter_mm),
            eccentricity_mm: design.built_eccentricity_mm(),
            teeth: design.teeth,
            sliding: Sliding::Running,
        }
    }

    /// This coupling in a torsion loop's branch `sigma` (+1 loading, −1 unloading), the pins'
    /// ratio starting at 0 (`Sliding::Torsion`).
    pub fn in_torsion(self, sigma: f64) -> Self {
        Coupling {
            sliding: Sliding::Torsion {
                sigma,
                pin_ratio: 0.0,
            },
            ..self
        }
    }

    /// Whether this is a torsion loop's friction (`Sliding::Torsion`).
    pub fn is_torsion(&self) -> bool {
        matches!(self.sliding, Sliding::Torsion { .. })
    }

    /// Whether any contact has friction (with none, the balance is the frictionless one).
    pub fn active(&self) -> bool {
        self.roller > 0.0 || self.pin > 0.0 || self.bearing_arm_mm > 0.0
    }
}

impl Coupling {
    /// s_i: the sign of the disc's sliding over roller `s` along t = ẑ × n (−1, 0 or 1): at
    /// crank angle `crank_rad` (the disc's own) under the running kinematics; in a torsion
    /// loop the disc turns about its centre `centre` by dβ of sign σ, so the contact slides at
    /// σ·(C − O_d)·n (`sliding::torsion_roller_sliding`).
    pub fn roller_sign(&self, crank_rad: f64, centre: Vec2, s: &RollerState) -> f64 {
        let v = match self.sliding {
            Sliding::Running => sliding::roller_sliding(
                crank_rad,
                self.eccentricity_mm,
                self.teeth,
                s.point,
                s.normal,
            ),
            Sliding::Torsion { sigma, .. } => {
                sigma * sliding::torsion_roller_sliding(centre, s.point, s.normal)
            }
        };
        sign(v)
    }

    /// l̃ = l + c_r·s·(C − O_d)·n, mm: the arm of roller `s`'s normal force that carries its
    /// friction's moment about the disc centre `centre` too (moment on the disc −F·l̃).
    pub fn roller_arm(&self, crank_rad: f64, centre: Vec2, s: &RollerState) -> f64 {
        s.arm_mm
            + self.roller
                * self.roller_sign(crank_rad, centre, s)
                * (s.point - centre).dot(&s.normal)
    }

    /// The friction force of roller `s` on the disc, N: −c_r·F·s·t, t = ẑ × n.
    pub fn roller_friction(&self, crank_rad: f64, centre: Vec2, s: &RollerState) -> Vec2 {
        let t = z_cross(s.normal);
        t * (-self.roller * s.force_n * self.roller_sign(crank_rad, centre, s))
    }

    /// The direction in which the hole of pin `p` slides over its pin (its friction on the
    /// disc is −c_p·F times it): running, τ = ẑ × e_φ for every hole (each orbits its pin at
    /// e·Ω); in a torsion loop, s_j·(ẑ × u_j), u_j the pin's contact direction and s_j the sign
    /// of σ·(−O_d·u_j − ρ·X_j·u_j) (`sliding::torsion_pin_sliding`), or zero where it vanishes.
    pub fn pin_direction(&self, e_phi: Vec2, centre: Vec2, p: &PinState) -> Vec2 {
        match self.sliding {
            Sliding::Running => z_cross(e_phi),
            Sliding::Torsion { sigma, pin_ratio } => {
                let v = sliding::torsion_pin_sliding(centre, p.point, p.direction, pin_ratio);
                z_cross(p.direction) * sign(sigma * v)
            }
        }
    }

    /// ã = a − c_p·X × d, mm (d = `pin_direction`): the arm of pin `p`'s normal force that
    /// carries its friction's moment about the axis too (the output torque is Σ F_j·ã_j);
    /// running, X × τ = X·e_φ.
    pub fn pin_arm(&self, e_phi: Vec2, centre: Vec2, p: &PinState) -> f64 {
        p.arm_mm - self.pin * cross(p.point, self.pin_direction(e_phi, centre, p))
    }

    /// The friction force of pin `p` on the disc, N: −c_p·F·d.
    pub fn pin_friction(&self, e_phi: Vec2, centre: Vec2, p: &PinState) -> Vec2 {
        self.pin_direction(e_phi, centre, p) * (-self.pin * p.force_n)
    }

    /// The sign of the bearing's friction moment on the disc: +1 running (the disc turns at
    /// −Ω relative to the crank), −σ in a torsion loop (the disc turns by σ·dβ against the
    /// locked eccentric, its friction resists).
    pub fn bearing_sign(&self) -> f64 {
        match self.sliding {
            Sliding::Running => 1.0,
            Sliding::Torsion { sigma, .. } => -sigma,
        }
    }

    /// M_b = ±c_b·|Fb|: the bearing's friction moment on the disc (counter-clockwise
    /// positive; `bearing_sign`) under a bearing force of magnitude |Fb| = `bearing_force_n`
    /// (N), N·mm.
    pub fn bearing_moment(&self, bearing_force_n: f64) -> f64 {
        self.bearing_sign() * self.bearing_arm_mm * bearing_force_n
    }

    /// Σ of every contact force on the disc (normal and friction) at crank angle `crank_rad`,
    /// N; the bearing force is its negative.
    pub fn net_force(&self, crank_rad: f64, sol: &AngleSolution) -> Vec2 {
        let e_phi = unit(crank_rad);
        let centre = e_phi * self.eccentricity_mm + sol.centre_offset_mm;
        self.roller_total(crank_rad, centre, &sol.rollers)
            + self.pin_total(e_phi, centre, &sol.pins)
    }

    /// Σ of the rollers' forces on the disc, normal and friction, N.
    pub fn roller_total(&self, crank_rad: f64, centre: Vec2, rollers: &[RollerState]) -> Vec2 {
        rollers
            .iter()
            .filter(|s| s.force_n != 0.0)
            .map(|s| s.force_vector() + self.roller_friction(crank_rad, centre, s))
            .sum()
    }

    /// Σ of the pins' forces on the disc, normal and friction, N.
    pub fn pin_total(&self, e_phi: Vec2, centre: Vec2, pins: &[PinState]) -> Vec2 {
        pins.iter()
            .filter(|p| p.force_n != 0.0)
            .map(|p| p.force_vector() + self.pin_friction(e_phi, centre, p))
            .sum()
    }

    /// The rollers' share of the pins' friction: Σ c_p·F_j·(O_d × d_j), N·mm (the disc's
    /// moment balance about its centre moves the pins' friction moment from the axis to O_d).
    pub fn pin_shift(&self, e_phi: Vec2, centre: Vec2, pins: &[PinState]) -> f64 {
        if self.pin == 0.0 {
            return 0.0;
        }
        pins.iter()
            .map(|p| self.pin * p.force_n * cross(centre, self.pin_direction(e_phi, centre, p)))
            .sum()
    }

    /// Whether the pins' sliding signs in a torsion loop change when the pins' ratio ρ becomes
    /// `pin_ratio` (their friction then acts the other way): false running.
    pub fn pin_signs_change(
        &self,
        e_phi: Vec2,
        centre: Vec2,
        pins: &[PinState],
        pin_ratio: f64,
    ) -> bool {
        let Sliding::Torsion { sigma, .. } = self.sliding else {
            return false;
        };
        let moved = Coupling {
            sliding: Sliding::Torsion { sigma, pin_ratio },
            ..*self
        };
        pins.iter()
            .filter(|p| p.force_n != 0.0)
            .any(|p| self.pin_direction(e_phi, centre, p) != moved.pin_direction(e_phi, centre, p))
    }

    /// T_in = E × Fb + M_b: one disc's share of the input torque from the crank's balance about
    /// the axis, N·mm, with the bearing's force on the disc given as the sweep records it: its
    /// magnitude |Fb| = `bearing_force_n` (N) at the angle ε = `angle_rad` from e_φ, so
    /// E × Fb = (e + de)·|Fb|·sin ε and M_b = ±c_b·|Fb| (`bearing_moment`). The one home of
    /// the formula: the coupled balance's energy and the efficiency's input torque call it.
    pub fn input_torque(&self, bearing_force_n: f64, angle_rad: f64) -> f64 {
        self.eccentricity_mm * bearing_force_n * angle_rad.sin()
            + self.bearing_moment(bearing_force_n)
    }

    /// The largest relative residual of one disc's coupled balance at crank angle `crank_rad`,
    /// evaluated from the forces as vectors at their points: the force balance with the
    /// bearing, the moment balance about the disc centre with the bearing's friction moment,
    /// and the flange's torque Σ F_j·ã_j = T.
    pub fn residual(&self, crank_rad: f64, sol: &AngleSolution, output_torque_nmm: f64) -> f64 {
        let e_phi = unit(crank_rad);
        let centre = e_phi * self.eccentricity_mm + sol.centre_offset_mm;
        let fb = sol.bearing_force_n.unwrap_or_default();
        let (mut force, mut force_scale) = (fb, fb.norm());
        let mb = self.bearing_moment(fb.norm());
        let (mut moment, mut moment_scale) = (mb, mb.abs());
        let mut add = |point: Vec2, f: Vec2| {
            force += f;
            force_scale += f.norm();
            let m = cross(point - centre, f);
            moment += m;
            moment_scale += m.abs();
        };
        for s in sol.rollers.iter().filter(|s| s.force_n != 0.0) {
            add(
                s.point,
                s.force_vector() + self.roller_friction(crank_rad, centre, s),
            );
        }
        let (mut torque, mut torque_scale) = (0.0, output_torque_nmm.abs());
        for p in sol.pins.iter().filter(|p| p.force_n != 0.0) {
            add(
                p.point,
                p.force_vector() + self.pin_friction(e_phi, centre, p),
            );
            let t = p.force_n * self.pin_arm(e_phi, centre, p);
            torque += t;
            torque_scale += t.abs();
        }
        // Without pins in the solution the disc's torque is the model's, not a contact's: only
        // the force balance is checked.
        let (moment, pins) = if sol.pins.is_empty() {
            (0.0, 0.0)
        } else {
            (
                rel(moment, moment_scale),
                rel(torque - output_torque_nmm, torque_scale),
            )
        };
        rel(force.norm(), force_scale).max(moment).max(pins)
    }

    /// The powers of one disc's coupled solution at crank angle `crank_rad`, per unit input
    /// speed (N·mm/rad): the terms of P_in = P_flange + Σ losses + W_n + W_b and
    /// P_flange = P_out + W_p (`Energy`).
    pub fn energy(&self, crank_rad: f64, sol: &AngleSolution, output_torque_nmm: f64) -> Energy {
        let e_phi = unit(crank_rad);
        let (nc, ecc) = (self.teeth, self.eccentricity_mm);
        let wd = disc_speed_ratio(nc);
        let centre = e_phi * ecc + sol.centre_offset_mm;
        let fb = sol.bearing_force_n.unwrap_or_default();
        let mut e = Energy {
            input: self.input_torque(fb.norm(), angle_from(e_phi, fb)),
            output: output_torque_nmm / nc as f64,
            crank_bearing: self.bearing_moment(fb.norm()) * relative_crank_speed_ratio(nc),
            ..Energy::default()
        };
        for s in sol.rollers.iter().filter(|s| s.force_n != 0.0) {
            let v = disc_velocity(crank_rad, ecc, nc, s.point);
            e.rollers -= self.roller_friction(crank_rad, centre, s).dot(&v);
            e.normal_work += s.force_n * s.normal.dot(&v);
        }
        for p in sol.pins.iter().filter(|p| p.force_n != 0.0) {
            // The hole's material relative to the pin: v_disc(X) − ωd ẑ × X.
            let x = p.point;
            let relative = disc_velocity(crank_rad, ecc, nc, x) - z_cross(x) * wd;
            let friction = self.pin_friction(e_phi, centre, p);
            e.output_pins -= friction.dot(&relative);
            e.normal_work -= p.force_n * p.direction.dot(&relative);
            // The power the pins take from the disc, −f·(ωd ẑ × X) = (1/nc)·X × f.
            e.flange += cross(x, p.force_vector() + friction) / nc as f64;
            e.pin_convention += p.force_n * cross(centre, p.direction) / nc as f64;
        }
        // The crank pushes at E with velocity ω ẑ × E; the disc's field at its centre.
        let eccentric_velocity = z_cross(e_phi) * ecc;
        e.bearing_offset =
            fb.dot(&(eccentric_velocity - disc_velocity(crank_rad, ecc, nc, centre)));
        e
    }
}

/// −1, 0 or 1.
fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The power terms of one disc at one crank angle, per unit input speed, N·mm/rad
/// (`Coupling::energy`). Two identities hold to round-off in the coupled balance:
/// - the disc's virtual power: P_in = P_flange + Σ losses + W_n + W_b (`imbalance`), which
///   fails where the disc's moment balance misses a friction moment;
/// - the flange's torque: P_flange = P_out + W_p (`flange_imbalance`), P_out = T/nc with T the
///   scene's torque, which fails where the pins' balance misses one.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energy {
    /// P_in/ω = T_in (this disc's share).
    pub input: f64,
    /// P_out/ω = T/nc, T the torque this disc balances.
    pub output: f64,
    /// The power the pins take from the disc, (1/nc)·Σ X_j × f_j, measured from the forces.
    pub flange: f64,
    /// −Σ f_t·v_rel over the rollers: the rollers' loss.
    pub rollers: f64,
    /// −Σ f_t·v_rel over the pins: the pins' loss.
    pub output_pins: f64,
    /// M_b·Ω/ω: the bearing's loss.
    pub crank_bearing: f64,
    /// W_n: Σ F·(relative normal velocity) of the contacts (approach positive).
    pub normal_work: f64,
    /// W_b = Fb·(ω ẑ × E − v_disc(O_d)): the bearing's offset from the nominal orbit.
    pub bearing_offset: f64,
    /// W_p = (1/nc)·Σ F_j·(O_d × û_j): the pins' normal forces' moment about the axis beyond
    /// the paper's (about the disc centre).
    pub pin_convention: f64,
}

impl Energy {
    /// P_in − P_flange − Σ losses − W_n − W_b: zero to round-off when the disc balances.
    pub fn imbalance(&self) -> f64 {
        self.input
            - self.flange
            - self.rollers
            - self.output_pins
            - self.crank_bearing
            - self.normal_work
            - self.bearing_offset
    }

    /// P_flange − P_out − W_p: zero to round-off when the pins balance the torque.
    pub fn flange_imbalance(&self) -> f64 {
        self.flange - self.output - self.pin_convention
    }

    /// The scale of the terms, for a relative imbalance.
    pub fn scale(&self) -> f64 {
        [
            self.input,
            self.output,
            self.flange,
            self.rollers,
            self.output_pins,
            self.crank_bearing,
            self.normal_work,
            self.bearing_offset,
            self.pin_convention,
        ]
        .iter()
        .map(|x| x.abs())
        .fold(0.0, f64::max)
    }
}
