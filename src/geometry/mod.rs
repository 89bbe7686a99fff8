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
