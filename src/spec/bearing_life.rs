//! What a `min_bearing_life_h` limit needs (ISO 281, MODEL.md "Several discs, torsion,
//! bearing life"): the bearing's rating, and, in every scene that computes the bearing force,
//! an input speed and a crank range of whole loaded periods. The equivalent load is a mean
//! over the load cycle; over part of it the life would be that of a load the bearing never
//! sees.
//!
//! The loaded period is a property of the reducer as built (`Design::loaded_period_rad`): a
//! roller, pin or hole off its place or a form error on the disc lengthens it (to 360° or to
//! nc crank turns). The rule is therefore checked on every reducer a run computes: the
//! spec's own at load, the parts a tolerance study draws (`spec::tolerances`) and the disc as
//! built from measured points (`engine::as_built`), each before anything runs, so that no
//! scene reaches its limits without a life to check.

use crate::error::{Error, Result};
use crate::model::{Design, Limits, Plan, Scene};

/// The limit's key.
const KEY: &str = "min_bearing_life_h";

/// The duty cycle's limit (`scenes[].duty_cycle`): the same rules, the speeds the bins'.
const DUTY_KEY: &str = "min_duty_life_h";

/// This module's rule (`check_scene`) on each of `scenes`, then the periods'
/// (`periods::check_scene`), for a reducer other than the drawing, `built` saying what made it
/// differ: the rules the parts a tolerance study draws and the disc as built are held to.
pub(crate) fn check_built<'s>(
    limits: &Limits,
    design: &Design,
    mut scenes: impl Iterator<Item = (usize, &'s Scene)> + Clone,
    built: &str,
) -> Result<()> {
    scenes
        .clone()
        .try_for_each(|s| check_scene(limits, design, s, Some(built)))?;
    scenes.try_for_each(|s| super::periods::check_scene(limits, design, s, Some(built)))
}

/// The rule on scene `i` of the spec (each in turn, or the one scene a tolerance study runs)
/// for the reducer `design`; `built` says what made it differ from the drawing (`None`: the
/// spec's own reducer), for the error to name.
pub(crate) fn check_scene(
    limits: &Limits,
    design: &Design,
    (i, s): (usize, &Scene),
    built: Option<&str>,
) -> Result<()> {
    for key in [KEY, DUTY_KEY] {
        let Some(limit) = limits.entries.iter().find(|l| l.def.key == key) else {
            continue;
        };
        if design.crank_bearing.is_none() {
            return Err(Error::invalid(
                format!("limits.{key}"),
                "a bearing life needs the bearing's rating: give `reducer.crank_bearing: \
                 {dynamic_load_rating_n}`"
                    .into(),
            ));
        }
        if Plan::for_scene(s).computes_quantity(limit.def.quantity) {
            scene(design, (i, s), built, key)?;
        }
    }
    Ok(())
}

/// The rule of the limit `KEY` (`min_bearing_life_h` or `min_duty_life_h`) on scene `i` of
/// the spec, which computes its life: an input speed (a duty cycle's bins have theirs) and
/// whole loaded periods of `design`.
fn scene(design: &Design, (i, s): (usize, &Scene), built: Option<&str>, key: &str) -> Result<()> {
    if !s.has_speed() {
        return Err(Error::invalid(
            format!("scenes[{i}]"),
            format!(
                "limits.{key} applies to scene `{}`, which computes the bearing force: it \
                 needs `input_speed_rpm` (the life in hours is at the crank's speed relative \
                 to the disc)",
                s.name
            ),
        ));
    }
    let why = "the equivalent load is a mean over whole load cycles (ISO 281)";
    super::periods::whole(design, (i, s), built, &format!("limits.{key}"), why)
}

#[cfg(test)]
mod tests {
    use super::super::periods::nearest_ranges;

    /// 360° is 3⅓ loaded periods of 108°: the whole ranges around it are 3 and 4 periods; a
    /// range shorter than one period has only the one above; a period with no short decimal
    /// (360°·30/66) is written to the digits that still span it.
    #[test]
    fn the_nearest_whole_ranges_bracket_the_span() {
        assert_eq!(
            nearest_ranges(0.0, 360.0, 108.0),
            ["0° to 324° (3 periods)", "0° to 432° (4 periods)"]
        );
        assert_eq!(nearest_ranges(0.0, 65.45, 108.0), ["0° to 108° (1 period)"]);
        assert_eq!(
            nearest_ranges(10.0, 100.0, 36.0),
            ["10° to 82° (2 periods)", "10° to 118° (3 periods)"]
        );
        let period = 360.0 * 30.0 / 66.0;
        let one = &nearest_ranges(0.0, 100.0, period)[0];
        let end: f64 = one
            .split(" to ")
            .nth(1)
            .and_then(|s| s.split('°').next())
            .and_then(|s| s.parse().ok())
            .unwrap();
        assert!((end / period - 1.0).abs() <= 1e-12, "{one}");
    }
}
