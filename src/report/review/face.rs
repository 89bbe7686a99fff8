//! The review's load along the face width ([`engine::face_profile`](crate::engine::face_profile)):
//! for each tilted scene, the line load of the most loaded roller at its worst crank angle,
//! tilted against designed (the same disc without the tilt).

use super::common::{figure, section, slug, Section};
use crate::engine::face_profile::FaceProfile;
use crate::model::quantity::MAX_LINE_LOAD;
use crate::model::results::SceneResult;
use crate::numeric::number;
use crate::report::svg::{LinePlot, Series, PALETTE};
use crate::spec::Spec;
use crate::units;
use maud::html;

/// The section, or nothing without a tilted scene.
pub(super) fn section_of(
    spec: &Spec,
    profiles: &[FaceProfile],
    results: &[SceneResult],
    files: &mut Vec<(String, String)>,
) -> Option<Section> {
    if profiles.is_empty() {
        return None;
    }
    let mut figures = Vec::new();
    for p in profiles {
        let scene = &spec.scenes[p.scene];
        // The tilt as run: the scene's plus the one as built.
        let m = spec.design.deviations.face(&scene.face).misalignment;
        let mut plot = LinePlot::new(
            &format!("Line load along the face: scene {}", scene.name),
            "z from the middle of the face (mm)",
            "line load (N/mm)",
        );
        // The plotted angle is the worst face load factor's, which need not be the max line
        // load's: the subtitle gives the latter (the check table's figure) so that the peak of
        // the plot is not read as it.
        let peak = results
            .get(p.scene)
            .and_then(|r| MAX_LINE_LOAD.scalar(r))
            .map(|e| {
                format!(
                    "; the scene's max line load, {} N/mm, is at {}",
                    number(e.value),
                    e.at
                )
            })
            .unwrap_or_default();
        plot.subtitle = format!(
            "roller {} at crank {}°, the scene's worst face load factor; slice means \
             ({} slices){peak}",
            p.roller,
            number(units::deg(p.crank_rad)),
            p.z_mm.len()
        );
        plot.include_zero = true;
        plot.series.push(Series::new(
            format!(
                "tilted θx {} mrad, θy {} mrad",
                crate::numeric::input(1e3 * m.about_x_rad),
                crate::numeric::input(1e3 * m.about_y_rad)
            ),
            p.z_mm.clone(),
            p.tilted_n_per_mm.clone(),
            PALETTE[0],
        ));
        if let Some(designed) = &p.designed_n_per_mm {
            let mut s = Series::new(
                "designed (no tilt)",
                p.z_mm.clone(),
                designed.clone(),
                PALETTE[1],
            );
            s.dashed = true;
            plot.series.push(s);
        }
        let file = format!("face-{}-{}.svg", p.scene + 1, slug(&scene.name));
        files.push((file.clone(), plot.to_svg()));
        figures.push((
            file,
            format!("Line load along the face, scene {}", scene.name),
            "The most loaded roller at the crank angle of the largest face load factor: the line \
             load of each slice (its mean, drawn at its centre) as the scene runs it (tilted) \
             and for the same disc and angle without the tilt (designed, solved alike)"
                .to_string(),
        ));
    }
    let body = html! {
        div.grid { @for (f, t, c) in &figures { (figure(f, t, c)) } }
    };
    Some(section(
        "face-width",
        html! { "Along the face width" },
        body,
    ))
}
