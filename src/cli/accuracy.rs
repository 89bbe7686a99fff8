//! `cycloid accuracy`: the options as given over the spec's `accuracy:` section, then the
//! library's ladder, its rows printed as each rung finishes.

use super::output::{print, stdout_error};
use super::{AccuracyArgs, Outcome};
use crate::engine::accuracy::{self, Setting};
use crate::engine::commands;
use crate::error::{Error, Result};
use crate::{report, spec};
use std::io::Write;

fn bad(flag: &str, m: String) -> Error {
    Error::invalid_value(format!("--{flag}: {m}"))
}

pub(super) fn run(asked: &AccuracyArgs, out: &mut dyn Write) -> Result<Outcome> {
    let spec = spec::load(&asked.spec)?;
    let (scene, options) = options(&spec, asked)?;
    // Rows are printed as their runs finish: the finest run comes first and takes longest.
    let mut written: Result<()> = Ok(());
    let ladder = commands::accuracy(&spec, scene, &options, &mut |event| {
        let text = match event {
            accuracy::Event::Started(layout) => report::accuracy::header(layout),
            accuracy::Event::Rung(layout, rung) => report::accuracy::row(layout, rung, false),
        };
        if written.is_ok() {
            written = print(out, &text).and_then(|_| out.flush().map_err(stdout_error));
        }
    })?;
    written?;
    print(out, &report::accuracy::footer(&ladder))?;
    Ok(Outcome::Passed)
}

/// The scene and the ladder's options: the flags given, over the spec's `accuracy:`, over the
/// defaults; checked against the scene.
fn options(spec: &spec::Spec, asked: &AccuracyArgs) -> Result<(usize, accuracy::Options)> {
    let from_spec = spec.accuracy.as_ref();
    let scene = match &asked.scene {
        Some(name) => spec::scene_index(&spec.scenes, name, "--scene")?,
        None => from_spec.map_or_else(|| accuracy::default_scene(spec), |a| a.scene),
    };
    let mut options = from_spec.map_or_else(accuracy::Options::default, |a| a.options);
    if let Some(n) = asked.finest {
        options.finest =
            accuracy::ladder_steps(n, 2 * accuracy::COARSEST).map_err(|m| bad("finest", m))?;
    }
    if let Some(n) = asked.settings_steps {
        options.settings_steps = Some(
            accuracy::ladder_steps(n, accuracy::COARSEST).map_err(|m| bad("settings-steps", m))?,
        );
    }
    let t = &mut options.tolerances;
    for ((flag, value), slot) in [
        "te-tol-arcsec",
        "force-tol-n",
        "ratio-tol",
        "clearance-tol-um",
    ]
    .into_iter()
    .zip([
        asked.te_tol_arcsec,
        asked.force_tol_n,
        asked.ratio_tol,
        asked.clearance_tol_um,
    ])
    .zip([
        &mut t.te_arcsec,
        &mut t.force_n,
        &mut t.ratio,
        &mut t.clearance_um,
    ]) {
        if let Some(v) = value {
            *slot = accuracy::tolerance(v).map_err(|m| bad(flag, m))?;
        }
    }
    accuracy::check(&spec.design, &spec.scenes[scene], &options).map_err(|(which, m)| {
        let flag = match which {
            Setting::Scene => "scene",
            Setting::Finest => "finest",
            Setting::SettingsSteps => "settings-steps",
        };
        bad(flag, m)
    })?;
    Ok((scene, options))
}
