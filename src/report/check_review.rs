//! The design review of a `check` run: the page's input built from what the run computed.

use crate::engine::commands::{CheckRun, Review};

/// The design review of `run` as files (name, text), `index.html` last.
pub fn render(run: &CheckRun, review: &Review) -> Vec<(String, String)> {
    let spec = &run.spec;
    let views: Vec<_> = (spec.studies.iter().zip(&run.studies).zip(&review.maps))
        .map(|((s, r), cells)| super::optimisation::view(spec, s, r, cells, review.map_steps))
        .collect();
    // The resolution warning `check` printed, as a banner under the verdict.
    let warnings: Vec<String> = (run.resolution.as_ref())
        .and_then(crate::report::accuracy::resolution_warning)
        .into_iter()
        .collect();
    let as_built = run.as_built.as_ref().and_then(|a| {
        let designed = a.designed.as_deref()?;
        Some(super::review::AsBuiltView {
            identification: &a.identification,
            designed_modification: a.designed_modification,
            designed,
        })
    });
    let input = super::review::ReportInput {
        spec,
        checks: &run.checks,
        results: &run.results,
        summaries: &run.summaries,
        goldens: &run.goldens,
        disc: &review.disc,
        optimisation: &views,
        accuracy: review.ladder.as_ref().map(|(l, _)| l),
        warnings: &warnings,
        as_built,
        efficiency: &review.efficiency,
        face: &review.face,
        solid: review.solid.as_ref(),
        mass: Some(&run.mass),
        unbalance: &run.unbalance,
    };
    super::review::render(&input)
}
