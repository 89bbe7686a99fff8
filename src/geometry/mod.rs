//! Geometry of the disc and the rollers: exact profile, clearance, design-rule checks.

pub mod clearance;
pub mod first_order;
pub mod profile;
pub mod validity;

pub type Vec2 = nalgebra::Vector2<f64>;

/// 2-D cross product a × b = a.x·b.y − a.y·b.x (z of the 3-D cross product).
#[inline]
pub fn cross(a: Vec2, b: Vec2) -> f64 {
    a.x * b.y - a.y * b.x
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
    let x2 = x * x;
    let s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))));
    let c = 1.0
        - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0 * (1.0 - x2 / 90.0))));
    (s, c)
}

/// (sin x, cos x − 1) without cancellation: Taylor series for |x| ≤ 0.05, and
/// cos x − 1 = −2·sin²(x/2) beyond. e^{ix} − 1 as a vector is (cos x − 1, sin x).
#[inline]
pub fn sin_cosm1(x: f64) -> (f64, f64) {
    if x.abs() > 0.05 {
        let h = (0.5 * x).sin();
        return (x.sin(), -2.0 * h * h);
    }
    let x2 = x * x;
    let s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))));
    let cm1 =
        -x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0 * (1.0 - x2 / 90.0))));
    (s, cm1)
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
