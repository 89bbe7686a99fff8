//! What the outputs show of torsion under a locked input and of the crank bearing's life: the
//! torsion block of a scene in the results JSON (`TorsionDoc`), and the design review's
//! torsion curves, table of catalogue figures and bearing-life table (`sections`).

use super::explain::HYSTERESIS;
use super::html::{data_table, figure, section, Section};
use super::json::Finite;
use super::svg::{LinePlot, Series, PALETTE};
use crate::engine::torsion::FIGURE_TORQUES;
use crate::model::quantity::{self as q, Quantity};
use crate::model::results::{SceneResult, TorsionCurves};
use crate::model::Scene;
use crate::numeric::number;
use crate::spec::Spec;
use crate::units::{self, nm_per_arcmin};
use maud::{html, Markup};
use serde::Serialize;

/// A torsion scene's block in the results JSON (flattened into the scene object).
#[derive(Serialize)]
pub struct TorsionDoc {
    /// The loop's torques, N·m [m].
    torque_nm: Vec<Finite>,
    /// γ [crank][m], arcmin.
    torsion_arcmin: Vec<Vec<Finite>>,
    lost_motion_arcmin: Vec<Finite>,
    backlash_arcmin: Vec<Finite>,
    /// The smaller direction [crank].
    torsional_rigidity_nm_per_arcmin: Vec<Finite>,
    torsional_rigidity_forward_nm_per_arcmin: Vec<Finite>,
    torsional_rigidity_reverse_nm_per_arcmin: Vec<Finite>,
    /// The model's hysteresis loss, 0, and why.
    hysteresis: &'static str,
}

fn finite(values: impl IntoIterator<Item = f64>) -> Vec<Finite> {
    values.into_iter().map(Finite).collect()
}

/// A per-crank curve of the registry, as written.
fn registry(r: &SceneResult, quantity: &Quantity) -> Vec<Finite> {
    let values = quantity.curves(r).and_then(|mut c| c.values.pop());
    finite(values.unwrap_or_default())
}

impl TorsionDoc {
    pub fn new(r: &SceneResult) -> Option<TorsionDoc> {
        let t = r.torsion.as_ref()?;
        let direction = |pick: fn((f64, f64)) -> f64| {
            finite(
                t.figures
                    .iter()
                    .map(|f| nm_per_arcmin(pick(f.rigidity_nmm_per_rad))),
            )
        };
        Some(TorsionDoc {
            torque_nm: finite(t.torque_nmm.iter().map(|&x| units::nm(x))),
            torsion_arcmin: t
                .torsion_rad
                .iter()
                .map(|row| finite(row.iter().map(|&g| units::arcmin(g))))
                .collect(),
            lost_motion_arcmin: registry(r, &q::TORSION_LOST_MOTION),
            backlash_arcmin: registry(r, &q::TORSION_BACKLASH),
            torsional_rigidity_nm_per_arcmin: registry(r, &q::TORSIONAL_RIGIDITY),
            torsional_rigidity_forward_nm_per_arcmin: direction(|d| d.0),
            torsional_rigidity_reverse_nm_per_arcmin: direction(|d| d.1),
            hysteresis: HYSTERESIS,
        })
    }
}

/// The torsion curve of a scene as drawn: per locked angle the loop's centre line (the
/// branches coincide), the rising branch from −rated to +rated with both one-sided values at
/// T = 0 (the dead band as a vertical step), in (N·m, arcmin).
fn centre_line(t: &TorsionCurves, k: usize, steps: usize) -> (Vec<f64>, Vec<f64>) {
    let row = &t.torsion_rad[k];
    let mut x: Vec<f64> = t.torque_nmm[..=2 * steps]
        .iter()
        .map(|&v| units::nm(v))
        .collect();
    let mut y: Vec<f64> = row[..=2 * steps]
        .iter()
        .map(|&g| units::arcmin(g))
        .collect();
    // γ(0⁺), from the falling branch, right after γ(0⁻).
    x.insert(steps + 1, 0.0);
    y.insert(steps + 1, units::arcmin(row[3 * steps]));
    (x, y)
}

/// Small diamonds (in data units, `size` = half-widths in x and y) around points, as one
/// series of closed outlines separated by gaps.
fn diamonds(points: &[(f64, f64)], (dx, dy): (f64, f64)) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for &(px, py) in points {
        for (ox, oy) in [(-dx, 0.0), (0.0, dy), (dx, 0.0), (0.0, -dy), (-dx, 0.0)] {
            x.push(px + ox);
            y.push(py + oy);
        }
        x.push(f64::NAN);
        y.push(f64::NAN);
    }
    (x, y)
}

/// The torsion plot of a scene: one line per locked angle, the figures' points (±3 %, ±50 %,
/// ±100 % of rated) marked.
fn torsion_plot(scene: &Scene, r: &SceneResult, t: &TorsionCurves) -> LinePlot {
    let sweep = scene.torque_sweep.as_ref();
    let steps = sweep.map_or(1, |s| s.steps);
    let rated = units::nm(sweep.map_or(0.0, |s| s.rated_nmm));
    let mut plot = LinePlot::new(
        &format!("Torsion under a locked input: scene {}", scene.name),
        "output torque T (N·m)",
        "torsion angle γ (arcmin)",
    );
    plot.subtitle = format!(
        "the loop −{r} → +{r} → −{r} N·m, {steps} steps per quarter; {HYSTERESIS}",
        r = number(rated)
    );
    let lines: Vec<_> = (0..t.torsion_rad.len())
        .map(|k| centre_line(t, k, steps))
        .collect();
    let ys = lines.iter().flat_map(|(_, y)| y.iter().copied());
    let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    let size = (0.012 * 2.0 * rated, 0.02 * (hi - lo).max(1e-9));
    for (k, (x, y)) in lines.into_iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let crank = units::deg(r.crank_rad[k]);
        plot.series
            .push(Series::new(format!("crank {crank:.2}°"), x, y, color));
        let marked: Vec<(f64, f64)> = FIGURE_TORQUES
            .iter()
            .zip(&t.figure_torsion_rad[k])
            .filter(|(f, _)| f.abs() >= 0.03)
            .map(|(f, &g)| (f * rated, units::arcmin(g)))
            .collect();
        let (mx, my) = diamonds(&marked, size);
        plot.series.push(Series::new("", mx, my, color));
    }
    plot.include_zero = true;
    plot
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
        th { "hysteresis loss" }
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
                td { "0 (frictionless model)" }
            }
        }
    };
    data_table(head, rows)
}

/// The definitions the figures follow, for the reader of the table.
const DEFINITIONS: &str = "Figures as the makers of precision reducers define them (Nabtesco \
     RV, Sumitomo Fine Cyclo catalogues): lost motion is the torsion angle between the loop's \
     points at ±3 % of the rated torque; backlash the dead band at zero torque, γ(0⁺) − γ(0⁻); \
     torsional rigidity the secant slope b/a between 50 % and 100 % of the rated torque, each \
     direction, the figure being the smaller. Each figure is solved at its own torque.";

/// The design review's torsion sections (one per torsion scene) and its bearing-life section
/// (when a scene rated the crank bearing); the plots go into `files` as (name, SVG).
pub(super) fn sections(
    spec: &Spec,
    results: &[SceneResult],
    prefix: impl Fn(usize, &Scene) -> String,
    files: &mut Vec<(String, String)>,
) -> Vec<Section> {
    let mut out = Vec::new();
    for (k, (scene, r)) in spec.scenes.iter().zip(results).enumerate() {
        let Some(t) = &r.torsion else { continue };
        let id = format!("{}-torsion", prefix(k, scene));
        let file = format!("{id}.svg");
        files.push((file.clone(), torsion_plot(scene, r, t).to_svg()));
        let body = html! {
            p.note { (DEFINITIONS) " " b { (HYSTERESIS) "." } }
            (figure(&file, "Torsion curve", "one line per locked crank angle; the points of \
                the figures (±3 %, ±50 %, ±100 % of the rated torque) marked ◇; at T = 0 the \
                dead band is the vertical step from γ(0⁻) to γ(0⁺)"))
            (figures_table(r, t))
        };
        out.push(section(
            id,
            html! { "Torsion: scene " code { (scene.name) } },
            body,
        ));
    }
    out.extend(bearing_section(spec, results));
    out
}

/// The crank bearing's rating life of every scene that rated it.
fn bearing_section(spec: &Spec, results: &[SceneResult]) -> Option<Section> {
    let rating = spec.design.crank_bearing?;
    // (scene, disc with several discs, its life): with several discs each disc has a bearing.
    let rated: Vec<_> = spec
        .scenes
        .iter()
        .zip(results)
        .flat_map(|(s, r)| {
            let one = r.discs.is_empty().then_some((None, r));
            let each = r.discs.iter().enumerate().map(|(k, d)| (Some(k), d));
            one.into_iter()
                .chain(each)
                .filter_map(move |(k, d)| Some((s, k, d.bearing_life?)))
        })
        .collect();
    let notes: Vec<String> = super::explain::notes(spec)
        .into_iter()
        .filter(|n| n.contains("crank-bearing"))
        .collect();
    if rated.is_empty() && notes.is_empty() {
        return None;
    }
    let body = html! {
        p.note {
            "ISO 281 with a varying load: P = (mean of Fb^p over whole loaded periods)^(1/p), \
             L10h = (C/P)^p · 10⁶ / (60 · n · (1 + 1/nc)) at the crank's speed relative to the \
             disc. C = " (number(rating.dynamic_load_rating_n)) " N, p = "
            (number(rating.life_exponent)) "."
        }
        (data_table(
            html! {
                th { "scene" } th { "input speed (rpm)" } th { "equivalent load P (N)" }
                th { "rating life L10h (h)" }
            },
            html! { @for (s, k, b) in &rated { tr {
                td { code { (s.name) } @if let Some(k) = k { " disc " (k) } }
                td { (s.input_speed_rpm.map_or("—".to_string(), number)) }
                td { (number(b.equivalent_load_n)) }
                td { (b.life_h.map_or("not rated".to_string(), number)) }
            } } },
        ))
        @for n in &notes { p.note { (n) } }
    };
    Some(section(
        "crank-bearing-life",
        html! { "Crank-bearing life" },
        body,
    ))
}
