//! The review's torsion under a locked input ([`engine::torsion`](crate::engine::torsion)): per torsion scene its curves
//! and its table of catalogue figures (`sections`).

use super::common::{data_table, figure, numbered, scenes_with, Section};
use super::plots::capitalised;
use crate::engine::torsion::FIGURE_TORQUES;
use crate::model::results::{SceneResult, TorsionCurves};
use crate::model::Scene;
use crate::numeric::{extent, number};
use crate::report::explain::{
    hysteresis, hysteresis_in_plot, torsion_compliances, torsion_law_note,
};
use crate::report::place::{self, counted};
use crate::report::svg::{LinePlot, Mark, Series, YCut, PALETTE};
use crate::spec::Spec;
use crate::units::{self, nm_per_arcmin};
use maud::{html, Markup};

/// The torsion curve of a scene as drawn: per locked angle the loop's centre line (the
/// branches coincide), the rising branch from −rated to +rated with both one-sided values at
/// T = 0 (the dead band as a vertical step), in (N·m, arcmin).
fn centre_line(t: &TorsionCurves, k: usize, steps: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut y) = whole_loop(t, k);
    // γ(0⁺), from the falling branch, right after γ(0⁻).
    let at_zero_plus = y[3 * steps];
    x.truncate(2 * steps + 1);
    y.truncate(2 * steps + 1);
    x.insert(steps + 1, 0.0);
    y.insert(steps + 1, at_zero_plus);
    (x, y)
}

/// The whole loop of a locked angle as solved, −rated → +rated → −rated, in (N·m, arcmin):
/// with friction its branches part.
fn whole_loop(t: &TorsionCurves, k: usize) -> (Vec<f64>, Vec<f64>) {
    (
        t.torque_nmm.iter().map(|&v| units::nm(v)).collect(),
        t.torsion_rad[k].iter().map(|&g| units::arcmin(g)).collect(),
    )
}

/// Fewer torques than this over −rated…+rated (fewer than 8 steps per quarter loop) are drawn
/// as a mark per torque: a line through them would pass off as a measured smooth curve.
pub const SPARSE_TORQUES: usize = 17;

/// The y axis is cut across the dead band when the band is wider than this many times the
/// larger twist beyond it (the span of either branch): on one axis the slope, the rigidity the
/// figures are about, would be a flat line beside a tall step.
pub const CUT_ABOVE: f64 = 2.0;

/// The torsion plot of a scene: one curve per locked angle (marks where the torques are few),
/// the figures' points (±3 %, ±50 %, ±100 % of rated) marked ◇, and, when the dead band dwarfs
/// the twist beyond it, the y axis cut across the band, the cut labelled with its width.
fn torsion_plot(scene: &Scene, r: &SceneResult, t: &TorsionCurves) -> LinePlot {
    let sweep = scene.torque_sweep.as_ref();
    let steps = sweep.map_or(1, |s| s.steps);
    let rated = units::nm(sweep.map_or(0.0, |s| s.rated_nmm));
    let (angles, torques) = (t.torsion_rad.len(), 2 * steps + 1);
    let sparse = torques < SPARSE_TORQUES;
    let mut plot = LinePlot::new(
        &format!(
            "Torsion at {}, {torques} torques: scene {}",
            counted(angles, "locked crank angle"),
            scene.name
        ),
        "output torque T (N·m)",
        "torsion angle γ (arcmin)",
    );
    plot.subtitle = format!(
        "the loop −{r} → +{r} → −{r} N·m, {steps} steps per quarter; {}",
        hysteresis_in_plot(t.friction),
        r = number(rated)
    );
    let lines: Vec<_> = (0..angles).map(|k| centre_line(t, k, steps)).collect();
    // With friction the branches part: the whole loop is drawn.
    let drawn: Vec<_> = if t.friction {
        (0..angles).map(|k| whole_loop(t, k)).collect()
    } else {
        lines.clone()
    };
    for (k, (x, y)) in drawn.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let curve = Series::new(place::crank(r.crank_rad[k]), x.clone(), y.clone(), color);
        plot.series.push(if sparse {
            curve.marked(Mark::Dot)
        } else {
            curve
        });
        let (mx, my): (Vec<f64>, Vec<f64>) = FIGURE_TORQUES
            .iter()
            .zip(&t.figure_torsion_rad[k])
            .filter(|(f, _)| f.abs() >= 0.03)
            .map(|(f, &g)| (f * rated, units::arcmin(g)))
            .unzip();
        plot.series
            .push(Series::new("", mx, my, color).marked(Mark::Diamond));
    }
    plot.y_cut = dead_band_cut(t, &lines, steps);
    plot.include_zero = plot.y_cut.is_none();
    plot
}

/// The cut across the dead band (see `CUT_ABOVE`), or none: from the highest γ of the falling
/// side (T ≤ 0⁻, the first `steps + 1` points of a centre line) to the lowest of the rising
/// side, over every angle; labelled with the backlash figures' range.
fn dead_band_cut(t: &TorsionCurves, lines: &[(Vec<f64>, Vec<f64>)], steps: usize) -> Option<YCut> {
    let side = |range: fn(&[f64], usize) -> &[f64]| {
        extent((lines.iter()).flat_map(|(_, y)| range(y, steps).iter().copied()))
    };
    let below = side(|y, s| &y[..=s]);
    let above = side(|y, s| &y[s + 1..]);
    let (lo, hi) = (below.1, above.0);
    let twist = (below.1 - below.0).max(above.1 - above.0);
    // A band not wider (or not finite: no curve) is drawn on one axis.
    let wide = (hi - lo).partial_cmp(&(CUT_ABOVE * twist)) == Some(std::cmp::Ordering::Greater);
    if !wide {
        return None;
    }
    let (least, most) = extent(t.figures.iter().map(|f| units::arcmin(f.backlash_rad)));
    let band = if number(least) == number(most) {
        number(least)
    } else {
        format!("{}–{}", number(least), number(most))
    };
    Some(YCut {
        lo,
        hi,
        at_x: 0.0,
        label: format!("dead band {band} arcmin"),
    })
}

/// The table of catalogue figures per locked angle.
fn figures_table(r: &SceneResult, t: &TorsionCurves) -> Markup {
    let arcmin = |x: f64| number(units::arcmin(x));
    let head = html! {
        th { "locked crank angle" }
        th { "lost motion ±3 % (arcmin)" }
        th { "backlash (arcmin)" }
        th { "rigidity + (N·m/arcmin)" }
        th { "rigidity − (N·m/arcmin)" }
        th { "torsional rigidity (N·m/arcmin)" }
        th { "hysteresis loss (arcmin)" }
        @if t.friction { th { "loop energy per cycle (J)" } }
    };
    let rows = html! {
        @for (k, f) in t.figures.iter().enumerate() {
            tr {
                td { (format!("{:.2}°", units::deg(r.crank_rad[k]))) }
                td { (arcmin(f.lost_motion_rad)) }
                td { (arcmin(f.backlash_rad)) }
                td { (number(nm_per_arcmin(f.rigidity_nmm_per_rad.0))) }
                td { (number(nm_per_arcmin(f.rigidity_nmm_per_rad.1))) }
                td { b { (number(nm_per_arcmin(f.rigidity()))) } }
                @if t.friction {
                    td { b { (hysteresis_cell(t, k)) } }
                    td { (number(1e-3 * f.loop_energy_nmm)) }
                } @else {
                    td { "0 (frictionless model)" }
                }
            }
        }
    };
    data_table(head, rows)
}

/// The hysteresis loss at locked angle `k`, arcmin, to the loop's resolution
/// (`TorsionCurves::hysteresis_resolution_rad`): narrower reads 0.
fn hysteresis_cell(t: &TorsionCurves, k: usize) -> String {
    let width = t.figures[k].hysteresis_rad;
    match width.abs() < t.hysteresis_resolution_rad(k) {
        true => "0".to_string(),
        false => number(units::arcmin(width)),
    }
}

/// The definitions the figures follow, for the reader of the table.
const DEFINITIONS: &str = "Figures as the makers of precision reducers define them (Nabtesco \
     RV, Sumitomo Fine Cyclo catalogues): lost motion is the torsion angle between the loop's \
     points at ±3 % of the rated torque; backlash the dead band at zero torque, γ(0⁺) − γ(0⁻); \
     torsional rigidity the secant slope b/a between 50 % and 100 % of the rated torque, each \
     direction, the figure being the smaller. Each figure is solved at its own torque.";

/// The parts held rigid, or "none (every part's compliance is modelled)".
fn not_modelled(parts: &[String]) -> String {
    match parts {
        [] => "none (every part's compliance is modelled)".to_string(),
        _ => parts.join("; "),
    }
}

/// The design review's torsion sections (one per torsion scene); the plots go into `files` as
/// (name, SVG).
pub(super) fn section(
    spec: &Spec,
    results: &[SceneResult],
    files: &mut Vec<(String, String)>,
) -> Vec<Section> {
    let mut out = Vec::new();
    let torsion = scenes_with(spec, results, |r| Some((r, r.reducer.torsion.as_ref()?)));
    for (k, scene, (r, t)) in torsion {
        let id = format!("{}-torsion", numbered("scene", k, &scene.name));
        let file = format!("{id}.svg");
        files.push((file.clone(), torsion_plot(scene, r, t).to_svg()));
        let c = torsion_compliances(&t.compliances);
        let body = html! {
            p.note { (DEFINITIONS) " " b { (capitalised(hysteresis(t.friction))) "." } }
            p.note {
                "Compliances modelled: " (c.modelled.join("; ")) ". Not modelled: "
                (not_modelled(&c.not_modelled)) ". Given: " (c.given.join("; "))
                ". " (torsion_law_note(t.compliances.contact_law)) "."
            }
            (figure(&file, "Torsion curve", "One curve per locked crank angle (a dot per \
                torque where the torques are few); the points of the figures (±3 %, ±50 %, \
                ±100 % of the rated torque) marked ◇; at T = 0 the dead band is the vertical \
                step from γ(0⁻) to γ(0⁺). When the band is wider than twice the twist beyond \
                it, the y axis is cut across the band (zigzags, the band's width written in \
                the cut), so that the slope beyond it shows."))
            (figures_table(r, t))
        };
        out.push(Section::new(
            id,
            html! { "Torsion: scene " code { (scene.name) } },
            body,
        ));
    }
    out
}
