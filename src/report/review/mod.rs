//! The design-review report (`--report DIR`): `index.html` plus one SVG per plot, for a
//! reviewer who opens it in a browser. No JavaScript; the page links the SVGs with `<img>`.
//! Built with maud: every text is escaped by construction.
//!
//! Contents: verdict and warnings, a table of contents, the headline results of every scene,
//! the design, every check and golden curve with its verdict; the disc at a crank angle as the
//! engine computed it ([`engine::drawing`](crate::engine::drawing)), the disc as a solid (`solid`)
//! and a close-up of the smallest gap; per scene, the
//! plots of its curves (`plots`); per optimisation study, the objective map with the global
//! sample, the winning local run's path, start, references and optimum, and a table of those
//! points; the accuracy ladder when one was run; the spec's source.
//!
//! This module builds the page; each section is built in its own module, by what it shows:
//! `summary` (headline results), `design`, `as_built` (a measured disc), `checks` (limits and
//! golden curves), `disc` (the drawing), `scenes` (each scene's `plots`), `torsion`,
//! `bearing_life`, `duty_cycle`, `optimisation`, `accuracy`. `common` holds the blocks they share and `shell`
//! the frame of a page (also the tolerance study's review, `tolerance`).

pub mod accuracy;
pub mod as_built;
pub mod bearing_life;
pub mod checks;
pub mod common;
pub mod design;
pub mod disc;
mod duty_cycle;
mod duty_spectrum;
mod efficiency;
mod face;
mod golden;
pub mod optimisation;
pub mod plots;
pub mod scenes;
pub mod shell;
pub mod solid;
pub mod summary;
pub mod tolerance;
pub mod torsion;

pub use as_built::AsBuiltView;
pub use optimisation::{OptimisationView, StudyPoint};

use crate::engine::accuracy::Ladder;
use crate::engine::drawing::Disc;
use crate::engine::golden::GoldenResult;
use crate::engine::verdict::Check;
use crate::model::results::SceneResult;
use crate::spec::Spec;
use common::Section;
use maud::html;
use shell::shell;

/// Everything the report shows.
pub struct ReportInput<'a> {
    pub spec: &'a Spec,
    /// Limit and golden checks.
    pub checks: &'a [Check],
    pub results: &'a [SceneResult],
    /// Each scene's summary, as the run marked it (`engine::summary::marked`).
    pub summaries: &'a [crate::engine::summary::SceneSummary],
    pub goldens: &'a [GoldenResult],
    /// The disc at the drawing's crank angle, as the engine computed it.
    pub disc: &'a Disc,
    /// Optimisation studies to draw and tabulate (none: no optimisation section).
    pub optimisation: &'a [OptimisationView],
    /// The accuracy ladder of a scene (`accuracy:` in the spec), when one was run.
    pub accuracy: Option<&'a Ladder>,
    /// Lines shown as a warning banner under the verdict (e.g. a crank resolution coarser
    /// than the accuracy tolerances need).
    pub warnings: &'a [String],
    /// The disc as built (`measured_profile:`): its identification and the results as
    /// designed, beside `results` (which are as built).
    pub as_built: Option<AsBuiltView<'a>>,
    /// Each scene's mean efficiency against its output torque (`None`: no efficiency).
    pub efficiency: &'a [Option<crate::model::results::TorqueCurve>],
    /// Each tilted scene's line load along the face, tilted and as designed.
    pub face: &'a [crate::engine::face_profile::FaceProfile],
    /// The disc as a solid, pictured beside the drawing (`None`: no picture).
    pub solid: Option<&'a crate::engine::commands::solid_picture::SolidPicture>,
    /// The discs' mass properties, for the design table (`None`: no row).
    pub mass: Option<&'a crate::engine::mass_properties::MassProperties>,
    /// The unbalance of each scene that computes `inertia`, for its section and its crank
    /// bearing's plot.
    pub unbalance: &'a [crate::engine::mass_properties::Unbalance],
}

/// The report's files, (file name, content): the SVGs, then `index.html` last.
pub fn render(input: &ReportInput) -> Vec<(String, String)> {
    let mut files = Vec::new();
    let designed = input
        .as_built
        .as_ref()
        .map_or(input.spec.modification, |v| v.designed_modification);
    let mut sections = vec![
        summary::section(input.summaries),
        design::section(input.spec, &designed, input.mass),
    ];
    if let Some(view) = &input.as_built {
        let built = as_built::section(input.spec, view, input.results, &mut files);
        sections.push(built);
    }
    if !input.checks.is_empty() {
        sections.push(checks::section(input.checks));
    }
    sections.extend(golden::section(input.goldens));
    sections.push(disc::section(
        input.spec,
        input.disc,
        input.solid,
        &mut files,
    ));
    for (k, (scene, r)) in input.spec.scenes.iter().zip(input.results).enumerate() {
        let unbalance = input.unbalance.iter().find(|u| u.scene == k);
        sections.extend(scenes::section(
            input.spec,
            (k, scene, r),
            unbalance,
            &mut files,
        ));
    }
    sections.extend(face::section(
        input.spec,
        input.face,
        input.results,
        &mut files,
    ));
    sections.extend(torsion::section(input.spec, input.results, &mut files));
    sections.extend(bearing_life::section(input.spec, input.results));
    sections.extend(duty_cycle::section(input.spec, input.results, &mut files));
    sections.extend(efficiency::section(
        input.spec,
        input.results,
        input.efficiency,
        &mut files,
    ));
    if !input.optimisation.is_empty() {
        sections.push(optimisation::section(input.optimisation, &mut files));
    }
    sections.extend(input.accuracy.map(accuracy::section));
    files.push(("index.html".into(), page(input, &sections)));
    files
}

fn page(input: &ReportInput, sections: &[Section]) -> String {
    let failed = input.checks.iter().filter(|c| !c.passed).count();
    let total = input.checks.len();
    let banner = html! {
        @if total == 0 {
            p.banner.pass { "No checks: the spec sets no limits and no golden curves; \
                the headline results below are what it computed" }
        } @else if failed == 0 {
            p.banner.pass { "PASSED: " (if total == 1 { "the one check passes".to_string() }
                else { format!("all {total} checks pass") }) }
        } @else {
            p.banner.fail { "FAILED: " (failed) " of " (total) " checks fail" }
        }
        @if !input.warnings.is_empty() {
            div.banner.warn { @for w in input.warnings { p { "Warning: " (w) } } }
        }
    };
    shell(input.spec, "Design review", banner, sections)
}
