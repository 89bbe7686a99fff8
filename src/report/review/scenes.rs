//! The review's section of each scene: what it computes, over which crank angles, and the plots
//! of its curves (`plots`), each disc's own with several discs.

use super::common::{figure, numbered, Section};
use super::plots;
use crate::engine::mass_properties::Unbalance;
use crate::model::results::SceneResult;
use crate::model::{ContactLaw, Effect, Plan, Scene};
use crate::numeric::number;
use crate::spec::Spec;
use crate::units;
use maud::html;

/// A scene's plots, or nothing when it computed no curve a plot draws.
/// `unbalance`: the scene's at speed, when it computes `inertia`.
pub(super) fn section(
    spec: &Spec,
    (k, scene, r): (usize, &Scene, &SceneResult),
    unbalance: Option<&Unbalance>,
    files: &mut Vec<(String, String)>,
) -> Option<Section> {
    let prefix = numbered("scene", k, &scene.name);
    // A duty cycle's curves are its bins', each at its own speed: no one speed to name.
    let at_speed = (unbalance.filter(|_| scene.duty_cycle.is_none()))
        .map(crate::report::mass_properties::bearing_plot_note);
    let plots = plots::scene_plots(spec, (r, None), &prefix, at_speed.as_deref());
    // With several discs, each disc's own curves (forces, lags, bearing, its torque share);
    // one disc's are the scene's.
    let discs: Vec<(usize, Vec<plots::Plot>)> = (r.discs.iter())
        .enumerate()
        .filter(|_| r.names_discs())
        .map(|(d, disc)| {
            (
                d,
                plots::scene_plots(
                    spec,
                    (r, Some(disc)),
                    &format!("{prefix}-disc-{d}"),
                    at_speed.as_deref(),
                ),
            )
        })
        .filter(|(_, p)| !p.is_empty())
        .collect();
    if plots.is_empty() && discs.is_empty() {
        return None;
    }
    let phase = |d: usize| number(units::deg(spec.design.disc_phase_rad(d)));
    let body = html! {
        p.note { (scene_summary(spec, scene)) }
        @if let Some(u) = unbalance {
            p.note { (crate::report::mass_properties::scene_note(spec, u)) }
        }
        @if !plots.is_empty() {
            div.grid { @for p in &plots { (figure(&p.file, &p.title, &p.caption)) } }
        }
        @for (d, disc) in &discs {
            h3 { "Disc " (d) " (crank phase " (phase(*d)) "°)" }
            div.grid { @for p in disc { (figure(&p.file, &p.title, &p.caption)) } }
        }
    };
    let every = plots
        .into_iter()
        .chain(discs.into_iter().flat_map(|(_, p)| p));
    files.extend(every.map(|p| (p.file, p.svg)));
    let heading = html! { "Scene " code { (scene.name) } };
    Some(Section::new(prefix, heading, body))
}

pub(super) fn scene_summary(spec: &Spec, scene: &Scene) -> String {
    let plan = Plan::for_scene(scene);
    let step = units::deg(crate::numeric::step(&scene.crank_rad));
    let effects: Vec<&str> = plan.effects.iter().map(|p| p.effect.name()).collect();
    let load = match &scene.torque_sweep {
        Some(t) => format!(
            "Input locked; output torque swept ±{} N·m ({} steps per quarter loop)",
            number(units::nm(t.rated_nmm)),
            t.steps
        ),
        None => format!(
            "Output torque {} N·m",
            number(units::nm(scene.output_torque_nmm))
        ),
    };
    let discs = match spec.design.discs {
        1 => String::new(),
        n => format!(", shared by {n} discs"),
    };
    let mut s = format!(
        "{load}{discs}; {} crank angles from {:.2}° in steps of {}°; computes {}.",
        scene.crank_rad.len(),
        scene.crank_rad.first().map_or(0.0, |&a| units::deg(a)),
        number(step),
        effects.join(", ")
    );
    if plan.has(Effect::RollerContact) {
        s += &format!(
            " Contact law {}, {} geometry, {} crank bearing.",
            match scene.contact_law {
                ContactLaw::PaperLinear => "F = (π/4)·E*·L·d (paper Eq. 9)",
                ContactLaw::HertzNonlinear => "Hertz line contact (Johnson, non-linear)",
            },
            scene.geometry,
            match scene.bearing_stiffness_n_per_mm {
                Some(k) => format!("compliant ({} N/mm)", number(k)),
                None => "rigid".into(),
            }
        );
    }
    let pins = plan.has(Effect::OutputPins);
    // (A torsion scene's crank angles are where the input is locked, not a sweep.)
    if scene.torque_sweep.is_none() && !scene.spans_loaded_periods(&spec.design, &plan) {
        let period = number(units::deg(scene.run_period_rad(&spec.design, &plan)));
        s += &if pins {
            format!(
                " The sweep does not cover whole periods of the loaded disc ({period}°: mesh \
                 and output pins, as run)."
            )
        } else {
            format!(" The sweep does not cover whole mesh periods ({period}°, as run).")
        };
    }
    s
}
