//! The review's friction, efficiency and heat ([`engine::efficiency`](crate::engine::efficiency)):
//! per scene with `efficiency`, the mean efficiency against the output torque from 5 % to 150 %
//! of the scene's (`TorqueCurve`, solved by [`engine::torque_curve`](crate::engine::torque_curve)), and with a speed the mean power lost
//! on each path as a stacked bar.

use super::common::{data_table, figure, scenes_with, signed, Section};
use crate::model::friction::PathLosses;
use crate::model::power_flow::Driver;
use crate::model::results::{ReducerEfficiency, SceneResult, TorqueCurve};
use crate::model::Scene;
use crate::numeric::number;
use crate::report::svg::{document, px, ticks, LinePlot, Mark, RefLine, Series, PALETTE, RED};
use crate::spec::Spec;
use crate::units;
use maud::html;

/// The paths in the order a bar stacks them, with their colours.
const PATHS: [(&str, usize); 4] = [
    ("rollers", 0),
    ("output pins", 1),
    ("crank bearing", 2),
    ("no-load drag", 7),
];

fn path_values(p: &PathLosses) -> [f64; 4] {
    [p.rollers, p.output_pins, p.crank_bearing, p.no_load]
}

/// The efficiency-against-torque plot of a scene: the mean efficiency at each torque of the
/// curve, the scene's own torque marked (a diamond on the curve, not a dashed red line: dashed
/// red is a limit), and the spec's `min_mean_efficiency` as the limit line.
fn torque_plot(spec: &Spec, scene: &Scene, c: &TorqueCurve, r: &ReducerEfficiency) -> LinePlot {
    let mean = r.mean_efficiency;
    let mut plot = LinePlot::new(
        &format!("Efficiency against output torque: scene {}", scene.name),
        "output torque T (N·m)",
        "mean efficiency",
    );
    plot.subtitle = format!(
        "{} over the scene's crank angles, the scene solved again at each torque; the drag and \
         any preload lose whatever the torque, so the efficiency falls at light load",
        flow_formula(r.flow.driver)
    );
    let x: Vec<f64> = c.torque_nmm.iter().map(|&t| units::nm(t)).collect();
    plot.series.push(Series::new(
        "mean efficiency",
        x,
        c.mean_efficiency.clone(),
        PALETTE[0],
    ));
    let at = units::nm(scene.output_torque_nmm);
    plot.series.push(
        Series::new(
            format!("the scene: {} N·m, {}", signed(number(at)), number(mean)),
            vec![at],
            vec![mean],
            "#222",
        )
        .marked(Mark::Diamond),
    );
    if let Some(value) = spec.limits.get("min_mean_efficiency") {
        plot.ref_lines.push(RefLine {
            value,
            label: format!("limit {}", number(value)),
            color: RED.into(),
        });
    }
    plot
}

/// The mean efficiency of the power that flows (`model::power_flow`): P_out/(P_out + mean
/// loss) with the input driving, (P − mean loss)/P with the output driving.
fn flow_formula(driver: Driver) -> &'static str {
    match driver {
        Driver::Input => "P_out/(P_out + mean loss)",
        Driver::Output => {
            "back-driven, (P − mean loss)/P with P = |T|·ω_out entering at the output,"
        }
    }
}

/// A scene's mean efficiency as its row reads it: back-driven and self-locking scenes say so.
fn mean_cell(r: &ReducerEfficiency) -> String {
    let value = number(r.mean_efficiency);
    match (r.flow.driver, r.self_locks) {
        (Driver::Input, _) => value,
        (Driver::Output, false) => format!("{value} (back-driven)"),
        (Driver::Output, true) => format!("{value} (back-driven: SELF-LOCKS)"),
    }
}

/// The caption's word on the dashed red line, when the spec sets `min_mean_efficiency`.
fn limit_note(spec: &Spec) -> &'static str {
    if spec.limits.get("min_mean_efficiency").is_some() {
        "; dashed red: the spec's limit min_mean_efficiency"
    } else {
        ""
    }
}

/// A stacked bar per scene of the mean power lost on each path, W.
fn loss_bars(bars: &[(&str, PathLosses)]) -> String {
    let (w, h, left, top, bottom): (f64, f64, f64, f64, f64) = (660.0, 400.0, 70.0, 40.0, 60.0);
    let legend_w = 150.0;
    let plot_w = w - left - legend_w - 20.0;
    let most = bars
        .iter()
        .map(|(_, p)| p.total())
        .fold(0.0_f64, f64::max)
        .max(1e-12);
    let yt = ticks(0.0, most, 6, true);
    let y_max = yt.values.last().copied().unwrap_or(most).max(most);
    let y = |v: f64| top + (h - top - bottom) * (1.0 - v / y_max);
    let slot = plot_w / bars.len().max(1) as f64;
    let bar_w = (slot * 0.5).min(90.0);
    let body = html! {
        text x=(px(left)) y="22" font-size="15" font-weight="bold" {
            "Mean power lost on each path (W)"
        }
        @for &v in &yt.values {
            line x1=(px(left)) x2=(px(left + plot_w)) y1=(px(y(v))) y2=(px(y(v)))
                stroke="#ddd" {}
            text x=(px(left - 6.0)) y=(px(y(v) + 4.0)) font-size="12" text-anchor="end" {
                (yt.label(v))
            }
        }
        line x1=(px(left)) x2=(px(left)) y1=(px(top)) y2=(px(h - bottom)) stroke="#222" {}
        line x1=(px(left)) x2=(px(left + plot_w)) y1=(px(h - bottom)) y2=(px(h - bottom))
            stroke="#222" {}
        @for (i, (name, p)) in bars.iter().enumerate() {
            @let x = left + slot * (i as f64 + 0.5) - bar_w / 2.0;
            @let values = path_values(p);
            @for (j, (_, colour)) in PATHS.iter().enumerate() {
                @let below: f64 = values[..j].iter().sum();
                @if values[j] > 0.0 {
                    rect x=(px(x)) width=(px(bar_w)) y=(px(y(below + values[j])))
                        height=(px(y(below) - y(below + values[j])))
                        fill=(PALETTE[*colour]) {}
                }
            }
            text x=(px(x + bar_w / 2.0)) y=(px(y(p.total()) - 6.0)) font-size="12"
                text-anchor="middle" { (number(p.total())) " W" }
            text x=(px(x + bar_w / 2.0)) y=(px(h - bottom + 18.0)) font-size="12"
                text-anchor="middle" { (name) }
        }
        text x="16" y=(px((top + h - bottom) / 2.0)) font-size="12" text-anchor="middle"
            transform=(format!("rotate(-90 16 {})", px((top + h - bottom) / 2.0))) {
            "power loss (W)"
        }
        @for (j, (label, colour)) in PATHS.iter().enumerate().rev() {
            @let ly = top + 20.0 * (PATHS.len() - 1 - j) as f64;
            rect x=(px(w - legend_w)) y=(px(ly)) width="14" height="14" fill=(PALETTE[*colour]) {}
            text x=(px(w - legend_w + 20.0)) y=(px(ly + 11.0)) font-size="12" { (label) }
        }
    };
    document(w, h, body)
}

/// The section: per scene with `efficiency` its torque curve, the losses per path in a table,
/// and with a speed the stacked bars of every such scene.
pub(super) fn section(
    spec: &Spec,
    results: &[SceneResult],
    curves: &[Option<TorqueCurve>],
    files: &mut Vec<(String, String)>,
) -> Option<Section> {
    let scenes = scenes_with(spec, results, |r| r.reducer.efficiency.as_ref());
    if scenes.is_empty() {
        return None;
    }
    let mut figures = Vec::new();
    let nm = |t_nmm: f64| signed(number(units::nm(t_nmm)));
    for &(k, s, e) in &scenes {
        let (Some(Some(c)), Some(r)) = (curves.get(k), &e.reducer) else {
            continue;
        };
        let file = format!("efficiency-{}.svg", k + 1);
        files.push((file.clone(), torque_plot(spec, s, c, r).to_svg()));
        figures.push((
            file,
            format!("Efficiency against torque, scene {}", s.name),
            format!(
                "{} torques from {} to {} N·m; the scene's {} N·m marked (diamond){}.",
                c.torque_nmm.len(),
                nm(c.torque_nmm.first().copied().unwrap_or(0.0)),
                nm(c.torque_nmm.last().copied().unwrap_or(0.0)),
                nm(s.output_torque_nmm),
                limit_note(spec)
            ),
        ));
    }
    let bars: Vec<(&str, PathLosses)> = scenes
        .iter()
        .filter_map(|(_, s, e)| Some((s.name.as_str(), e.power_loss_w()?)))
        .collect();
    if !bars.is_empty() {
        files.push(("efficiency-losses.svg".into(), loss_bars(&bars)));
        figures.push((
            "efficiency-losses.svg".into(),
            "Power lost on each path".into(),
            "The mean over each scene's crank angles at its input speed.".into(),
        ));
    }
    let model = spec.design.friction.map_or("none", |f| f.model.name());
    let back_driven = (scenes.iter())
        .filter_map(|(_, _, e)| e.reducer.as_ref())
        .any(|r| r.flow.driver == Driver::Output);
    let body = html! {
        p.note {
            "Each loss is a Coulomb force μ·F times the speed its surfaces slide at (docs/effects/friction.md, \
             \"Friction, efficiency and heat\"); the " (model) " model. η = P_out/(P_out + loss), \
             the mean efficiency P_out/(P_out + mean loss)."
            @if back_driven {
                " Where the output drives (a negative output torque) the power P = |T|·ω_out \
                 enters at the output and η = (P − loss)/P reaches the input; where the losses \
                 take all of it (η ≤ 0) the reducer self-locks."
            }
        }
        (data_table(
            html! {
                th { "scene" } th { "mean efficiency" } th { "rollers (W)" }
                th { "output pins (W)" } th { "crank bearing (W)" } th { "no-load (W)" }
                th { "total (W)" } th { "temperature (°C)" }
            },
            html! { @for (_, s, e) in &scenes { tr {
                td { code { (s.name) } }
                td { (e.reducer.as_ref().map_or("—".into(), mean_cell)) }
                @match e.power_loss_w() {
                    Some(p) => {
                        @for v in path_values(&p) { td { (number(v)) } }
                        td { (number(p.total())) }
                    }
                    None => { @for _ in 0..5 { td { "— (no speed)" } } }
                }
                td { (e.reducer.as_ref().and_then(|r| r.temperature_c).map_or("—".into(), number)) }
            } } },
        ))
        div.grid { @for (f, t, c) in &figures { (figure(f, t, c)) } }
    };
    Some(Section::new(
        "efficiency",
        html! { "Friction, efficiency and heat" },
        body,
    ))
}
