//! The review's design: the reducer as the spec gives it and its tooth-profile modification.

use super::common::{data_table, Section};
use crate::model::{
    Crowning, Friction, FrictionModel, Modification, PinFriction, PinMode, RollerFriction,
    RollerMode, Thermal,
};
use crate::numeric::{input, number};
use crate::spec::Spec;
use crate::units;
use maud::{html, Markup};

/// The design as the spec gives it, with the modification `m` it was designed with (the
/// spec's own; with a measured disc the scenes ran on the identified one, `as_built`).
pub(super) fn section(
    spec: &Spec,
    m: &Modification,
    mass: Option<&crate::engine::mass_properties::MassProperties>,
) -> Section {
    let d = &spec.design;
    let mm = |x: f64| format!("{} mm", number(x));
    let (disc, rollers) = (&d.disc_material, &d.roller_material);
    let pairs = |head: &str, rows: Markup| data_table(html! { th colspan="2" { (head) } }, rows);
    let row = |k: &str, v: String| html! { tr { th { (k) } td { (v) } } };
    let reducer = html! {
        (row("teeth nc / rollers np", format!("{} / {}", d.teeth, d.rollers)))
        (row("eccentricity e", mm(d.eccentricity_mm)))
        (row("roller circle Rp / roller radius Rrp",
            format!("{} / {}", mm(d.roller_circle_radius_mm), mm(d.roller_radius_mm))))
        (row("face width B", mm(d.face_width_mm)))
        (row("output pins", format!("{} on rw {}, pin radius {}, hole radius {}", d.pins.count,
            mm(d.pins.circle_radius_mm), mm(d.pins.pin_radius_mm), mm(d.hole_radius_mm()))))
        (row("material", format!("E {} GPa, ν {} (rollers and pins: E {} GPa, ν {}); E* {} GPa",
            number(units::gpa(disc.youngs_modulus_mpa)), number(disc.poisson_ratio),
            number(units::gpa(rollers.youngs_modulus_mpa)), number(rollers.poisson_ratio),
            number(units::gpa(d.contact_modulus_mpa())))))
        (row("K1 = e·np/Rp", number(d.k1())))
        @if d.discs > 1 {
            (row("discs", format!("{}, at crank phases {}", d.discs,
                (0..d.discs).map(|k| format!("{}°", number(units::deg(d.disc_phase_rad(k)))))
                    .collect::<Vec<_>>().join(", "))))
        }
        @if let Some(b) = &d.crank_bearing {
            (row("crank bearing (each disc)", bearing_text(b)))
        }
        @for (k, v) in friction_rows(d.friction.as_ref(), d.thermal.as_ref()) {
            (row(k, v))
        }
        @for (k, v) in mass.map(|m| crate::report::mass_properties::design_rows(spec, m))
            .into_iter().flatten() {
            (row(k, v))
        }
    };
    let modification = html! {
        (row("shift ΔRp", mm(m.shift_mm)))
        (row("equidistant ΔRrp", mm(m.equidistant_mm)))
        (row("rotation Δδ", format!("{} deg", number(units::deg(m.rotation_rad)))))
        (row("tip clearance ΔRrp − ΔRp", format!("{} µm", number(units::um(m.tip_clearance_mm())))))
        @if let Some(c) = spec.scenes.first().and_then(|s| crowning(&s.face.crowning)) {
            (row("crowning", c))
        }
    };
    let body = html! {
        div.cols { (pairs("reducer", reducer)) (pairs("tooth-profile modification", modification)) }
    };
    Section::new("design", html! { "Design" }, body)
}

/// The friction and heat inputs (`reducer.friction`, `reducer.thermal`) as the design table
/// states them, (what, value with its unit), each value as the spec writes it; none without
/// them. A path the spec gives no friction says so.
fn friction_rows(f: Option<&Friction>, t: Option<&Thermal>) -> Vec<(&'static str, String)> {
    let mut rows = Vec::new();
    if let Some(f) = f {
        rows.push((
            "friction model",
            match f.model {
                FrictionModel::Loss => {
                    "loss (the frictionless balance's forces, each path's \
                                        loss μ·F·sliding speed)"
                }
                FrictionModel::Coupled => "coupled (friction μ·F inside every contact's balance)",
            }
            .to_string(),
        ));
        let none = || "no friction (not given)".to_string();
        rows.push((
            "friction, rollers",
            match f.rollers {
                Some(RollerFriction {
                    mode: RollerMode::Fixed,
                    mu,
                }) => {
                    format!("fixed, μ {} (the disc slides over the roller)", input(mu))
                }
                Some(RollerFriction {
                    mode: RollerMode::Rotating { bore_radius_mm },
                    mu,
                }) => {
                    format!(
                        "rotating on pins of radius r_b {} mm, μ {} (at the roller's pin)",
                        input(bore_radius_mm),
                        input(mu)
                    )
                }
                None => none(),
            },
        ));
        rows.push((
            "friction, output pins",
            match f.output_pins {
                Some(PinFriction {
                    mode: PinMode::Fixed,
                    mu,
                }) => {
                    format!("fixed, μ {} (the hole slides over the pin)", input(mu))
                }
                Some(PinFriction {
                    mode: PinMode::Sleeve { bore_radius_mm },
                    mu,
                }) => format!(
                    "free sleeves on pins of radius r_bore {} mm, μ {} (between sleeve and pin)",
                    input(bore_radius_mm),
                    input(mu)
                ),
                None => none(),
            },
        ));
        rows.push((
            "friction, crank bearing",
            match f.crank_bearing {
                Some(b) => format!(
                    "μ {} at its bore d {} mm",
                    input(b.mu),
                    input(b.bore_diameter_mm)
                ),
                None => none(),
            },
        ));
        let t0 = &f.no_load_torque_nmm;
        let no_load = if !t0.is_constant() {
            Some(crate::report::explain::no_load_table(t0))
        } else {
            (t0.max_nmm() > 0.0).then(|| format!("{} N·mm", input(t0.max_nmm())))
        };
        rows.extend(no_load.map(|v| ("no-load torque at the input", v)));
    }
    if let Some(t) = t {
        rows.push((
            "housing's heat path",
            format!(
                "area A {} m², heat transfer h {} W/(m²·K), ambient {} °C",
                input(t.housing_area_m2),
                input(t.heat_transfer_w_per_m2k),
                input(t.ambient_c)
            ),
        ));
    }
    rows
}

/// The disc's crowning along the face (`modification.crowning`, every scene's alike) as the
/// design table states it; `None` for a straight disc.
fn crowning(c: &Crowning) -> Option<String> {
    let mm = |x: f64| format!("{} mm", number(x));
    match *c {
        Crowning::None => None,
        Crowning::Circular {
            radius_mm,
            start_mm,
        } => Some(format!(
            "circular, Rc {}, flat over |z| ≤ {}",
            mm(radius_mm),
            mm(start_mm)
        )),
        Crowning::Logarithmic {
            design_load_n,
            end_drop_mm,
            load_coefficient,
            crowned_fraction,
        } => Some(format!(
            "logarithmic (Fujiwara & Kawase), Q {} N, end drop {}, K1 {}, K2 {}",
            number(design_load_n),
            mm(end_drop_mm),
            number(load_coefficient),
            number(crowned_fraction)
        )),
    }
}

/// The crank bearing as given: its dynamic rating and life exponent, and, where the spec
/// gives them, its static rating C0 (the strength effect's static safety) and its outer
/// diameter (the disc's bore).
fn bearing_text(b: &crate::model::CrankBearing) -> String {
    let mut text = format!(
        "C {} N, life exponent p {}",
        number(b.dynamic_load_rating_n),
        number(b.life_exponent)
    );
    if let Some(c0) = b.static_load_rating_n {
        text += &format!(", C0 {} N", number(c0));
    }
    if let Some(d) = b.outer_diameter_mm {
        text += &format!(", outer diameter {} mm (the disc's bore)", number(d));
    }
    text
}
