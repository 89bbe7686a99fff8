//! The reducer as designed: geometry, materials, and the closed forms of the roller-centre
//! locus that the design rules need (MODEL.md "Profile"); the tooth-profile modification is
//! `modification`. Engine units: mm, MPa, rad.

use super::deviations::Deviations;
use super::friction::{Friction, Thermal};
use super::modification::Modification;

/// Elastic material of one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E, MPa (spec: `youngs_modulus_gpa`, in GPa).
    pub youngs_modulus_mpa: f64,
    /// Poisson's ratio ν, in [0, 0.5).
    pub poisson_ratio: f64,
}

impl Material {
    /// Compliance term (1 − ν²)/E in 1/MPa.
    pub fn compliance_per_mpa(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus_mpa
    }
}

/// Output mechanism: pins on the output flange, running in holes of the disc.
/// A hole's radius is `pin_radius_mm + e + hole_clearance_mm` (ideal pin-in-hole plus clearance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputPins {
    /// M, the number of output pins (and of holes in each disc).
    pub count: usize,
    /// rw, radius of the circle of pin centres (and of hole centres in the disc), mm.
    pub circle_radius_mm: f64,
    /// Radius of a pin, mm.
    pub pin_radius_mm: f64,
    /// Radial clearance of a hole beyond the ideal pin-in-hole radius, mm (≥ 0; 0: ideal).
    pub hole_clearance_mm: f64,
    /// How the pins are carried by the output flange, when they bend (spec:
    /// `reducer.output_pins.support`); none: rigid pins (the paper's model).
    pub support: Option<PinSupport>,
}

/// How an output pin is held, for its bending (`equilibrium::pin_beam`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PinSupportKind {
    /// Clamped in the flange at z = 0, free at z = length.
    Cantilever,
    /// Clamped in the flange at z = 0 and simply supported at z = length (a propped
    /// cantilever: the pin's far end in a second flange or a support ring that holds it
    /// radially but not in slope).
    BothEnds,
}

named!(PinSupportKind "pin support" {
    Cantilever => "cantilever",
    BothEnds => "both_ends",
});

/// An output pin as a beam (spec: `reducer.output_pins.support`): its support, its length
/// from the flange and where each disc's mid-plane sits along it, mm from the flange.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinSupport {
    /// Cantilever or both ends held.
    pub kind: PinSupportKind,
    /// L, the pin's length from the flange face to its free or supported end, mm.
    pub length_mm: f64,
    /// a_k, disc k's mid-plane along the pin from the flange, mm, in (0, L]; the first
    /// `Design::discs` entries are the discs', the rest 0.
    pub disc_positions_mm: [f64; MAX_DISCS],
}

impl OutputPins {
    /// The nominal centre of pin (and hole) j, mm: (rw·cos 2πj/M, rw·sin 2πj/M), in the disc
    /// frame for a hole, the flange's for a pin.
    pub fn centre_mm(&self, j: usize) -> [f64; 2] {
        let a = std::f64::consts::TAU * j as f64 / self.count as f64;
        [
            self.circle_radius_mm * a.cos(),
            self.circle_radius_mm * a.sin(),
        ]
    }
}

/// Reducer geometry (MODEL.md "Paper design"): `rollers = teeth + 1`, and `discs` identical
/// discs at crank phases 2πk/discs (MODEL.md "Several discs").
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// nc, the number of teeth of a disc.
    pub teeth: usize,
    /// np = nc + 1, the number of rollers fixed in the housing.
    pub rollers: usize,
    /// Identical discs on the crank, 1 to `MAX_DISCS`.
    pub discs: usize,
    /// e, the crank eccentricity, mm: at crank angle φ = 0 the disc centre is at (e, 0).
    pub eccentricity_mm: f64,
    /// Rp, radius of the circle of roller centres, mm.
    pub roller_circle_radius_mm: f64,
    /// Rrp, radius of a roller, mm.
    pub roller_radius_mm: f64,
    /// B, the face width of a disc, mm: the length L of every line contact.
    pub face_width_mm: f64,
    /// The output mechanism: pins on the output flange in holes of the disc.
    pub pins: OutputPins,
    /// The disc's material (spec: `reducer.material`).
    pub disc_material: Material,
    /// The rollers' material (`reducer.roller_material`; the disc's when not given); the output
    /// pins' contacts take it for the pins too.
    pub roller_material: Material,
    /// What the disc's and the rollers' materials bear (`yield_strength_mpa`,
    /// `contact_fatigue` of `reducer.material` and `reducer.roller_material`).
    pub strength: super::strength::Strength,
    /// The crank bearing's rating (spec: `reducer.crank_bearing`), for its rating life.
    pub crank_bearing: Option<CrankBearing>,
    /// The parts as built (`reducer.deviations`; all zero: the drawing).
    pub deviations: Deviations,
    /// Friction at the contacts (`reducer.friction`; none: the frictionless model).
    pub friction: Option<Friction>,
    /// The housing's heat path (`reducer.thermal`), for a steady temperature.
    pub thermal: Option<Thermal>,
    /// The torsional compliance of the rest of the reducer (carrier, housing, shafts), in
    /// series with the contacts and pins, rad/(N·mm) (spec:
    /// `reducer.structure_compliance_arcmin_per_knm`); 0: none given. It adds c·T to the
    /// torsion angle of a torsion scene only.
    pub structure_compliance_rad_per_nmm: f64,
    /// ρ, the discs' density, kg/mm³ (spec: `reducer.material.density_kg_per_m3`, kg/m³;
    /// steel's 7,850 by default), for their mass and inertia.
    pub density_kg_per_mm3: f64,
    /// The output's inertia about its axis, kg·mm² (spec: `reducer.output_inertia_kgm2`, in
    /// kg·m²; 0: not given), for the inertia at the input.
    pub output_inertia_kgmm2: f64,
    /// J_r, each roller's inertia about its own axis, kg·mm² (`reducer.roller_inertia_kgm2`,
    /// kg·m²; 0: not given), given only for rollers that turn on their pins: their spin's
    /// share of the inertia at the input (`engine::mass_properties`).
    pub roller_inertia_kgmm2: f64,
}

/// The rating of the crank bearing of a disc (ISO 281): its basic dynamic load rating C and
/// the life exponent p of L10 = (C/P)^p millions of revolutions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrankBearing {
    /// C, N (spec: `dynamic_load_rating_n`).
    pub dynamic_load_rating_n: f64,
    /// p: 10/3 for roller bearings (the default), 3 for ball bearings.
    pub life_exponent: f64,
    /// The bearing's outer diameter, mm: the disc's bore (spec: `outer_diameter_mm`); only the
    /// exported solid (`profile --step`, `--stl`) cuts it.
    pub outer_diameter_mm: Option<f64>,
    /// C0, the basic static load rating (ISO 76), N (spec: `static_load_rating_n`), for the
    /// static safety s0 = C0/the largest bearing force.
    pub static_load_rating_n: Option<f64>,
}

impl CrankBearing {
    /// The life exponent of roller bearings (ISO 281).
    pub const ROLLER_LIFE_EXPONENT: f64 = 10.0 / 3.0;
}

/// Most discs a reducer may have (`reducer.discs`): reducers are built with one to three.
pub const MAX_DISCS: usize = 4;

/// Crank phase of disc k of `count`, rad: 2πk/count (MODEL.md "Several discs").
pub fn disc_phase_rad(k: usize, count: usize) -> f64 {
    std::f64::consts::TAU * k as f64 / count as f64
}

/// Short-amplitude coefficient K1 = e·np/Rp (MODEL.md): the spec refuses K1 ≥ 1 (the locus
/// would loop), a design search's `rules.max_k1` bounds it.
pub fn k1(eccentricity_mm: f64, rollers: usize, roller_circle_radius_mm: f64) -> f64 {
    eccentricity_mm * rollers as f64 / roller_circle_radius_mm
}

/// Root radius of the modified profile, mm: the locus radius Rp + ΔRp (`locus_radius_mm`) less
/// e and the offset Rrp + ΔRrp (`offset_mm`), where the output-pin holes must stop short: the
/// spec's hole rule (`spec::rules`) and a design search's ligaments.
pub fn root_radius_mm(locus_radius_mm: f64, eccentricity_mm: f64, offset_mm: f64) -> f64 {
    locus_radius_mm - eccentricity_mm - offset_mm
}

/// Gap between neighbouring rollers, mm: 2·Rp·sin(π/np) − 2·Rrp (the rollers overlap at
/// ≤ 0): the spec's rule (`spec::rules`) and a design search's `rules.min_roller_gap_mm`.
pub fn roller_gap_mm(roller_circle_radius_mm: f64, roller_radius_mm: f64, rollers: usize) -> f64 {
    let pitch = 2.0 * roller_circle_radius_mm * (std::f64::consts::PI / rollers as f64).sin();
    pitch - 2.0 * roller_radius_mm
}

/// The material around the output-pin holes, mm (the spec refuses a disc with one ≤ 0, a
/// design search's `rules.min_ligament_mm` bounds the smallest).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ligaments {
    /// Between a hole and the tooth root: root − rw − rh.
    pub to_root_mm: f64,
    /// Between neighbouring holes: 2·rw·sin(π/M) − 2·rh.
    pub between_holes_mm: f64,
    /// Between a hole and the disc centre: rw − rh.
    pub to_centre_mm: f64,
}

impl Ligaments {
    /// Of M holes of radius rh on the circle rw, the tooth root at `root_mm`
    /// (Rp + ΔRp − e − (Rrp + ΔRrp)).
    pub fn of(circle_radius_mm: f64, hole_radius_mm: f64, count: usize, root_mm: f64) -> Self {
        let (rw, rh) = (circle_radius_mm, hole_radius_mm);
        Ligaments {
            to_root_mm: root_mm - rw - rh,
            between_holes_mm: 2.0 * rw * (std::f64::consts::PI / count as f64).sin() - 2.0 * rh,
            to_centre_mm: rw - rh,
        }
    }

    /// The smallest of the three, mm.
    pub fn smallest_mm(&self) -> f64 {
        self.between_holes_mm
            .min(self.to_root_mm)
            .min(self.to_centre_mm)
    }
}

impl Design {
    /// Crank phase of disc k of this design, rad (`disc_phase_rad`).
    pub fn disc_phase_rad(&self, k: usize) -> f64 {
        disc_phase_rad(k, self.discs)
    }

    /// The crank's eccentricity as built, e + de, mm: the orbit of every disc centre
    /// (`reducer.deviations.eccentricity_mm` the deviation de; MODEL.md "Part deviations").
    pub fn built_eccentricity_mm(&self) -> f64 {
        self.eccentricity_mm + self.deviations.eccentricity_mm
    }

    /// Short-amplitude coefficient K1 = e·np/Rp (MODEL.md); a disc exists only for K1 < 1.
    pub fn k1(&self) -> f64 {
        k1(
            self.eccentricity_mm,
            self.rollers,
            self.roller_circle_radius_mm,
        )
    }

    /// Contact modulus E* = 1 / ((1−ν1²)/E1 + (1−ν2²)/E2) in MPa (paper Eq. 10).
    pub fn contact_modulus_mpa(&self) -> f64 {
        1.0 / (self.disc_material.compliance_per_mpa() + self.roller_material.compliance_per_mpa())
    }

    /// The largest output torque the first-order geometry is given, N·mm: every roller of
    /// every disc pressed by its own radius Rrp at the largest first-order arm e·nc, on the
    /// paper's law, np·N·(π/4)·E*·L·Rrp·e·nc (3.8e5 N·m for the paper's design). The closed
    /// form keeps the arms of the ideal pose whatever the load; a roller pressed by its own
    /// radius has its centre on the disc's profile, where no contact is left to linearise (the
    /// exact geometry's rollers slide off their flanks long before: the paper's design holds
    /// ~8.5e4 N·m). Below this bound no force can overflow a double; above it the forces are
    /// no contact's (1e300 N·m gave 2e301 N and an infinite bearing force).
    pub fn first_order_torque_bound_nmm(&self) -> f64 {
        let stiffness =
            0.25 * std::f64::consts::PI * self.contact_modulus_mpa() * self.face_width_mm;
        let arm = self.eccentricity_mm * self.teeth as f64;
        (self.rollers * self.discs) as f64 * stiffness * self.roller_radius_mm * arm
    }

    /// Angular position of roller i in the fixed frame: 2πi/np.
    pub fn roller_angle(&self, i: usize) -> f64 {
        std::f64::consts::TAU * i as f64 / self.rollers as f64
    }

    /// Mesh period in crank angle: 2π/np, after which every gap repeats with the roller index
    /// shifted by one; with rollers as built that are not alike, a whole crank turn; with a
    /// form error on the disc, a whole turn of the disc (nc crank turns): the loaded period
    /// without the pins and the tilt (`loaded_period_rad`).
    pub fn mesh_period_rad(&self) -> f64 {
        self.loaded_period_rad(false, false)
    }

    /// Teeth after which the disc as built is itself again: nc/gcd(nc, k₁, k₂, …) over the
    /// orders k of its form error (a term of order k comes back after a turn by 2π·m/nc, m
    /// teeth, when k·m/nc is whole), 1 without one. Order 0 (a constant w) repeats every tooth.
    pub fn form_period_teeth(&self) -> usize {
        let nc = self.teeth;
        let common = (self.deviations.form.iter())
            .filter(|f| f.amplitude_mm() != 0.0)
            .fold(nc, |g, f| gcd(g, f.order));
        nc / common.max(1)
    }

    /// Mesh periods (2π/np of crank each) after which the gaps of all the rollers repeat as a
    /// set, so that the smallest gap over the mesh repeats (MODEL.md "Clearance"). Crank
    /// φ + 2π/np puts roller i where roller i − 1 was at φ, one tooth further round the disc
    /// (its locus parameter 2πi/np + φ/nc advances by 2π/np + 2π/(np·nc) = 2π/nc); the crank
    /// eccentricity and the grinding errors act on every roller and tooth alike. So the set
    /// repeats after P = `form_period_teeth` mesh periods, when the disc has come back to
    /// itself; with rollers as built that are not alike the same roller must come back too,
    /// after lcm(np, P). Paper's design (np 10, nc 9): 1 nominal; a form error of order 3, 3
    /// (108°); of order 2, 9 (324°); rollers as built, 10 (360°), and with a form of order 2,
    /// 90 (3240°, where each roller's own gap repeats, `mesh_period_rad`).
    pub fn clearance_periods(&self) -> usize {
        let p = self.form_period_teeth();
        if self.deviations.moves_rollers() {
            self.rollers / gcd(self.rollers, p) * p
        } else {
            p
        }
    }

    /// The crank period of the smallest gap over the mesh, rad: `clearance_periods` mesh
    /// periods of 2π/np.
    pub fn clearance_period_rad(&self) -> f64 {
        std::f64::consts::TAU * self.clearance_periods() as f64 / self.rollers as f64
    }

    /// Mesh periods per crank turn: np, or 1 when some roller is off its place or size. A
    /// disc with a form error meets every roller with every tooth only over a whole turn of
    /// the disc, nc crank turns (`mesh_period_rad` then says so).
    fn mesh_periods_per_turn(&self) -> usize {
        if self.deviations.moves_rollers() {
            1
        } else {
            self.rollers
        }
    }

    /// Period of the output-pin pattern in crank angle, 2π·nc/(np·M): a pin's arm depends on
    /// γj − φ = 2πj/M − φ·np/nc, and the pattern repeats when that advances by 2π/M.
    pub fn pin_period_rad(&self) -> f64 {
        std::f64::consts::TAU * self.teeth as f64 / (self.rollers * self.pins.count) as f64
    }

    /// Crank period of loaded curves: the mesh period, or, with the output pins modelled, the
    /// least common multiple of it and the pin period (108° for the paper's design: TE = β + βo,
    /// pin and bearing forces repeat only after it). In units of u = 2π/(np·M) the mesh period
    /// is np·M/(periods per turn) and the pin period nc. Pins or holes as built repeat only
    /// after a whole turn of the disc, nc crank turns. `tilted`: the disc is tilted against
    /// the housing (a scene's or the as-built tilt), which, fixed in the housing, gives each
    /// roller its own closing by its fixed place, so that, like rollers not alike, the mesh
    /// repeats only after a whole crank turn (1080° for the paper's design with its 6 pins).
    /// Callers go through `model::period`, which knows the scene's tilt.
    pub fn loaded_period_rad(&self, pins_modelled: bool, tilted: bool) -> f64 {
        let turn = std::f64::consts::TAU;
        let per_turn = if tilted {
            1
        } else {
            self.mesh_periods_per_turn()
        };
        if !self.deviations.form.is_empty() {
            return turn * self.teeth as f64;
        }
        if !pins_modelled {
            return turn / per_turn as f64;
        }
        if self.deviations.moves_pins() {
            return turn * self.teeth as f64;
        }
        let units = self.rollers * self.pins.count;
        let period = pinned_period_units(self.rollers, self.pins.count, self.teeth, per_turn);
        turn / units as f64 * period as f64
    }

    /// Radius of an output-pin hole in the disc: pin radius + e + hole clearance.
    pub fn hole_radius_mm(&self) -> f64 {
        self.pins.pin_radius_mm + self.eccentricity_mm + self.pins.hole_clearance_mm
    }
}

/// Closed forms of the roller-centre locus C(t) = R'(cos t, sin t) − e(cos np·t, sin np·t).
///
/// With c = cos((np − 1)t), expanding C' × C'' and |C'|²:
///   κ_C = N/D,  N = R'² + e²np³ − R'e·np(np + 1)·c,  D = (R'² + e²np² − 2R'e·np·c)^{3/2}.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Locus {
    /// np, the number of rollers.
    pub rollers: usize,
    /// e, the eccentricity, mm.
    pub eccentricity_mm: f64,
    /// R' = Rp + ΔRp, mm.
    pub radius_mm: f64,
}

/// Smallest radius of curvature on the convex part of the locus C, and where.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvexRadius {
    /// The smallest radius of curvature, mm (infinite when the locus is nowhere convex).
    pub radius_mm: f64,
    /// Locus parameter from the tooth root, rad.
    pub t: f64,
}

impl Locus {
    /// (N, D) of κ_C = N/D at c = cos((np − 1)t): (C' × C'', |C'|³).
    #[inline]
    pub fn curvature_parts(&self, c: f64) -> (f64, f64) {
        let (bend, speed2) = self.bend_and_speed2(c);
        (bend, speed2 * speed2.sqrt())
    }

    /// (C' × C'', |C'|²) at c = cos((np − 1)t), mm²/rad² and mm²/rad²: with n = np,
    /// C' × C'' = R'² + e²n³ − R'e·n(n + 1)·c and |C'|² = R'² + e²n² − 2R'e·n·c.
    #[inline]
    pub fn bend_and_speed2(&self, c: f64) -> (f64, f64) {
        let n = self.rollers as f64;
        let (r, e) = (self.radius_mm, self.eccentricity_mm);
        (
            r * r + e * e * n * n * n - r * e * n * (n + 1.0) * c,
            r * r + e * e * n * n - 2.0 * r * e * n * c,
        )
    }

    /// κ_C at c = cos((np − 1)t), 1/mm, positive where convex.
    pub fn curvature_at(&self, c: f64) -> f64 {
        let (numerator, denominator) = self.curvature_parts(c);
        numerator / denominator
    }

    /// The smallest convex radius of curvature of C (= 1/max κ_C), in closed form.
    ///
    /// κ_C = (A − B·c)/(P − Q·c)^{3/2}, A = R'² + e²n³, B = R'e·n(n + 1), P = R'² + e²n²,
    /// Q = 2R'e·n. The numerator of dκ/dc, (3QA − 2BP)/2 − (QB/2)·c, is linear and decreasing
    /// in c, so κ has a single maximum at c* = (3QA − 2BP)/(QB), clamped to [−1, 1] (c = 1 is
    /// the tooth root, −1 the tip). The point is t = acos(c*)/(n − 1) from the root, the same on
    /// every tooth and both flanks.
    pub fn min_convex_radius(&self) -> ConvexRadius {
        let n = self.rollers as f64;
        let (r, e) = (self.radius_mm, self.eccentricity_mm);
        let (a, b) = (r * r + e * e * n * n * n, r * e * n * (n + 1.0));
        let (p, q) = (r * r + e * e * n * n, 2.0 * r * e * n);
        let c = ((3.0 * q * a - 2.0 * b * p) / (q * b)).clamp(-1.0, 1.0);
        let k = self.curvature_at(c);
        ConvexRadius {
            radius_mm: if k > 0.0 { 1.0 / k } else { f64::INFINITY },
            t: c.acos() / (n - 1.0),
        }
    }
}

impl Design {
    /// The roller-centre locus of this design under a modification (R' = Rp + ΔRp).
    pub fn locus(&self, m: &Modification) -> Locus {
        Locus {
            rollers: self.rollers,
            eccentricity_mm: self.eccentricity_mm,
            radius_mm: self.roller_circle_radius_mm + m.shift_mm,
        }
    }
}

/// Greatest common divisor (Euclid); gcd(a, 0) = a.
pub(crate) fn gcd(mut a: usize, mut b: usize) -> usize {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// The crank period of loaded curves with the output pins modelled, in units u = 2π/(np·M):
/// the least common multiple of the mesh period, np·M/`per_turn` units (`per_turn` mesh
/// periods in a crank turn: np, or 1 when the mesh repeats only after a whole turn), and the
/// pin period, nc units (`Design::pin_period_rad`). 36 units (108°) for the paper's design
/// (np 10, M 6, nc 9). The one home of the arithmetic of `Design::loaded_period_rad` and of a
/// design search's scenes, which need it before their design exists.
pub fn pinned_period_units(rollers: usize, pins: usize, teeth: usize, per_turn: usize) -> usize {
    let mesh = rollers * pins / per_turn;
    mesh / gcd(mesh, teeth) * teeth
}
