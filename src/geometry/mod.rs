//! Geometry of the disc and the rollers: exact profile, clearance, design-rule checks.

pub mod clearance;
pub mod disc_mesh;
pub mod disc_solid;
pub mod first_order;
pub mod form_error;
pub mod mass_properties;
pub mod mesh_minimum;
pub mod placement;
pub mod polyline;
pub mod profile;
pub mod roller_spin;

pub type Vec2 = nalgebra::Vector2<f64>;

/// 2-D cross product a × b = a.x·b.y − a.y·b.x (z of the 3-D cross product).
#[inline]
pub fn cross(a: Vec2, b: Vec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// ẑ × v = (−v.y, v.x): `v` turned a quarter turn counter-clockwise.
#[inline]
pub fn z_cross(v: Vec2) -> Vec2 {
    Vec2::new(-v.y, v.x)
}

/// The angle of `v` from the unit direction `from`, counter-clockwise, in [−π, π], rad:
/// atan2(from × v, from·v).
#[inline]
pub fn angle_from(from: Vec2, v: Vec2) -> f64 {
    cross(from, v).atan2(from.dot(&v))
}

/// x reduced to [−π, π): x itself when it is in range (the common case of a warm start next
/// to its reference, without the cost of a floating-point remainder).
#[inline]
pub fn wrap_pi(x: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if (-PI..PI).contains(&x) {
        x
    } else {
        (x + PI).rem_euclid(TAU) - PI
    }
}

/// x reduced to [0, 2π): x itself when it is in range.
#[inline]
pub fn wrap_tau(x: f64) -> f64 {
    use std::f64::consts::TAU;
    if (0.0..TAU).contains(&x) {
        x
    } else {
        x.rem_euclid(TAU)
    }
}

/// The unit vector at angle x, (cos x, sin x).
#[inline]
pub fn unit(x: f64) -> Vec2 {
    let (s, c) = x.sin_cos();
    Vec2::new(c, s)
}

/// Rotate `v` counter-clockwise by the angle whose cosine and sine are given.
#[inline]
pub fn rotate(v: Vec2, cos: f64, sin: f64) -> Vec2 {
    Vec2::new(cos * v.x - sin * v.y, sin * v.x + cos * v.y)
}

/// sin and cos of a small angle |x| ≤ 0.05 by Taylor series to x⁹ (error < x¹¹/11! ≈ 1e-21),
/// and by libm beyond.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if x.abs() > 0.05 {
        return x.sin_cos();
    }
    let (s, cm1) = small_sin_cosm1(x);
    (s, 1.0 + cm1)
}

/// sin and cos of a sequence of nearby angles (the crank angles of a sweep, one after the other):
/// the first, and any more than 0.05 rad from the current reference, by libm (which becomes the
/// reference); the others by turning the reference through the difference d = x − x_ref:
///   sin x = s_r + (s_r·(cos d − 1) + c_r·sin d),  cos x = c_r + (c_r·(cos d − 1) − s_r·sin d),
/// with the series of `sin_cosm1` for d. A correction of size |d| is added to the reference, so
/// the result is within a few ulp of 1 (absolute) of libm's; d itself is exact when x and x_ref
/// are within a factor 2 (Sterbenz), and otherwise off by at most half an ulp of the larger of
/// |x| and |x_ref|, ≤ ε·(|x| + 0.05)/2 (they are at most 0.05 apart).
#[derive(Debug, Clone, Copy)]
pub struct NearbySinCos {
    angle: f64,
    sin: f64,
    cos: f64,
}

impl Default for NearbySinCos {
    fn default() -> Self {
        NearbySinCos {
            angle: f64::NAN,
            sin: 0.0,
            cos: 1.0,
        }
    }
}

impl NearbySinCos {
    /// (sin x, cos x).
    #[inline]
    pub fn sin_cos(&mut self, x: f64) -> (f64, f64) {
        let d = x - self.angle;
        // A NaN difference (no reference yet) takes the libm branch.
        if d.abs() <= 0.05 {
            let (sd, cm1) = small_sin_cosm1(d);
            let (s, c) = (self.sin, self.cos);
            return (s + (s * cm1 + c * sd), c + (c * cm1 - s * sd));
        }
        (self.sin, self.cos) = x.sin_cos();
        self.angle = x;
        (self.sin, self.cos)
    }
}

/// atan2(y, x) of a sequence of vectors that turn little from one to the next (a force along a
/// sweep): the first, any turned by more than atan 0.05 from the current reference (or not in
/// its half-plane), and any whose reference lies within 0.06 rad of the cut at ±π, by libm
/// (which becomes the reference); the others as the reference's angle plus the turn from it,
/// δ = atan t with t = (r × v)/(r · v), by the Taylor series of atan to t¹¹ (truncation
/// < t¹³/13 < 2e-17·|t| at |t| ≤ 0.05). Away from the cut, the sum cannot cross it, so no
/// reduction is needed and the result is on libm's side of it. t carries the round-off of a
/// cross product of nearly parallel vectors, ~ε absolute, so the result is within a few ulp of
/// π of libm's.
#[derive(Debug, Clone, Copy)]
pub struct NearbyAtan2 {
    angle: f64,
    reference: Vec2,
}

impl Default for NearbyAtan2 {
    fn default() -> Self {
        NearbyAtan2 {
            angle: 0.0,
            reference: Vec2::zeros(),
        }
    }
}

impl NearbyAtan2 {
    /// atan2(y, x), in [−π, π].
    #[inline]
    pub fn atan2(&mut self, y: f64, x: f64) -> f64 {
        use std::f64::consts::PI;
        let r = self.reference;
        let (turn, along) = (r.x * y - r.y * x, r.x * x + r.y * y);
        let near = along > 0.0 && turn.abs() <= 0.05 * along;
        if near && self.angle.abs() <= PI - 0.06 {
            let t = turn / along;
            let t2 = t * t;
            let series = 1.0
                - t2 * (1.0 / 3.0
                    - t2 * (1.0 / 5.0 - t2 * (1.0 / 7.0 - t2 * (1.0 / 9.0 - t2 * (1.0 / 11.0)))));
            return self.angle + t * series;
        }
        self.angle = y.atan2(x);
        self.reference = Vec2::new(x, y);
        self.angle
    }
}

/// Taylor series of sin x (to x⁹) and cos x − 1 (to x¹⁰) in Horner form, multiplying by the
/// reciprocals of the factorial ratios (a division in the chain would cost its latency at every
/// level); each reciprocal is rounded once, a relative error of ε per level, so the result is
/// within a few ulp.
#[inline]
fn small_sin_cosm1(x: f64) -> (f64, f64) {
    let x2 = x * x;
    let s = x
        * (1.0
            - x2 * (1.0 / 6.0)
                * (1.0
                    - x2 * (1.0 / 20.0) * (1.0 - x2 * (1.0 / 42.0) * (1.0 - x2 * (1.0 / 72.0)))));
    let cm1 = -x2
        * 0.5
        * (1.0
            - x2 * (1.0 / 12.0)
                * (1.0
                    - x2 * (1.0 / 30.0) * (1.0 - x2 * (1.0 / 56.0) * (1.0 - x2 * (1.0 / 90.0)))));
    (s, cm1)
}

/// (sin x, cos x − 1) without cancellation: Taylor series for |x| ≤ 0.05, and
/// cos x − 1 = −2·sin²(x/2) beyond. e^{ix} − 1 as a vector is (cos x − 1, sin x).
#[inline]
pub fn sin_cosm1(x: f64) -> (f64, f64) {
    if x.abs() > 0.05 {
        let h = (0.5 * x).sin();
        return (x.sin(), -2.0 * h * h);
    }
    small_sin_cosm1(x)
}

/// Complex product of two vectors.
#[inline]
pub fn cmul(a: Vec2, b: Vec2) -> Vec2 {
    Vec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

/// e^{ix} − 1 as a vector, without cancellation.
#[inline]
pub fn expi_minus_one(x: f64) -> Vec2 {
    let (s, cm1) = sin_cosm1(x);
    Vec2::new(cm1, s)
}

/// (cos k·t, sin k·t) for each of `orders`, by powers of e^{it} while they ascend: one sin_cos
/// per call instead of one per order; k products lose at most ~k·ε (2e-14 at order 200). An
/// order below the one before is evaluated directly.
pub fn cos_sin_of_orders(
    t: f64,
    orders: impl IntoIterator<Item = usize>,
) -> impl Iterator<Item = (f64, f64)> {
    let (s1, c1) = t.sin_cos();
    let (mut c, mut s, mut k) = (1.0, 0.0, 0);
    orders.into_iter().map(move |order| {
        if order < k {
            let (s, c) = (order as f64 * t).sin_cos();
            return (c, s);
        }
        while k < order {
            (c, s) = (c * c1 - s * s1, s * c1 + c * s1);
            k += 1;
        }
        (c, s)
    })
}

#[cfg(test)]
mod tests {
    use super::{sin_cos, sin_cosm1, wrap_pi, wrap_tau, NearbyAtan2, NearbySinCos};
    use std::f64::consts::{PI, TAU};

    /// The series agree with libm (correctly rounded to < 1 ulp) within a few ulp (Horner
    /// evaluation adds ~2) over the range they are used on, and hand over to it beyond 0.05.
    #[test]
    fn small_angle_sin_cos_matches_libm() {
        for k in -2000..=2000 {
            let x = 0.06 * k as f64 / 2000.0;
            let ((s, c), (s0, c0)) = (sin_cos(x), x.sin_cos());
            assert!(
                (s - s0).abs() <= 4.0 * f64::EPSILON * s0.abs(),
                "sin {x}: {s} vs {s0}"
            );
            assert!((c - c0).abs() <= 4.0 * f64::EPSILON, "cos {x}: {c} vs {c0}");
            // cos x − 1 against −2·sin²(x/2), which has no cancellation.
            let (_, cm1) = sin_cosm1(x);
            let h = (0.5 * x).sin();
            let cm1_0 = -2.0 * h * h;
            assert!(
                (cm1 - cm1_0).abs() <= 8.0 * f64::EPSILON * cm1_0.abs(),
                "cos−1 {x}"
            );
        }
    }

    /// Turning a reference through small steps agrees with libm within 4 ulp of 1 (the
    /// correction of `NearbySinCos` adds ~2 ulp to libm's half ulp) plus half an ulp of x (the
    /// rounding of the difference far from zero, ≤ |x|·ε/2), on sequences that step forward,
    /// backward, by more than the 0.05 rad reach (a new reference each time) and far from zero.
    #[test]
    fn nearby_sin_cos_matches_libm() {
        for (start, step) in [
            (0.0, 1.7e-4),
            (1.0, -3e-3),
            (-2.5, 0.011),
            (30.0, 0.07),
            (-40.0, 2e-5),
        ] {
            let mut near = NearbySinCos::default();
            for k in 0..2000 {
                let x = start + step * k as f64;
                let ((s, c), (s0, c0)) = (near.sin_cos(x), x.sin_cos());
                let tol = (4.0 + 0.5 * x.abs()) * f64::EPSILON;
                assert!(
                    (s - s0).abs() <= tol && (c - c0).abs() <= tol,
                    "{x}: {s} {c} vs {s0} {c0}"
                );
            }
        }
    }

    /// Angles of a turning vector agree with libm's atan2 within 6 ulp of π (the turn's
    /// round-off, ~ε, the series' and the sum's, against libm's half ulp): vectors turning
    /// either way through ±π (the reduction), by more than the series' reach (a new reference)
    /// and of changing length, and the zero vector.
    #[test]
    fn nearby_atan2_matches_libm() {
        for (start, step) in [
            (0.3, 1.7e-4),
            (3.1, 2e-3),
            (-3.0, -3e-3),
            (1.0, 0.09),
            (-0.5, 1e-6),
        ] {
            let mut near = NearbyAtan2::default();
            for k in 0..4000 {
                let a = start + step * k as f64;
                let length = 1e3 * (1.0 + 0.5 * (0.01 * k as f64).sin());
                let (y, x) = (length * a.sin(), length * a.cos());
                let (got, want) = (near.atan2(y, x), y.atan2(x));
                assert!(
                    (got - want).abs() <= 6.0 * f64::EPSILON * PI,
                    "{a}: {got} vs {want}"
                );
            }
        }
        let mut near = NearbyAtan2::default();
        assert_eq!(near.atan2(0.0, 0.0), 0.0);
        assert_eq!(near.atan2(0.0, 0.0), 0.0);
        // Across the cut by round-off: libm's side of it, not 2π away.
        let mut near = NearbyAtan2::default();
        near.atan2(0.01, -1.0);
        assert_eq!(near.atan2(-1e-17, -1.0), (-1e-17f64).atan2(-1.0));
    }

    /// Reduction keeps in-range values and lands every other value in range, a whole number of
    /// turns away (to the round-off of the remainder).
    #[test]
    fn wraps_reduce_by_whole_turns() {
        for k in -400..=400 {
            let x = 0.05 * k as f64;
            let (a, b) = (wrap_pi(x), wrap_tau(x));
            assert!(
                (-PI..PI).contains(&a) && (0.0..TAU).contains(&b),
                "{x}: {a} {b}"
            );
            for w in [a, b] {
                let turns = (x - w) / TAU;
                assert!((turns - turns.round()).abs() < 1e-12, "{x} → {w}");
            }
            if (-PI..PI).contains(&x) {
                assert_eq!(a, x);
            }
        }
    }
}
