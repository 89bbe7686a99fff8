//! The coverage of a spec: every limit is evaluated by some scene, and every golden's scene
//! computes its quantity. A spec that fails it is refused at load, for every command: a limit
//! that no scene evaluates would otherwise pass unseen.

use super::Spec;
use crate::error::{Error, Result};
use crate::model::quantity::NEEDS_FACE;
use crate::model::{Effect, Plan};

/// Every limit must be evaluated by at least one scene, and every golden's scene must compute
/// its quantity.
pub(crate) fn check(spec: &Spec) -> Result<()> {
    for g in &spec.golden {
        let q = g.quantity;
        let scene = spec.scenes.iter().find(|s| s.name == g.scene);
        if scene.is_some_and(|s| {
            NEEDS_FACE.contains(&q) && !spec.design.deviations.face(&s.face).is_resolved()
        }) {
            return Err(Error::invalid(
                format!("{}.quantity", g.key),
                format!(
                    "scene `{}` does not resolve the load along the face width; give it \
                     `face_slices: 2` or more",
                    g.scene
                ),
            ));
        }
        if scene.is_some_and(|s| !Plan::for_scene(s).computes(q.effect)) {
            return Err(Error::invalid(
                format!("{}.quantity", g.key),
                format!(
                    "scene `{}` does not compute `{}`; add the effect `{}` to the scene",
                    g.scene,
                    q.key,
                    q.effect.name()
                ),
            ));
        }
    }
    for l in &spec.limits.entries {
        let d = l.def;
        let effect = d.quantity.effect;
        let face = NEEDS_FACE.contains(&d.quantity);
        let covered = spec.scenes.iter().any(|s| {
            Plan::for_scene(s).computes_quantity(d.quantity)
                && (!face || spec.design.deviations.face(&s.face).is_resolved())
        });
        if face && !covered {
            return Err(Error::invalid(
                format!("limits.{}", d.key),
                "no scene resolves the load along the face width; give a scene with \
                 `roller_contact` and `face_slices: 2` or more"
                    .to_string(),
            ));
        }
        if !covered {
            let how = match effect {
                _ if d.quantity.for_duty() == Some(true) => {
                    format!("give a scene computing `{}` a `duty_cycle`", effect.name())
                }
                _ if d.quantity.for_duty() == Some(false)
                    && spec.scenes.iter().any(|s| s.duty_cycle.is_some()) =>
                {
                    format!(
                        "a scene with a `duty_cycle` has its own figures (`duty_life_h`, \
                         `duty_mean_efficiency`: limits.min_duty_life_h), each bin's `{}` in \
                         its run; add the effect `{}` to a scene without a duty cycle",
                        d.quantity.key,
                        effect.name()
                    )
                }
                Effect::Torsion => "give a scene `torque_sweep: {rated_nm, steps}`".to_string(),
                e if e.is_loaded() => format!(
                    "add the effect `{}` to a scene loaded over the crank angle (not a \
                     `torque_sweep` scene)",
                    e.name()
                ),
                e => format!("add the effect `{}` to a scene", e.name()),
            };
            return Err(Error::invalid(
                format!("limits.{}", d.key),
                format!("no scene computes this limit's quantity; {how}"),
            ));
        }
    }
    Ok(())
}
