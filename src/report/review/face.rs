//! The review's load along the face width ([`engine::face_profile`](crate::engine::face_profile)):
//! for each tilted or crowned scene, the line load of the most loaded roller at one crank
//! angle (a tilted scene's worst face load factor, a crowned, aligned scene's largest line
//! load; the plot's title names it), tilted against designed (the same disc without the tilt).

use super::common::{figure, numbered, Section};
use crate::engine::face_profile::{FaceAngle, FaceProfile};
use crate::model::quantity::MAX_LINE_LOAD;
use crate::model::results::SceneResult;
use crate::numeric::number;
use crate::report::place;
use crate::report::svg::{LinePlot, Series, PALETTE};
use crate::spec::Spec;
use maud::html;

/// The line loads `q` of the slices centred at `z_mm` on a face `width_mm` wide (n equal
/// slices, each B/n wide) as a step curve, mm and N/mm: each slice's mean held over
/// [z_s − B/2n, z_s + B/2n], so that the curve spans the whole face, −B/2…B/2, and shows each
/// value as what it is, a mean over its slice (not a sample at its centre).
fn steps(z_mm: &[f64], width_mm: f64, q: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let half = 0.5 * width_mm / z_mm.len().max(1) as f64;
    z_mm.iter()
        .zip(q)
        .flat_map(|(&z, &v)| [(z - half, v), (z + half, v)])
        .unzip()
}

/// The section, or nothing without a tilted scene.
pub(super) fn section(
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
        // As the check table locates an extreme (`report::place`), so that the plot names the
        // same angle the table does.
        let crank = place::crank(p.crank_rad);
        let why = match p.angle {
            FaceAngle::WorstFactor => "largest face load factor",
            FaceAngle::LargestLineLoad => "largest line load",
        };
        let mut plot = LinePlot::new(
            &format!("Line load along the face: scene {}", scene.name),
            "z from the middle of the face (mm)",
            "line load (N/mm)",
        );
        // At the worst face load factor's angle the peak need not be the max line load: the
        // subtitle gives the latter (the check table's figure) so that the plot's peak is not
        // read as it.
        let peak = results
            .get(p.scene)
            .and_then(|r| MAX_LINE_LOAD.scalar(r))
            .filter(|_| p.angle == FaceAngle::WorstFactor)
            .map(|e| {
                format!(
                    "; the scene's max line load, {} N/mm, is at {}",
                    number(e.value),
                    place::text(&e.at)
                )
            })
            .unwrap_or_default();
        plot.subtitle = format!(
            "at {crank}, the scene's {why}: roller {}; slice means ({} slices){peak}",
            p.roller,
            p.z_mm.len()
        );
        plot.include_zero = true;
        // The whole face, −B/2…B/2, with round ticks inside it.
        let half = 0.5 * spec.design.face_width_mm;
        plot.x_range = Some((-half, half));
        let (x, y) = steps(&p.z_mm, 2.0 * half, &p.tilted_n_per_mm);
        let name = if m.is_zero() {
            "crowned, aligned".to_string()
        } else {
            format!(
                "tilted θx {} mrad, θy {} mrad",
                crate::numeric::input(1e3 * m.about_x_rad),
                crate::numeric::input(1e3 * m.about_y_rad)
            )
        };
        plot.series.push(Series::new(name, x, y, PALETTE[0]));
        if let Some(designed) = &p.designed_n_per_mm {
            let (x, y) = steps(&p.z_mm, 2.0 * half, designed);
            let mut s = Series::new("designed (no tilt)", x, y, PALETTE[1]);
            s.dashed = true;
            plot.series.push(s);
        }
        let file = format!("{}.svg", numbered("face", p.scene, &scene.name));
        files.push((file.clone(), plot.to_svg()));
        figures.push((
            file,
            format!("Line load along the face, scene {}", scene.name),
            format!(
                "The most loaded roller at the crank angle of the {why}, over the whole face \
                 width: the line load of each slice (its mean over the slice, drawn as a step \
                 across the slice's width) as the scene runs it{}.",
                if m.is_zero() {
                    ""
                } else {
                    " (tilted) and for the same disc and angle without the tilt (designed, \
                     solved alike)"
                }
            ),
        ));
    }
    let body = html! {
        div.grid { @for (f, t, c) in &figures { (figure(f, t, c)) } }
    };
    Some(Section::new(
        "face-width",
        html! { "Along the face width" },
        body,
    ))
}
