//! `effects: [inertia]` (`Effect::Inertia`): what the discs' centripetal force at speed needs
//! and what it is not built for.

use crate::error::{Error, Result};
use crate::model::{Design, Effect, FrictionModel, Plan, Scene};

/// A scene that computes `inertia` runs at a speed (a duty cycle's bins have theirs), on a
/// rigid crank bearing and without the coupled friction model: the centripetal force enters the
/// bearing's force balance of the rigid, frictionless balance (and so the loss model's
/// bearing loss); the compliant bearing's offset and the coupled model's bearing friction
/// moment would need it inside their own solves, which are not built.
pub(super) fn check(design: &Design, scenes: &[Scene]) -> Result<()> {
    let coupled = design
        .friction
        .is_some_and(|f| f.model == FrictionModel::Coupled);
    for (i, s) in scenes.iter().enumerate() {
        if !Plan::for_scene(s).computes(Effect::Inertia) {
            continue;
        }
        let refuse = |why: &str| {
            Err(Error::invalid(
                format!("scenes[{i}].effects"),
                format!("scene `{}` computes `inertia`, {why}", s.name),
            ))
        };
        if !s.has_speed() {
            return refuse(
                "which needs `input_speed_rpm`: the centripetal force m·e·ω² is at a speed",
            );
        }
        if s.bearing_stiffness_n_per_mm.is_some() {
            return refuse(
                "which is built for a rigid crank bearing only: remove \
                 `bearing_stiffness_n_per_mm` or the effect",
            );
        }
        if coupled {
            return refuse(
                "which is built without the coupled friction model only (its bearing friction \
                 moment would need the force inside its balance): use `friction.model: loss` \
                 or remove the effect",
            );
        }
    }
    Ok(())
}
