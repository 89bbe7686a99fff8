//! The review's pictures of a duty cycle: its load spectrum (each bin's output torque and input
//! speed over its share of the cycle's time) and each bin's shares of the cycle (time,
//! revolutions, crank-bearing damage by Palmgren–Miner, `engine::duty_cycle::damage_shares`).

use crate::model::results::DutyCycle;
use crate::report::svg::frame::{rotated, titles, top};
use crate::report::svg::{document, px, ticks, PALETTE};
use crate::units;
use maud::{html, Markup};

/// Width of a figure and its plot area's left and right edges, px.
const W: f64 = 660.0;
const LEFT: f64 = 80.0;
const RIGHT: f64 = 620.0;

/// One bar: its x extent (px), value, class (what it shows) and colour.
struct Bar {
    x: (f64, f64),
    value: f64,
    class: &'static str,
    color: &'static str,
}

/// A panel of bars from zero (px from `y0`, `height` tall) under the y axis `label`: its frame
/// (class `panel`), round ticks over the bars' range and zero, the zero line and the bars (each
/// a `rect` of its class, from zero to its value).
fn panel(y0: f64, height: f64, label: &str, bars: &[Bar]) -> Markup {
    let lo = bars.iter().map(|b| b.value).fold(0.0, f64::min);
    let hi = bars.iter().map(|b| b.value).fold(0.0, f64::max);
    let t = ticks(lo, hi, 4, true);
    let y = |v: f64| y0 + height * (t.hi - v) / (t.hi - t.lo);
    html! {
        rect.panel x=(px(LEFT)) y=(px(y0)) width=(px(RIGHT - LEFT)) height=(px(height))
            fill="none" stroke="#333" {}
        @for &v in &t.values {
            line x1=(px(LEFT - 5.0)) x2=(px(LEFT)) y1=(px(y(v))) y2=(px(y(v))) stroke="#333" {}
            text x=(px(LEFT - 8.0)) y=(px(y(v) + 4.0)) font-size="12" text-anchor="end" {
                (t.label(v))
            }
        }
        @for b in bars {
            @let (top, bottom) = (y(b.value.max(0.0)), y(b.value.min(0.0)));
            rect class=(b.class) x=(px(b.x.0)) y=(px(top)) width=(px(b.x.1 - b.x.0))
                height=(px(bottom - top)) fill=(b.color) {}
        }
        line x1=(px(LEFT)) x2=(px(RIGHT)) y1=(px(y(0.0))) y2=(px(y(0.0))) stroke="#333" {}
        (rotated(16.0, y0 + height / 2.0, label))
    }
}

/// The load spectrum of a cycle: x the cycle's time (0 to 1, each bin a bar as wide as its
/// time share, in the spec's order), the output torque (N·m, signed) above and the input speed
/// (rpm) below, each bar numbered by its bin.
pub(super) fn spectrum(scene: &str, d: &DutyCycle) -> String {
    let top = top(1);
    let (height, gap) = (170.0, 46.0);
    let x = |t: f64| LEFT + t * (RIGHT - LEFT);
    let mut start = 0.0;
    let spans: Vec<(f64, f64)> = (d.bins.iter())
        .map(|b| {
            let span = (x(start), x(start + b.bin.time_share));
            start += b.bin.time_share;
            span
        })
        .collect();
    let bars = |f: &dyn Fn(usize) -> f64, class, color| -> Vec<Bar> {
        let each = spans.iter().enumerate();
        (each.map(|(i, &x)| Bar {
            x,
            value: f(i),
            class,
            color,
        }))
        .collect()
    };
    let torque = bars(
        &|i| units::nm(d.bins[i].bin.output_torque_nmm),
        "torque",
        PALETTE[0],
    );
    let speed = bars(&|i| d.bins[i].bin.input_speed_rpm, "speed", PALETTE[1]);
    let lower = top + height + gap;
    let bottom = lower + height;
    let subtitle = format!(
        "{} bins, each as wide as its share of the cycle's time, in the spec's order",
        d.bins.len()
    );
    let t = ticks(0.0, 1.0, 5, true);
    let body = html! {
        (titles(LEFT, &format!("Load spectrum: scene {scene}"), &[subtitle]))
        (panel(top, height, "output torque (N·m)", &torque))
        (panel(lower, height, "input speed (rpm)", &speed))
        @for (i, &(a, b)) in spans.iter().enumerate() {
            @if b - a >= 14.0 {
                text.bin x=(px((a + b) / 2.0)) y=(px(top + height + 16.0)) font-size="12"
                    text-anchor="middle" { "bin " (i) }
            }
        }
        @for &v in &t.values {
            line x1=(px(x(v))) x2=(px(x(v))) y1=(px(bottom)) y2=(px(bottom + 5.0)) stroke="#333" {}
            text x=(px(x(v))) y=(px(bottom + 18.0)) font-size="12" text-anchor="middle" {
                (t.label(v))
            }
        }
        text x=(px((LEFT + RIGHT) / 2.0)) y=(px(bottom + 38.0)) font-size="13"
            text-anchor="middle" { "share of the cycle's time" }
    };
    document(W, bottom + 50.0, body)
}

/// Each bin's shares of the cycle as grouped bars, in %: its time share, its share of the
/// revolutions sᵢ·nᵢ/Σ sⱼ·nⱼ and, per disc, its share of the crank bearing's damage
/// (`damage`, `[disc][bin]`, none when the bearing is not rated).
pub(super) fn shares(scene: &str, d: &DutyCycle, damage: Option<&[Vec<f64>]>) -> String {
    let n = d.bins.len();
    let mut groups: Vec<(String, &'static str, Vec<f64>)> = vec![
        (
            "time".into(),
            "time-share",
            d.bins.iter().map(|b| b.bin.time_share).collect(),
        ),
        (
            "revolutions".into(),
            "revolution-share",
            (d.bins.iter()).map(|b| d.revolution_share(b)).collect(),
        ),
    ];
    for (k, shares) in damage.unwrap_or_default().iter().enumerate() {
        let disc = if damage.is_some_and(|s| s.len() > 1) {
            format!(" (disc {k})")
        } else {
            String::new()
        };
        groups.push((
            format!("crank-bearing damage{disc}"),
            "damage-share",
            shares.clone(),
        ));
    }
    let top = top(1);
    let height = 260.0;
    let slot = (RIGHT - LEFT) / n.max(1) as f64;
    let bar_w = 0.8 * slot / groups.len() as f64;
    let mut bars = Vec::new();
    for (g, (_, class, values)) in groups.iter().enumerate() {
        for (i, &v) in values.iter().enumerate() {
            let x0 = LEFT + slot * (i as f64 + 0.1) + bar_w * g as f64;
            bars.push(Bar {
                x: (x0, x0 + bar_w),
                value: 100.0 * v,
                class,
                color: PALETTE[g % PALETTE.len()],
            });
        }
    }
    let bottom = top + height;
    let legend_y = bottom + 46.0;
    let body = html! {
        (titles(LEFT, &format!("Shares of the cycle per bin: scene {scene}"),
            &["time, revolutions and crank-bearing damage (Miner's rule)".to_string()]))
        (panel(top, height, "share (%)", &bars))
        @for i in 0..n {
            text.bin x=(px(LEFT + slot * (i as f64 + 0.5))) y=(px(bottom + 18.0)) font-size="12"
                text-anchor="middle" { "bin " (i) }
        }
        @for (g, (name, _, _)) in groups.iter().enumerate() {
            @let lx = LEFT + 200.0 * (g % 3) as f64;
            @let ly = legend_y + 20.0 * (g / 3) as f64;
            rect x=(px(lx)) y=(px(ly - 11.0)) width="14" height="14"
                fill=(PALETTE[g % PALETTE.len()]) {}
            text.legend x=(px(lx + 20.0)) y=(px(ly)) font-size="12" { (name) }
        }
    };
    document(
        W,
        legend_y + 20.0 * groups.len().div_ceil(3) as f64 + 10.0,
        body,
    )
}
