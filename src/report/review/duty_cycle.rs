//! The review's duty cycles ([`engine::duty_cycle`](crate::engine::duty_cycle)): per duty-cycle
//! scene the cycle's figures (crank-bearing life by Palmgren–Miner, equivalent torque, mean
//! speed, energy-weighted efficiency), a table of its bins and their pictures (`duty_spectrum`:
//! the load spectrum, and each bin's shares of time, revolutions and bearing damage).

use super::common::{data_table, figure, numbered, scenes_with, signed, Section};
use super::duty_spectrum;
use crate::engine::duty_cycle::{bin_equivalent_loads, damage_shares};
use crate::model::quantity::{MAX_CONTACT_PRESSURE, MEAN_EFFICIENCY};
use crate::model::results::SceneResult;
use crate::numeric::number;
use crate::report::place::or_unbounded;
use crate::spec::Spec;
use crate::units;
use maud::html;

/// The duty cycles of the spec's scenes, one block per duty-cycle scene with its pictures
/// (pushed to `files`); `None` without one.
pub(super) fn section(
    spec: &Spec,
    results: &[SceneResult],
    files: &mut Vec<(String, String)>,
) -> Option<Section> {
    let cycles = scenes_with(spec, results, |r| r.duty.as_deref());
    if cycles.is_empty() {
        return None;
    }
    let mut pictures = Vec::new();
    for &(k, s, d) in &cycles {
        let prefix = numbered("duty", k, &s.name);
        let damage = damage_shares(&spec.design, &d.bins);
        let (spectrum, shares) = (
            format!("{prefix}-spectrum.svg"),
            format!("{prefix}-shares.svg"),
        );
        files.push((spectrum.clone(), duty_spectrum::spectrum(&s.name, d)));
        files.push((
            shares.clone(),
            duty_spectrum::shares(&s.name, d, damage.as_deref()),
        ));
        pictures.push((spectrum, shares, damage.is_some()));
    }
    let optional = |x: Option<f64>| x.map_or("—".to_string(), number);
    let body = html! {
        p.note {
            "Each bin runs as its scene loaded at the bin's torque and speed over the scene's \
             crank range. ISO 281 with the Palmgren–Miner rule: P = (Σ sᵢ·nᵢ·Pᵢ^p / \
             Σ sᵢ·nᵢ)^(1/p), Pᵢ each bin's equivalent load over its loaded period, \
             L10h = (C/P)^p · 10⁶ / (60 · Σ sᵢ·nᵢ · (1 + 1/nc)); a bin at a standstill turns no \
             revolution. Equivalent torque T_eq = (Σ sᵢ·nᵢ·|Tᵢ|³ / Σ sᵢ·nᵢ)^(1/3) (weighted by \
             revolutions), mean speed Σ sᵢ·nᵢ; mean efficiency by energy Σ sᵢ·nᵢ·Dᵢ / \
             Σ sᵢ·nᵢ·Eᵢ, each bin's power delivered Dᵢ and entering Eᵢ as its power flows (the \
             output driving a bin of negative torque; a bin at a standstill has no efficiency)."
        }
        @for ((_, s, d), (spectrum, shares, damage)) in cycles.iter().zip(&pictures) {
            h3 { "Scene " code { (s.name) } }
            ul {
                @for (k, b) in d.life.iter().enumerate() {
                    li {
                        @if d.life.len() > 1 { "disc " (k) ": " }
                        "crank-bearing life L10h "
                        (b.life_h.map_or("not rated".to_string(), |h| {
                            or_unbounded(h, |h| format!("{} h", number(h)))
                        }))
                        " at P = " (number(b.equivalent_load_n)) " N"
                    }
                }
                @if d.life.is_empty() {
                    li { "crank-bearing life not rated (no `reducer.crank_bearing`, or the crank \
                          range is not whole loaded periods)" }
                }
                li { "equivalent output torque " (signed(number(units::nm(d.equivalent_torque_nmm)))) " N·m" }
                li { "mean input speed " (number(d.mean_speed_rpm)) " rpm" }
                @if let Some(e) = d.mean_efficiency {
                    li { "mean efficiency by energy " (number(e)) }
                }
            }
            (data_table(
                html! {
                    th { "bin" } th { "output torque (N·m)" } th { "input speed (rpm)" }
                    th { "time share" } th { "share of revolutions" }
                    th { "equivalent load Pᵢ (N)" } th { "peak pressure (MPa)" }
                    th { "mean efficiency" }
                },
                html! { @for (j, b) in d.bins.iter().enumerate() { tr {
                    td { (j) }
                    td { (signed(number(units::nm(b.bin.output_torque_nmm)))) }
                    td { (number(b.bin.input_speed_rpm)) }
                    td { (number(b.bin.time_share)) }
                    td { (number(d.revolution_share(b))) }
                    td { (bin_equivalent_loads(&b.result).map_or("—".to_string(), |p| {
                        p.iter().map(|&x| number(x)).collect::<Vec<_>>().join(", ")
                    })) }
                    td { (optional(MAX_CONTACT_PRESSURE.scalar(&b.result).map(|e| e.value))) }
                    td { (optional(MEAN_EFFICIENCY.scalar(&b.result).map(|e| e.value))) }
                } } },
            ))
            div.grid {
                (figure(spectrum, &format!("Load spectrum, scene {}", s.name),
                    "Each bin's output torque (signed: negative brakes) and input speed, as wide \
                     as its share of the cycle's time."))
                (figure(shares, &format!("Shares of the cycle, scene {}", s.name),
                    if *damage {
                        "Each bin's share of the time, of the revolutions (sᵢ·nᵢ / Σ sⱼ·nⱼ) \
                         and of the crank bearing's damage by Miner's rule (sᵢ·nᵢ·Pᵢ^p / \
                         Σ sⱼ·nⱼ·Pⱼ^p); a standstill turns and wears nothing."
                    } else {
                        "Each bin's share of the time and of the revolutions (sᵢ·nᵢ / \
                         Σ sⱼ·nⱼ); the crank bearing is not rated, so no damage is shown."
                    }))
            }
        }
    };
    Some(Section::new("duty-cycle", html! { "Duty cycle" }, body))
}
