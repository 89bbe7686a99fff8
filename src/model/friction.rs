//! Friction at every contact and the heat path of the housing (spec: `reducer.friction`,
//! `reducer.thermal`; MODEL.md "Friction, efficiency and heat"). Plain data; the sliding
//! speeds are `equilibrium::friction::sliding`, the losses and the coupled balance are built
//! on them.

/// Which friction model a scene runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrictionModel {
    /// Forces from the frictionless balance; each loss = μ·F·sliding speed (the literature's
    /// standard). Forces, lags and every frictionless output stay as without friction.
    Loss,
    /// Friction forces μ·F along every contact's tangent, against its sliding, inside the
    /// balance; the input torque follows from the crank's balance (the default).
    Coupled,
}

named!(FrictionModel "friction model" {
    Loss => "loss",
    Coupled => "coupled",
});

/// How the ring rollers move (spec: `reducer.friction.rollers.mode`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RollerMode {
    /// Fixed in the housing: the disc slides over the roller.
    Fixed,
    /// Each roller turns on its pin of radius `bore_radius_mm` (< Rrp): it rolls on the disc
    /// and slides on the pin at the disc's sliding speed × r_b / Rrp.
    Rotating {
        /// r_b, mm.
        bore_radius_mm: f64,
    },
}

/// How the output pins meet the holes (spec: `reducer.friction.output_pins.mode`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PinMode {
    /// The hole slides over the pin at e·Ω.
    Fixed,
    /// A free sleeve of outer radius `output_pins.pin_radius_mm` turns on a pin of radius
    /// `bore_radius_mm` (< the sleeve's): it rolls in the hole and slides on the pin at
    /// e·Ω·r_bore / r_pin.
    Sleeve {
        /// r_bore, mm.
        bore_radius_mm: f64,
    },
}

impl RollerMode {
    /// `x` (a sliding speed, or a friction coefficient) scaled by this mode's slip factor: the
    /// ratio of the speed at which the friction slides to the disc's sliding speed at the
    /// roller, 1 (fixed) or r_b/Rrp (rotating: the roller rolls on the disc and its bore slides
    /// on its pin), `roller_radius_mm` = Rrp. Computed as x·r_b/Rrp, in that order.
    pub fn slip_scaled(&self, x: f64, roller_radius_mm: f64) -> f64 {
        match *self {
            RollerMode::Fixed => x,
            RollerMode::Rotating { bore_radius_mm } => x * bore_radius_mm / roller_radius_mm,
        }
    }
}

impl PinMode {
    /// `x` scaled by this mode's slip factor: 1 (fixed: the hole slides over the pin) or
    /// r_bore/r_pin (a free sleeve rolls in the hole and slides on its pin), `pin_radius_mm` =
    /// r_pin, the sleeve's outer radius. Computed as x·r_bore/r_pin, in that order.
    pub fn slip_scaled(&self, x: f64, pin_radius_mm: f64) -> f64 {
        match *self {
            PinMode::Fixed => x,
            PinMode::Sleeve { bore_radius_mm } => x * bore_radius_mm / pin_radius_mm,
        }
    }
}

/// Friction of the ring rollers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerFriction {
    /// Fixed or rotating.
    pub mode: RollerMode,
    /// μ in [0, 1): at the disc for fixed rollers, at the roller's pin for rotating ones.
    pub mu: f64,
}

/// Friction of the output pins.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinFriction {
    /// Fixed pins or free sleeves.
    pub mode: PinMode,
    /// μ in [0, 1): in the hole for fixed pins, between sleeve and pin for sleeves.
    pub mu: f64,
}

/// Friction of the crank bearing: a friction torque μ·Fb·d/2 at the crank's speed relative
/// to the disc, Ω.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BearingFriction {
    /// μ in [0, 1), referred to the bore.
    pub mu: f64,
    /// d, the bearing's bore, mm.
    pub bore_diameter_mm: f64,
}

/// Friction at every contact (spec: `reducer.friction`). A path not given has no friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    /// Loss or coupled (the default).
    pub model: FrictionModel,
    /// The ring rollers, when given.
    pub rollers: Option<RollerFriction>,
    /// The output pins, when given.
    pub output_pins: Option<PinFriction>,
    /// The crank bearing, when given.
    pub crank_bearing: Option<BearingFriction>,
    /// The drag at the input (seals, churning), N·mm, one number or a table over the input
    /// speed (spec: `no_load_torque_nmm`; 0 when not given).
    pub no_load_torque_nmm: NoLoadTorque,
}

/// Most points of a no-load torque table: a catalogue's running-torque curve has a handful.
pub const MAX_NO_LOAD_POINTS: usize = 32;

/// The no-load running torque T0 at the input against the input speed, N·mm: points
/// (n_rpm, T0) increasing in speed, linear between them and held beyond the ends; one point is
/// a constant drag. Fixed storage, so `Friction` stays `Copy`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoLoadTorque {
    points: [[f64; 2]; MAX_NO_LOAD_POINTS],
    len: usize,
}

impl NoLoadTorque {
    /// The same drag at every speed, N·mm.
    pub fn constant(torque_nmm: f64) -> Self {
        Self::table(&[[0.0, torque_nmm]])
    }

    /// The table of `points` [rpm, N·mm] (1 to `MAX_NO_LOAD_POINTS`, increasing in speed, as
    /// `spec::friction` checks); more points are cut to the first `MAX_NO_LOAD_POINTS`.
    pub fn table(points: &[[f64; 2]]) -> Self {
        let mut t = NoLoadTorque {
            points: [[0.0; 2]; MAX_NO_LOAD_POINTS],
            len: points.len().min(MAX_NO_LOAD_POINTS),
        };
        t.points[..t.len].copy_from_slice(&points[..t.len]);
        t
    }

    /// The table's points [rpm, N·mm].
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points[..self.len]
    }

    /// One point: the same drag at every speed.
    pub fn is_constant(&self) -> bool {
        self.len <= 1
    }

    /// The largest drag of the table, N·mm (0 for none).
    pub fn max_nmm(&self) -> f64 {
        self.points().iter().map(|p| p[1]).fold(0.0, f64::max)
    }

    /// T0 at `rpm`, N·mm: linear between the neighbouring points, held beyond the ends.
    /// Without a speed (`None`: a duty cycle's standstill bin) T0 at 0 rpm, the first point's
    /// (`spec::friction` refuses a table where a scene computes the efficiency without one).
    pub fn at_rpm(&self, rpm: Option<f64>) -> f64 {
        let p = self.points();
        let Some(n) = rpm else {
            return p.first().map_or(0.0, |q| q[1]);
        };
        match p.iter().position(|q| q[0] > n) {
            None => p.last().map_or(0.0, |q| q[1]),
            Some(0) => p[0][1],
            Some(k) => {
                let ([n0, t0], [n1, t1]) = (p[k - 1], p[k]);
                t0 + (t1 - t0) * (n - n0) / (n1 - n0)
            }
        }
    }
}

/// The housing's heat path (spec: `reducer.thermal`): the steady temperature of a scene with a
/// speed is ambient + P_loss / (h·A).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thermal {
    /// A, the housing's surface that sheds heat, m².
    pub housing_area_m2: f64,
    /// h, the heat transfer coefficient, W/(m²·K).
    pub heat_transfer_w_per_m2k: f64,
    /// The ambient temperature, °C.
    pub ambient_c: f64,
}

impl Thermal {
    /// The steady temperature at a mean power loss `loss_w`, °C.
    pub fn temperature_c(&self, loss_w: f64) -> f64 {
        self.ambient_c + loss_w / (self.heat_transfer_w_per_m2k * self.housing_area_m2)
    }
}

/// The loss power of each path per unit input speed, N·mm/rad (MODEL.md "Friction, efficiency
/// and heat"): the power at ω = 1 rad/s in N·mm/s.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PathLosses {
    /// Σ over the ring rollers: μ·F_i·|v_t,i| (fixed), × r_b/Rrp (rotating on their pins).
    pub rollers: f64,
    /// Σ over the output pins: μ·F_j·e·Ω/ω (fixed), × r_bore/r_pin (free sleeves).
    pub output_pins: f64,
    /// The crank bearing: μ·|Fb|·(d/2)·Ω/ω.
    pub crank_bearing: f64,
    /// The input's constant drag T0 (seals, churning): T0·ω/ω = T0, once per reducer.
    pub no_load: f64,
}

impl PathLosses {
    /// The sum of every path, N·mm/rad.
    pub fn total(&self) -> f64 {
        self.rollers + self.output_pins + self.crank_bearing + self.no_load
    }

    /// The path-by-path sum of `self` and `other` (the discs of one reducer).
    pub fn plus(&self, other: &PathLosses) -> PathLosses {
        PathLosses {
            rollers: self.rollers + other.rollers,
            output_pins: self.output_pins + other.output_pins,
            crank_bearing: self.crank_bearing + other.crank_bearing,
            no_load: self.no_load + other.no_load,
        }
    }

    /// Every path times `factor` (ω for N·mm/s, a mean's 1/n).
    pub fn scaled(&self, factor: f64) -> PathLosses {
        PathLosses {
            rollers: self.rollers * factor,
            output_pins: self.output_pins * factor,
            crank_bearing: self.crank_bearing * factor,
            no_load: self.no_load * factor,
        }
    }
}
