//! The crank period of the reducer as run: after how much crank angle a scene's loaded curves
//! (roller, pin and bearing forces, TE, the ratio, the line loads along the face) repeat. One
//! home for every symmetry a reducer as run may break, so that each consumer (the limits, the
//! ratio's differencing, the bearing life, optimise, the design search, tolerance studies,
//! the accuracy ladder and the review) reads the same period:
//!
//! - the mesh, 2π/np of crank (MODEL.md "Clearance"); a whole crank turn when the rollers are
//!   not alike: off their places or sizes as built, or tilted against the disc by a tilt fixed
//!   in the housing (the scene's `misalignment` plus `reducer.deviations.misalignment`, each
//!   roller closing by its own fixed place);
//! - the output pins, 2π·nc/(np·M), when planned; a whole turn of the disc (nc crank turns)
//!   with a pin or hole off its place;
//! - a form error on the disc (measured or drawn): a whole turn of the disc;
//! - several discs: each runs the one disc's curves at its own phase, so the set repeats with
//!   the one disc's period.
//!
//! The arithmetic is `Design::loaded_period_rad`; this module decides which symmetries the
//! scene breaks, and `Scene::run_period_rad` is the period of a scene under its plan.

use super::design::Design;
use super::face::Face;

/// Whether the contacts of a scene with `face` on `design` see a tilt (θ_scene + θ_dev ≠ 0):
/// the face the contacts see is `Deviations::face`, the scene's tilt plus the tilt as built,
/// and its loaded curves then repeat only after whole crank turns
/// (`Design::loaded_period_rad`).
pub fn tilted(design: &Design, face: &Face) -> bool {
    !design.deviations.face(face).misalignment.is_zero()
}
