//! Whole periods of the reducer as run (`Scene::run_period_rad`): a limit judged on a
//! loaded figure (TE and ratio fluctuation, the largest roller, pin and bearing forces, contact
//! pressure, face load factor and line load, rollers in contact, efficiency, bearing life) is
//! refused on a scene whose crank range is not a whole number of those periods, at the
//! scene's `crank`, naming the period and the nearest ranges of whole periods. A fluctuation,
//! an extreme or a mean over part of a period is not the reducer's: on the paper's design
//! tilted by 1 mrad the TE fluctuation over 36° is 8.3″, over its period of 1080° 22.0″.
//!
//! The period is a property of the reducer as built and as run (its deviations, its form, the
//! tilt as built or in the scene, the pins planned), so the rule is checked on every reducer a
//! run computes, as the bearing life's (`spec::bearing_life`), which shares `whole`: the
//! spec's own, the parts a tolerance study draws, the disc as built from measured points.

use crate::error::{Error, Result};
use crate::model::{Design, Limits, Plan, Scene, Study};
use crate::{numeric, units};

/// Every limit on a loaded figure, on scene `i` of the spec (each in turn, or the one scene a
/// tolerance study runs) if it computes it, for the reducer `design`; `built` says what made
/// it differ from the drawing (`None`: the spec's own reducer), for the error to name.
pub(crate) fn check_scene(
    limits: &Limits,
    design: &Design,
    (i, s): (usize, &Scene),
    built: Option<&str>,
) -> Result<()> {
    let plan = Plan::for_scene(s);
    let judged = limits
        .entries
        .iter()
        .find(|l| l.def.quantity.effect.is_loaded() && plan.computes_quantity(l.def.quantity));
    let Some(limit) = judged else {
        return Ok(());
    };
    let why = "a fluctuation, an extreme or a mean over part of a period is not the reducer's";
    whole(
        design,
        (i, s),
        built,
        &format!("limits.{}", limit.def.key),
        why,
    )
}

/// Scene `i` spans whole periods of the reducer as run, else the refusal at its `crank` for
/// `what` (the limit that needs them), with `why` and the nearest ranges of whole periods.
pub(crate) fn whole(
    design: &Design,
    (i, s): (usize, &Scene),
    built: Option<&str>,
    what: &str,
    why: &str,
) -> Result<()> {
    let plan = Plan::for_scene(s);
    let period = s.run_period_rad(design, &plan);
    if s.spans_whole(period) {
        return Ok(());
    }
    let of = match built {
        Some(what) => format!(" for the reducer as built, {what}"),
        None => String::new(),
    };
    Err(Error::invalid(
        format!("scenes[{i}].crank"),
        format!(
            "{what} applies to scene `{}`, whose crank range {}° to {}° is not a whole \
             number of loaded periods ({}°{of}): {why}; the nearest ranges of whole periods: {}",
            s.name,
            numeric::input(s.crank_from_deg),
            numeric::input(s.crank_to_deg),
            numeric::number(units::deg(period)),
            nearest_ranges(s.crank_from_deg, s.crank_to_deg, units::deg(period)).join(" or ")
        ),
    ))
}

/// The crank ranges from `from_deg` nearest to `from_deg`..`to_deg` that are whole numbers of
/// `period_deg` (the whole numbers of periods just below and just above its span, at least
/// one), as "0° to 324° (3 periods)"; each end written as the shortest decimal that still
/// spans its periods to 1e-12 (what `Scene::spans_whole` accepts, 1e-9, with room for the
/// conversion to radians).
pub(crate) fn nearest_ranges(from_deg: f64, to_deg: f64, period_deg: f64) -> Vec<String> {
    let span = (to_deg - from_deg) / period_deg;
    let below = span.floor().max(1.0);
    let above = span.ceil().max(1.0);
    let counts = if below == above {
        vec![below]
    } else {
        vec![below, above]
    };
    counts
        .into_iter()
        .map(|k| {
            let end = shortest(from_deg + k * period_deg, |x| {
                ((x - from_deg) / period_deg - k).abs() <= 1e-12 * k
            });
            let periods = if k == 1.0 { "period" } else { "periods" };
            format!("{}° to {end}° ({k} {periods})", numeric::input(from_deg))
        })
        .collect()
}

/// `x` with the fewest decimals (up to 12) whose value `ok` accepts, else in full.
fn shortest(x: f64, ok: impl Fn(f64) -> bool) -> String {
    (0..=12)
        .map(|d| format!("{x:.d$}"))
        .find(|s| s.parse::<f64>().is_ok_and(&ok))
        .unwrap_or_else(|| format!("{x}"))
}

/// The rule on an optimisation study (`key`, its spec key, for the message): an objective or
/// a bounded objective on a loaded figure needs the study's scene to span whole periods of the
/// reducer as run, as a limit does; a study that searches over part of a period optimises
/// what the reducer does not do.
pub(crate) fn check_study(
    study: &Study,
    key: &str,
    design: &Design,
    scenes: &[Scene],
) -> Result<()> {
    let terms = study.objective.iter().chain(&study.objective_limits);
    let Some((objective, _)) = terms
        .into_iter()
        .find(|(o, _)| o.quantity.effect.is_loaded())
    else {
        return Ok(());
    };
    let what = format!("{key}'s objective {}", objective.name);
    let why = "a study over part of a period optimises what the reducer does not do";
    let i = study.scene;
    whole(design, (i, &scenes[i]), None, &what, why)
}
