//! The modified disc profile, evaluated exactly (closed form, analytic derivatives).
//!
//! Frame: the disc frame, origin at the disc centre, x along the disc's own reference line
//! (MODEL.md: roller 0 sits in the root at t = 0 when φ = 0). Units: mm and rad.
//!
//! Roller-centre locus (MODEL.md "Profile", after paper Eq. 6):
//!   C(t) = R'·(cos t, sin t) − e·(cos np·t, sin np·t),   R' = Rp + ΔRp,
//! disc profile, the inward offset of the locus by r' = Rrp + ΔRrp, turned by Δδ:
//!   Γ(t) = Rot(Δδ)·(C(t) − r'·N(t)),   N the outward unit normal of C.
//! With the tangent T = C'/|C'| and curvature κ_C = (C' × C'')/|C'|³ (positive where convex),
//! Γ'(t) = |C'|·(1 − r'·κ_C)·T, so Γ is regular (no cusp, no undercut) iff r'·κ_C < 1 everywhere:
//! r' must be smaller than the smallest convex radius of curvature of C.

use super::form_error::FormError;
use super::{cmul, cross, expi_minus_one, rotate, sin_cos, unit, z_cross, Vec2};
use crate::model::{Design, FormTerm, Locus, Modification};
use std::f64::consts::PI;
use std::sync::Arc;

/// Largest step of the closest-point Newton iterations, rad of t.
const MAX_STEP: f64 = 0.05;
/// Most steps of the closest-point Newton iterations.
const MAX_ITER: usize = 60;

/// The guarded Newton step on h(t) = (C(t) − q)·C'(t) = 0 of a closest-point iteration: −h/h'
/// within ±`MAX_STEP`, or a full `MAX_STEP` downhill where h' ≤ 0 (not a minimum yet).
/// Inlined as the three copies it replaced were: `closest_point_in_frame` runs once per roller
/// and angle, and called it cost 0.1 % more instructions over a whole check.
#[inline]
fn newton_step(h: f64, dh: f64) -> f64 {
    if dh > 0.0 {
        (-h / dh).clamp(-MAX_STEP, MAX_STEP)
    } else {
        -h.signum() * MAX_STEP
    }
}

/// Disc profile of one design and modification, and, for a disc as built, its form error
/// (`with_form`): Γ(t) = Rot(Δδ)·(C(t) − (r' + w(t))·N(t)).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// Number of rollers np (lobes of the locus term).
    pub rollers: usize,
    /// Eccentricity e, mm.
    pub eccentricity_mm: f64,
    /// R' = Rp + ΔRp, mm.
    pub locus_radius_mm: f64,
    /// r' = Rrp + ΔRrp, mm.
    pub offset_mm: f64,
    /// Δδ, rad, counter-clockwise.
    pub rotation_rad: f64,
    rot_cos: f64,
    rot_sin: f64,
    /// The form error w(t) (`FormError::default()` for the profile as drawn); shared by the
    /// clones a sweep hands its workers.
    form: Arc<FormError>,
}

/// Locus value and its first two derivatives with respect to t.
#[derive(Debug, Clone, Copy)]
pub struct LocusJet {
    pub c: Vec2,
    pub d1: Vec2,
    pub d2: Vec2,
}

/// sin and cos of t and of n·t, carried through a Newton iteration.
#[derive(Debug, Clone, Copy)]
struct Trig {
    s: f64,
    c: f64,
    sn: f64,
    cn: f64,
}

impl Trig {
    #[inline]
    fn at(t: f64, n: f64) -> Trig {
        let (s, c) = t.sin_cos();
        let (sn, cn) = (n * t).sin_cos();
        Trig { s, c, sn, cn }
    }

    /// The trig of t + dt from that of dt (`by`), by angle addition.
    #[inline]
    fn turned_by(&self, by: &Trig) -> Trig {
        Trig {
            s: self.s * by.c + self.c * by.s,
            c: self.c * by.c - self.s * by.s,
            sn: self.sn * by.cn + self.cn * by.sn,
            cn: self.cn * by.cn - self.sn * by.sn,
        }
    }

    /// The trig of t + dt by angle addition (exact libm calls when n·dt is not small).
    #[inline]
    fn advanced(&self, t: f64, dt: f64, n: f64) -> Trig {
        if (n * dt).abs() > 0.05 {
            return Trig::at(t + dt, n);
        }
        let (s, c) = sin_cos(dt);
        let (sn, cn) = sin_cos(n * dt);
        self.turned_by(&Trig { s, c, sn, cn })
    }
}

/// Foot of the normal from a point to Γ. Disc frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Foot {
    /// Locus parameter t of the foot (wrapped into [0, 2π)).
    pub t: f64,
    /// Closest point on Γ, mm.
    pub point: Vec2,
    /// Outward unit normal of Γ at the foot (points out of the disc material).
    pub normal: Vec2,
    /// Signed distance of the query point from Γ along `normal`, mm: positive outside the disc.
    pub signed_distance_mm: f64,
    /// Signed distance of the query point from the locus C along `normal`, mm
    /// (`signed_distance_mm` − r', without the rounding of adding and removing r').
    pub locus_distance_mm: f64,
}

/// The reference of a closest-point search near a locus point L(t_ref) =
/// r_ref·e^{i·t_ref} − e·e^{i·np·t_ref}: `base` = e^{i·t_ref}, `lobe` = e^{i·np·t_ref}.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocusFrame {
    pub t_ref: f64,
    pub r_ref: f64,
    pub base: Vec2,
    pub lobe: Vec2,
}

/// The guarded Newton iteration left its bracket or ran out of iterations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosestPointFailure {
    pub t_start: f64,
    pub t_last: f64,
    pub iterations: usize,
}

impl Profile {
    pub fn new(design: &Design, modification: &Modification) -> Self {
        Self::from_parts(
            design.rollers,
            design.eccentricity_mm,
            design.roller_circle_radius_mm + modification.shift_mm,
            design.roller_radius_mm + modification.equidistant_mm,
            modification.rotation_within_pitch(design.teeth),
        )
    }

    pub fn from_parts(
        rollers: usize,
        eccentricity_mm: f64,
        locus_radius_mm: f64,
        offset_mm: f64,
        rotation_rad: f64,
    ) -> Self {
        let (rot_sin, rot_cos) = rotation_rad.sin_cos();
        Profile {
            rollers,
            eccentricity_mm,
            locus_radius_mm,
            offset_mm,
            rotation_rad,
            rot_cos,
            rot_sin,
            form: Arc::new(FormError::default()),
        }
    }

    /// This profile with the form error `form` along its normal (MODEL.md "Measured profiles";
    /// positive w: material missing).
    pub fn with_form(mut self, form: &[FormTerm]) -> Self {
        self.form = Arc::new(FormError::new(form));
        self
    }

    /// The disc of `design` as ground: `modification` plus the design's grinding errors
    /// (`Deviations::ground`), with its form error; the profile every check meshes, the one the
    /// mass and the solid exports are of.
    pub fn as_ground(design: &Design, modification: &Modification) -> Self {
        let d = &design.deviations;
        Profile::new(design, &d.ground(modification)).with_form(&d.form)
    }

    /// Whether the profile carries a form error.
    pub fn has_form(&self) -> bool {
        self.form.is_some()
    }

    /// The form error the profile carries.
    pub fn form(&self) -> &FormError {
        &self.form
    }

    /// C, C', C'' at t (mm, mm/rad, mm/rad²).
    #[inline]
    pub fn locus_jet(&self, t: f64) -> LocusJet {
        self.jet_from(&Trig::at(t, self.rollers as f64))
    }

    /// C, C', C'' from the sines and cosines of t and n·t.
    #[inline]
    fn jet_from(&self, trig: &Trig) -> LocusJet {
        let n = self.rollers as f64;
        let (r, e) = (self.locus_radius_mm, self.eccentricity_mm);
        let Trig { s, c, sn, cn } = *trig;
        LocusJet {
            c: Vec2::new(r * c - e * cn, r * s - e * sn),
            d1: Vec2::new(-r * s + e * n * sn, r * c - e * n * cn),
            d2: Vec2::new(-r * c + e * n * n * cn, -r * s + e * n * n * sn),
        }
    }

    /// The largest moment arm of a foot of Γ about the disc centre, mm: the distance from the
    /// centre to Γ's normal there. Every normal of the locus C(t) = R′e^{it} − e·e^{i·np·t}
    /// passes through the pitch point nc·e·e^{i·np·t} (C − that point = −iC′), at most e·nc
    /// from the centre. A form error w tilts Γ's normal from C's by θ, with
    /// tan θ = |w′|/((1 − (r′ + w)·κ_C)·|C′|) (Γ′ = (1 − (r′ + w)·κ_C)·|C′|·T − w′·N), which adds
    /// at most |Γ|·sin θ ≤ (R′ + e + r′ + |w|)·tan θ; |C′| ≥ R′ − e·np, and κ_C is at most its
    /// single maximum, 1/`Locus::min_convex_radius` (0 where the locus is nowhere convex).
    /// Infinite when that speed is not bounded away from zero. With 1e-9 for round-off.
    pub fn arm_bound_mm(&self) -> f64 {
        let (r, e) = (self.locus_radius_mm, self.eccentricity_mm);
        let n = self.rollers as f64;
        let pitch = e * (n - 1.0);
        if !self.has_form() {
            return pitch * (1.0 + 1e-9);
        }
        let convex = 1.0 / self.locus().min_convex_radius().radius_mm;
        let w = self.form.bound_mm();
        let speed = (1.0 - (self.offset_mm + w) * convex) * (r - e * n);
        if speed <= 0.0 || r - e * n <= 0.0 {
            return f64::INFINITY;
        }
        let tilt = self.form.slope_bound() / speed;
        (pitch + (r + e + self.offset_mm + w) * tilt) * (1.0 + 1e-9)
    }

    /// The extrema of |C| in turn, disc frame, mm: C(kπ/nc) for k = 0 … 2nc − 1
    /// (|C|² = R'² + e² − 2R'e·cos(nc·t)), a root (|C| = R' − e) at even k, a tip (R' + e) at
    /// odd k. Between two in turn a foot's moment arm keeps its sign: the arm is the distance
    /// from the disc centre to the normal at the foot, zero only where the normal is radial, at
    /// an extremum of |C|.
    pub fn arc_ends(&self) -> Vec<Vec2> {
        let nc = self.rollers - 1;
        let (r, e) = (self.locus_radius_mm, self.eccentricity_mm);
        (0..2 * nc)
            .map(|k| {
                let radius = if k % 2 == 0 { r - e } else { r + e };
                self.turned(unit(k as f64 * PI / nc as f64) * radius)
            })
            .collect()
    }

    /// C''' at t, mm/rad³ (for the derivative of the curvature).
    pub fn locus_d3(&self, t: f64) -> Vec2 {
        let n = self.rollers as f64;
        let (r, e) = (self.locus_radius_mm, self.eccentricity_mm);
        let Trig { s, c, sn, cn } = Trig::at(t, n);
        Vec2::new(r * s - e * n.powi(3) * sn, -r * c + e * n.powi(3) * cn)
    }

    /// Signed curvature of the locus, κ_C = (C' × C'')/|C'|³, 1/mm; positive where convex.
    /// In closed form (expand C' × C'' and |C'|² with c = cos((n − 1)t)):
    ///   κ_C = (R'² + e²n³ − R'e·n(n + 1)·c) / (R'² + e²n² − 2R'e·n·c)^{3/2}.
    pub fn locus_curvature(&self, t: f64) -> f64 {
        self.locus()
            .curvature_at(((self.rollers - 1) as f64 * t).cos())
    }

    /// The locus C of this profile, for its closed forms.
    pub fn locus(&self) -> Locus {
        Locus {
            rollers: self.rollers,
            eccentricity_mm: self.eccentricity_mm,
            radius_mm: self.locus_radius_mm,
        }
    }

    /// dκ_C/dt = (C' × C''')/|C'|³ − 3·κ_C·(C'·C'')/|C'|², 1/(mm·rad).
    pub fn locus_curvature_derivative(&self, t: f64) -> f64 {
        let j = self.locus_jet(t);
        let s2 = j.d1.norm_squared();
        cross(j.d1, self.locus_d3(t)) / s2.powf(1.5)
            - 3.0 * cross(j.d1, j.d2) / s2.powf(1.5) * j.d1.dot(&j.d2) / s2
    }

    /// The outward unit normal, unturned, of a curve whose derivative is `d1`: −ẑ × d1/|d1|.
    fn unrotated_normal(d1: Vec2) -> Vec2 {
        Vec2::new(d1.y, -d1.x) / d1.norm()
    }

    fn turned(&self, v: Vec2) -> Vec2 {
        rotate(v, self.rot_cos, self.rot_sin)
    }

    fn unturned(&self, v: Vec2) -> Vec2 {
        rotate(v, self.rot_cos, -self.rot_sin)
    }

    /// Γ(t), mm, disc frame.
    pub fn point(&self, t: f64) -> Vec2 {
        let j = self.locus_jet(t);
        let w = self.form.jet(t).0;
        self.turned(j.c - (self.offset_mm + w) * Self::unrotated_normal(j.d1))
    }

    /// Outward unit normal of Γ at t, disc frame (that of C when there is no form error).
    pub fn normal(&self, t: f64) -> Vec2 {
        if self.has_form() {
            return self.turned(Self::unrotated_normal(self.formed_jet(t).d1));
        }
        self.turned(Self::unrotated_normal(self.locus_jet(t).d1))
    }

    /// Γ'(t), mm/rad, disc frame: |C'|·(1 − r'κ_C)·T without a form error.
    pub fn tangent(&self, t: f64) -> Vec2 {
        if self.has_form() {
            return self.turned(self.formed_jet(t).d1);
        }
        let j = self.locus_jet(t);
        let k = cross(j.d1, j.d2) / j.d1.norm().powi(3);
        self.turned(j.d1 * (1.0 - self.offset_mm * k))
    }

    /// |Γ'(t)|, mm/rad, of the profile without its form error, in closed form in
    /// c = cos((n − 1)t): with κ_C = (C' × C'')/v³ and v = |C'| (`Locus::bend_and_speed2`),
    /// |Γ'| = v·(1 − r'κ_C) = v − r'·(C' × C'')/v². One cosine and one square root, where
    /// `tangent` takes two sine-cosine pairs (an arc length's quadrature calls it often).
    pub fn speed(&self, t: f64) -> f64 {
        let c = ((self.rollers - 1) as f64 * t).cos();
        let (bend, speed2) = self.locus().bend_and_speed2(c);
        speed2.sqrt() - self.offset_mm * bend / speed2
    }

    /// Signed curvature of Γ, κ_Γ = κ_C/(1 − r'κ_C), 1/mm; positive where the disc is convex.
    /// Its reciprocal is ρ_C − r' (the offset shortens convex radii by r'). With a form error,
    /// (Γ' × Γ'')/|Γ'|³ of the formed profile (`formed_jet`).
    pub fn curvature(&self, t: f64) -> f64 {
        if self.has_form() {
            let g = self.formed_jet(t);
            return cross(g.d1, g.d2) / g.d1.norm().powi(3);
        }
        self.curvature_at(((self.rollers - 1) as f64 * t).cos())
    }

    /// Γ, Γ' and Γ'' of the profile with its form error, unturned, from the Frenet frame of
    /// C: with v = |C'|, T = C'/v, N the outward normal, N' = v·κ_C·T, T' = −v·κ_C·N and
    /// ρ = r' + w,
    ///   Γ'  = A·T + B·N,  A = v·(1 − ρκ_C), B = −w',
    ///   Γ'' = (A' + B·v·κ_C)·T + (B' − A·v·κ_C)·N,  A' = v'·(1 − ρκ_C) − v·(w'κ_C + ρκ_C'),
    /// v' = C'·C''/v, B' = −w''.
    fn formed_jet(&self, t: f64) -> LocusJet {
        let j = self.locus_jet(t);
        self.formed_from(&j, self.locus_d3(t), self.form.jet(t))
    }

    /// `formed_jet` from the locus jet, the third derivative of C and (w, w', w'').
    fn formed_from(&self, j: &LocusJet, d3: Vec2, (w, w1, w2): (f64, f64, f64)) -> LocusJet {
        let v = j.d1.norm();
        let tangent = j.d1 / v;
        let normal = Vec2::new(tangent.y, -tangent.x);
        let kappa = cross(j.d1, j.d2) / (v * v * v);
        let dv = j.d1.dot(&j.d2) / v;
        let dkappa = cross(j.d1, d3) / (v * v * v) - 3.0 * kappa * j.d1.dot(&j.d2) / (v * v);
        let rho = self.offset_mm + w;
        let a = v * (1.0 - rho * kappa);
        let b = -w1;
        let da = dv * (1.0 - rho * kappa) - v * (w1 * kappa + rho * dkappa);
        let db = -w2;
        LocusJet {
            c: j.c - rho * normal,
            d1: tangent * a + normal * b,
            d2: tangent * (da + b * v * kappa) + normal * (db - a * v * kappa),
        }
    }

    /// κ_Γ from c = cos((n − 1)t): with κ_C = N/D (`Locus::curvature_at`),
    /// κ_Γ = κ_C/(1 − r'κ_C) = N/(D − r'·N), one division.
    pub fn curvature_at(&self, c: f64) -> f64 {
        let (numerator, denominator) = self.locus().curvature_parts(c);
        numerator / (denominator - self.offset_mm * numerator)
    }

    /// A lower bound of the reach of the locus C, mm: a point closer to C than the reach has one
    /// nearest point on C, and a foot of the normal from it (a stationary point of the
    /// distance, what Newton finds) closer than the reach is that nearest point (Federer,
    /// "Curvature measures", 1959, Thm 4.8 (12)).
    ///
    /// The reach of a closed C² curve is the smaller of its least radius of curvature and half
    /// its shortest double normal, a chord normal to the curve at both ends (Aamari et al.,
    /// "Estimating the reach of a manifold", 2019, Thm 3.4). Both are bounded in closed form
    /// (c = cos((np − 1)t), n = np, R' the locus radius):
    /// - curvature: κ_C(c) has a single stationary point, its maximum (`Locus::min_convex_radius`),
    ///   so max |κ_C| is there or at c = ±1 (root, tip);
    /// - double normals: |C(a) − C(b)| ≥ 2R'·|sin(Δ/2)| − 2e·|sin(n·Δ/2)| ≥ 2(R' − e·n)·|sin(Δ/2)|
    ///   (Δ = a − b, and |sin(n·x)| ≤ n·|sin x|). Along a double normal from a to b the tangent
    ///   turns by at least π/2: it is ⊥ to the chord at a and ∥ to it somewhere between (mean
    ///   value theorem). It turns at dθ/dt = C' × C''/|C'|², a ratio of functions linear in c,
    ///   hence largest in magnitude at c = ±1: ω = max(|R' − e·n²|/(R' − e·n),
    ///   (R' + e·n²)/(R' + e·n)). So |Δ| ≥ π/(2ω) on the shorter arc, and a double normal is at
    ///   least 2(R' − e·n)·sin(π/(4ω)) long.
    pub fn locus_reach_bound_mm(&self) -> f64 {
        let locus = self.locus();
        let n = self.rollers as f64;
        let (r, e) = (self.locus_radius_mm, self.eccentricity_mm);
        let slowest = r - e * n;
        if slowest <= 0.0 {
            return 0.0;
        }
        let convex = 1.0 / locus.min_convex_radius().radius_mm;
        let curvature = [locus.curvature_at(1.0), locus.curvature_at(-1.0), convex]
            .into_iter()
            .fold(0.0, |m: f64, k| m.max(k.abs()));
        let turn_rate = ((r - e * n * n).abs() / slowest).max((r + e * n * n) / (r + e * n));
        let shortest_arc = (0.5 * PI / turn_rate).min(PI);
        (1.0 / curvature).min(slowest * (0.5 * shortest_arc).sin())
    }

    /// Closest point on Γ to `p` (disc frame) within half a roller pitch (π/np) of `t_start`,
    /// by guarded Newton.
    ///
    /// Stationarity of |Γ(t) − p|² is (Γ − p)·Γ' = 0. Because Γ' ∥ T and N ⊥ T, for a regular
    /// profile this is exactly (C(t) − p)·C'(t) = 0, so the iteration runs on
    ///   h(t) = (C − p)·C',   h'(t) = |C'|² + (C − p)·C''.
    /// Guards: a step is at most 0.05 rad, a non-positive h' takes a bounded descent step, and
    /// the foot must stay within half a roller pitch (π/np) of `t_start`.
    ///
    /// Newton finds the local minimum of the distance around its start. A roller pushed
    /// towards the opposite flank of its tooth space (interference, a lagging disc) can be
    /// nearer to that flank, so Newton also starts from every local minimum of a coarse scan of
    /// the reach, and the nearest foot wins.
    pub fn closest_point(&self, p: Vec2, t_start: f64) -> Result<Foot, ClosestPointFailure> {
        const SCAN: usize = 32;
        let q = self.unturned(p);
        let t0 = t_start.rem_euclid(std::f64::consts::TAU);
        let reach = PI / self.rollers as f64;
        let dt = 2.0 * reach / SCAN as f64;
        let ts = |k: usize| t0 - reach + dt * k as f64;
        // The scan's sines and cosines by turning the first by a fixed step (angle addition,
        // ~33 roundings of ε at the end: the scan only ranks distances to seed Newton), instead
        // of two libm calls per parameter.
        let turn = Trig::at(dt, self.rollers as f64);
        let mut trig = Trig::at(ts(0), self.rollers as f64);
        let mut ds = [0.0; SCAN + 1];
        for d in &mut ds {
            let j = self.jet_from(&trig);
            *d = (j.c - self.offset_mm * Self::unrotated_normal(j.d1) - q).norm();
            trig = trig.turned_by(&turn);
        }
        let seeds = (1..SCAN)
            .filter(|&k| ds[k] <= ds[k - 1] && ds[k] <= ds[k + 1])
            .map(ts);
        let mut best = self.newton(q, t0, t0, reach);
        for seed in seeds {
            if let Ok(foot) = self.newton(q, t0, seed, reach) {
                let nearer = match &best {
                    Ok(b) => foot.signed_distance_mm.abs() < b.signed_distance_mm.abs(),
                    Err(_) => true,
                };
                if nearer {
                    best = Ok(foot);
                }
            }
        }
        best.map_err(|failure| ClosestPointFailure { t_start, ..failure })
    }

    /// Foot of `p` (disc frame) by the guarded Newton iteration of `closest_point` from
    /// `t_start` alone, without its scan for other local minima: the nearest foot when `t_start`
    /// is the foot of a nearby point (a warm start), at a fraction of the cost.
    pub fn closest_point_from(&self, p: Vec2, t_start: f64) -> Result<Foot, ClosestPointFailure> {
        let t0 = t_start.rem_euclid(std::f64::consts::TAU);
        self.newton(self.unturned(p), t0, t0, PI / self.rollers as f64)
    }

    /// Guarded Newton from `seed` for the foot of `q` (`q` in the unturned frame); the foot must
    /// stay within `reach` of `t0`.
    fn newton(&self, q: Vec2, t0: f64, seed: f64, reach: f64) -> Result<Foot, ClosestPointFailure> {
        let mut t = seed;
        let n = self.rollers as f64;
        // sin/cos are computed once; Newton updates advance them by angle addition.
        let mut trig = Trig::at(t, n);
        for iteration in 1..=MAX_ITER {
            let j = self.jet_from(&trig);
            let d = j.c - q;
            let h = d.dot(&j.d1);
            let dh = j.d1.norm_squared() + d.dot(&j.d2);
            // At a minimum whose h is down to its round-off (products of coordinates ~|C|, |p|
            // with |C'|), the foot is found: near a degenerate foot (the point close to the
            // centre of curvature of a concave flank, h' ≈ 0) the step −h/h' is round-off noise
            // that need not fall below 1e-13 rad, and the iteration would run out.
            let noise = 64.0 * f64::EPSILON * (j.c.norm() + q.norm()) * j.d1.norm();
            if dh > 0.0 && h.abs() <= noise {
                return self.foot_from(t, &j, q);
            }
            let step = newton_step(h, dh);
            if step.abs() <= 1e-13 {
                return self.foot_from(t, &j, q);
            }
            trig = trig.advanced(t, step, n);
            t += step;
            if (t - t0).abs() > reach || !t.is_finite() {
                return Err(ClosestPointFailure {
                    t_start: t0,
                    t_last: t,
                    iterations: iteration,
                });
            }
            // Newton is quadratic here (h' > 0 and the step is tiny): the error after this step
            // is ~ (h''/2h')·step² < 1e-15 rad, so the jet at the new t is the answer.
            if dh > 0.0 && step.abs() <= 1e-8 {
                return self.foot_from(t, &self.jet_from(&trig), q);
            }
        }
        Err(ClosestPointFailure {
            t_start: t0,
            t_last: t,
            iterations: MAX_ITER,
        })
    }

    /// Closest point on Γ to the point q = e^{−iα}·L(t_ref) + w (disc frame), where
    /// L(t) = r_ref·e^{it} − e·e^{i·np·t} is a locus of this profile's eccentricity and lobes,
    /// α a rotation and w a vector, both small.
    ///
    /// A roller centre sits on such a locus (r_ref = Rp, t_ref its own locus parameter), so this
    /// is the roller's closest point without forming C(t) − q from two vectors of size ~Rp: that
    /// difference, the sub-micrometre approach of a lightly loaded contact, would carry a
    /// rounding of a few ulp of Rp (~1e-14 mm), too much for the 1e-9 balance. Here
    ///   C(t_ref + s) − q = e^{i·t_ref}·((R' − r_ref) + R'·(e^{is} − 1))
    ///                      − e·e^{i·np·t_ref}·(e^{i·np·s} − 1) − (e^{−iα} − 1)·L(t_ref) − w
    /// with e^{ix} − 1 = (cos x − 1, sin x) formed without cancellation: every term is formed
    /// from small quantities. Same iteration and guards as `closest_point`, in s = t − t_ref.
    pub fn closest_point_near_locus(
        &self,
        t_ref: f64,
        r_ref: f64,
        alpha: f64,
        w: Vec2,
        t_start: f64,
    ) -> Result<Foot, ClosestPointFailure> {
        let frame = self.frame(t_ref, r_ref);
        let s0 = super::wrap_pi(t_start - t_ref);
        self.closest_point_in_frame(&frame, alpha, w, s0)
    }

    /// The frame of `closest_point_near_locus` for one reference parameter.
    pub fn frame(&self, t_ref: f64, r_ref: f64) -> LocusFrame {
        let n = self.rollers as f64;
        LocusFrame {
            t_ref,
            r_ref,
            base: unit(t_ref),
            lobe: unit(n * t_ref),
        }
    }

    /// `closest_point_near_locus` in a prepared frame, starting at s = `s_start`. The sines and
    /// cosines of s and np·s are carried through the Newton iteration as e^{is} − 1 and
    /// e^{i·np·s} − 1, advanced by angle addition: no trigonometric call per iteration and no
    /// cancellation.
    pub fn closest_point_in_frame(
        &self,
        frame: &LocusFrame,
        alpha: f64,
        w: Vec2,
        s_start: f64,
    ) -> Result<Foot, ClosestPointFailure> {
        let n = self.rollers as f64;
        let (e, rl) = (self.eccentricity_mm, self.locus_radius_mm);
        let LocusFrame {
            base,
            lobe,
            r_ref,
            t_ref,
        } = *frame;
        // The profile turned by Δδ is the query turned back by Δδ.
        let alpha = alpha + self.rotation_rad;
        let w = self.unturned(w);
        let locus_ref = base * r_ref - lobe * e;
        let fixed = -(cmul(expi_minus_one(-alpha), locus_ref) + w);
        let at = |e1: Vec2, en: Vec2| {
            let et = base + cmul(base, e1);
            let ent = lobe + cmul(lobe, en);
            let radial = Vec2::new(rl - r_ref, 0.0) + e1 * rl;
            let diff = cmul(base, radial) - cmul(lobe, en) * e + fixed;
            let v = et * rl - ent * (e * n);
            let d1 = z_cross(v);
            let d2 = ent * (e * n * n) - et * rl;
            (et, ent, diff, d1, d2)
        };
        let foot = |s: f64, e1: Vec2, en: Vec2| {
            let (et, ent, diff, d1, _) = at(e1, en);
            let normal = Self::unrotated_normal(d1);
            if self.has_form() {
                let at_foot = diff - self.offset_mm * normal;
                return self.formed_foot(t_ref + s, (et, ent), at_foot);
            }
            let point = et * rl - ent * e - self.offset_mm * normal;
            let locus_distance_mm = -diff.dot(&normal);
            Ok(Foot {
                t: super::wrap_tau(t_ref + s),
                point: self.turned(point),
                normal: self.turned(normal),
                signed_distance_mm: self.offset_mm + locus_distance_mm,
                locus_distance_mm,
            })
        };
        let reach = PI / self.rollers as f64;
        let mut s = s_start;
        let (mut e1, mut en) = (expi_minus_one(s), expi_minus_one(n * s));
        for iteration in 1..=MAX_ITER {
            let (_, _, diff, d1, d2) = at(e1, en);
            let h = diff.dot(&d1);
            let dh = d1.norm_squared() + diff.dot(&d2);
            let step = newton_step(h, dh);
            if step.abs() <= 1e-13 {
                return foot(s, e1, en);
            }
            let (d_1, d_n) = (expi_minus_one(step), expi_minus_one(n * step));
            e1 += cmul(e1, d_1) + d_1;
            en += cmul(en, d_n) + d_n;
            s += step;
            if (s - s_start).abs() > reach || !s.is_finite() {
                return Err(ClosestPointFailure {
                    t_start: t_ref + s_start,
                    t_last: t_ref + s,
                    iterations: iteration,
                });
            }
            // Quadratic convergence: after a step this small the error is ~1e-16 rad.
            if dh > 0.0 && step.abs() <= 1e-8 {
                return foot(s, e1, en);
            }
        }
        Err(ClosestPointFailure {
            t_start: t_ref + s_start,
            t_last: t_ref + s,
            iterations: MAX_ITER,
        })
    }

    fn foot_from(&self, t: f64, j: &LocusJet, q: Vec2) -> Result<Foot, ClosestPointFailure> {
        let n = Self::unrotated_normal(j.d1);
        let point = j.c - self.offset_mm * n;
        if self.has_form() {
            let n_t = self.rollers as f64 * t;
            let trig = (unit(t), unit(n_t));
            return self.formed_foot(t, trig, point - q);
        }
        Ok(Foot {
            t: super::wrap_tau(t),
            point: self.turned(point),
            normal: self.turned(n),
            signed_distance_mm: (q - point).dot(&n),
            locus_distance_mm: (q - j.c).dot(&n),
        })
    }

    /// The foot on the profile with its form error, from the foot t0 on the profile without it
    /// (`at_foot` = Γ0(t0) − q, unturned, formed from small quantities by the caller; `trig`
    /// = (e^{i·t0}, e^{i·np·t0})): Newton on h(t) = (Γ(t) − q)·Γ'(t) with the formed jet
    /// (`formed_from`), where Γ(t) − q = at_foot + (C(t) − C(t0)) − r'·(N(t) − N(t0)) −
    /// w(t)·N(t), every term small. A form error of micrometres moves the foot by about
    /// |w'|/|Γ'| rad: two or three steps.
    fn formed_foot(
        &self,
        t0: f64,
        (base, lobe): (Vec2, Vec2),
        at_foot: Vec2,
    ) -> Result<Foot, ClosestPointFailure> {
        const MAX_ITER: usize = 30;
        let n = self.rollers as f64;
        let (e, rl, r) = (self.eccentricity_mm, self.locus_radius_mm, self.offset_mm);
        let jet_at = |e1: Vec2, en: Vec2| {
            let et = base + cmul(base, e1);
            let ent = lobe + cmul(lobe, en);
            let jet = LocusJet {
                c: et * rl - ent * e,
                d1: z_cross(et * rl - ent * (e * n)),
                d2: ent * (e * n * n) - et * rl,
            };
            let d3 = z_cross(ent * (e * n * n * n) - et * rl);
            let moved = cmul(base, e1) * rl - cmul(lobe, en) * e;
            (jet, d3, moved)
        };
        let n0 = Self::unrotated_normal(jet_at(Vec2::zeros(), Vec2::zeros()).0.d1);
        let reach = PI / self.rollers as f64;
        let mut s = 0.0;
        for iteration in 1..=MAX_ITER {
            let (jet, d3, moved) = jet_at(expi_minus_one(s), expi_minus_one(n * s));
            let form = self.form.jet(t0 + s);
            let g = self.formed_from(&jet, d3, form);
            let normal_c = Self::unrotated_normal(jet.d1);
            let d = at_foot + moved - (normal_c - n0) * r - normal_c * form.0;
            let h = d.dot(&g.d1);
            let dh = g.d1.norm_squared() + d.dot(&g.d2);
            let step = newton_step(h, dh);
            if dh > 0.0 && step.abs() <= 1e-14 {
                let normal = Self::unrotated_normal(g.d1);
                let signed = -d.dot(&normal);
                return Ok(Foot {
                    t: super::wrap_tau(t0 + s),
                    point: self.turned(g.c),
                    normal: self.turned(normal),
                    signed_distance_mm: signed,
                    locus_distance_mm: signed - r,
                });
            }
            s += step;
            if s.abs() > reach || !s.is_finite() {
                return Err(ClosestPointFailure {
                    t_start: t0,
                    t_last: t0 + s,
                    iterations: iteration,
                });
            }
        }
        Err(ClosestPointFailure {
            t_start: t0,
            t_last: t0 + s,
            iterations: MAX_ITER,
        })
    }
}
