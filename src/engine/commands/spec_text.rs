//! The YAML of a spec built in the spec's raw form: what `design` writes for each design of
//! its front (`design_search::candidate::raw_spec`), read back by `spec::parse` as the same
//! spec. Numbers are written in their shortest form that reads back as the same double.

use crate::model::quantity::LIMITS;
use crate::spec::raw::*;
use std::fmt::Write;

/// A number as YAML that reads back as the same double (Rust's shortest round-trip form).
fn num(x: f64) -> String {
    format!("{x:?}")
}

/// A flow mapping `{ key: value, … }` of the pairs whose value is given.
fn flow(pairs: &[(&str, Option<String>)]) -> String {
    let items: Vec<String> = (pairs.iter())
        .filter_map(|(k, v)| v.as_ref().map(|v| format!("{k}: {v}")))
        .collect();
    format!("{{ {} }}", items.join(", "))
}

/// A line `key: value` (`key` indented as the line is), when the value is given.
fn line(s: &mut String, key: &str, value: Option<String>) {
    if let Some(v) = value {
        let _ = writeln!(s, "{key}: {v}");
    }
}

/// The text of `raw`, with `header` first as comments: the keys a design search's spec uses
/// (no studies, goldens, deviations or measured points: it has none).
pub(crate) fn spec_text(raw: &RawSpec, header: &str) -> String {
    let mut s = String::new();
    for line in header.lines() {
        let _ = writeln!(s, "# {line}");
    }
    let name = serde_json::to_string(&raw.name).unwrap_or_default();
    let _ = writeln!(s, "name: {name}");
    reducer(&mut s, &raw.reducer);
    let m = &raw.modification;
    let _ = writeln!(s, "modification:");
    let _ = writeln!(s, "  shift_mm: {}", num(m.shift_mm));
    let _ = writeln!(s, "  equidistant_mm: {}", num(m.equidistant_mm));
    line(&mut s, "  crowning", m.crowning.as_ref().map(crowning));
    let _ = writeln!(s, "scenes:");
    raw.scenes.iter().for_each(|c| scene(&mut s, c));
    if !raw.limits.is_empty() {
        let _ = writeln!(s, "limits:");
        // In the registry's order, as a spec lists them.
        for def in LIMITS {
            if let Some(RawLimit::Bound(v)) = raw.limits.get(def.key) {
                let _ = writeln!(s, "  {}: {}", def.key, num(*v));
            }
        }
    }
    s
}

fn reducer(s: &mut String, r: &RawReducer) {
    let _ = writeln!(s, "reducer:");
    let _ = writeln!(s, "  teeth: {}", r.teeth);
    let _ = writeln!(s, "  rollers: {}", r.rollers);
    let _ = writeln!(s, "  eccentricity_mm: {}", num(r.eccentricity_mm));
    let _ = writeln!(
        s,
        "  roller_circle_radius_mm: {}",
        num(r.roller_circle_radius_mm)
    );
    let _ = writeln!(s, "  roller_radius_mm: {}", num(r.roller_radius_mm));
    let _ = writeln!(s, "  face_width_mm: {}", num(r.face_width_mm));
    let _ = writeln!(s, "  discs: {}", r.discs);
    let p = &r.output_pins;
    let _ = writeln!(s, "  output_pins:");
    let _ = writeln!(s, "    count: {}", p.count);
    let _ = writeln!(s, "    circle_radius_mm: {}", num(p.circle_radius_mm));
    let _ = writeln!(s, "    pin_radius_mm: {}", num(p.pin_radius_mm));
    let _ = writeln!(s, "    hole_clearance_mm: {}", num(p.hole_clearance_mm));
    if let Some(support) = &p.support {
        let positions: Vec<String> = support.disc_positions_mm.iter().map(|&a| num(a)).collect();
        let support = flow(&[
            ("kind", Some(support.kind.clone())),
            ("length_mm", Some(num(support.length_mm))),
            (
                "disc_positions_mm",
                Some(format!("[{}]", positions.join(", "))),
            ),
        ]);
        let _ = writeln!(s, "    support: {support}");
    }
    material(s, "material", &r.material);
    if let Some(m) = &r.roller_material {
        material(s, "roller_material", m);
    }
    if let Some(b) = &r.crank_bearing {
        let _ = writeln!(s, "  crank_bearing:");
        let _ = writeln!(
            s,
            "    dynamic_load_rating_n: {}",
            num(b.dynamic_load_rating_n)
        );
        line(s, "    life_exponent", b.life_exponent.map(num));
        let c0 = b.static_load_rating_n.map(num);
        line(s, "    static_load_rating_n", c0);
    }
    if let Some(f) = &r.friction {
        friction(s, f);
    }
    if let Some(t) = &r.thermal {
        let thermal = flow(&[
            ("housing_area_m2", Some(num(t.housing_area_m2))),
            (
                "heat_transfer_w_per_m2k",
                Some(num(t.heat_transfer_w_per_m2k)),
            ),
            ("ambient_c", Some(num(t.ambient_c))),
        ]);
        let _ = writeln!(s, "  thermal: {thermal}");
    }
}

/// `reducer.material` or `reducer.roller_material` (`key`): elasticity, density, strength.
fn material(s: &mut String, key: &str, m: &RawMaterial) {
    let _ = writeln!(s, "  {key}:");
    let _ = writeln!(s, "    youngs_modulus_gpa: {}", num(m.youngs_modulus_gpa));
    let _ = writeln!(s, "    poisson_ratio: {}", num(m.poisson_ratio));
    line(s, "    density_kg_per_m3", m.density_kg_per_m3.map(num));
    line(s, "    yield_strength_mpa", m.yield_strength_mpa.map(num));
    if let Some(f) = &m.contact_fatigue {
        let law = flow(&[
            ("pressure_mpa", Some(num(f.pressure_mpa))),
            ("cycles", Some(num(f.cycles))),
            ("exponent", Some(num(f.exponent))),
            ("endurance_pressure_mpa", f.endurance_pressure_mpa.map(num)),
        ]);
        let _ = writeln!(s, "    contact_fatigue: {law}");
    }
}

fn friction(s: &mut String, f: &RawFriction) {
    let path = |mode: &str, mu: f64, bore: Option<f64>| {
        flow(&[
            ("mode", Some(mode.to_string())),
            ("mu", Some(num(mu))),
            ("bore_radius_mm", bore.map(num)),
        ])
    };
    let _ = writeln!(s, "  friction:");
    line(s, "    model", f.model.clone());
    let rollers = (f.rollers.as_ref()).map(|r| path(&r.mode, r.mu, r.bore_radius_mm));
    line(s, "    rollers", rollers);
    let pins = (f.output_pins.as_ref()).map(|p| path(&p.mode, p.mu, p.bore_radius_mm));
    line(s, "    output_pins", pins);
    if let Some(b) = &f.crank_bearing {
        let bearing = flow(&[
            ("mu", Some(num(b.mu))),
            ("bore_diameter_mm", Some(num(b.bore_diameter_mm))),
        ]);
        let _ = writeln!(s, "    crank_bearing: {bearing}");
    }
    let t0 = match &f.no_load_torque_nmm {
        None => return,
        Some(RawNoLoad::Constant(t)) => num(*t),
        Some(RawNoLoad::Table(points)) => {
            let pairs: Vec<String> = (points.iter())
                .map(|[n, t]| format!("[{}, {}]", num(*n), num(*t)))
                .collect();
            format!("[{}]", pairs.join(", "))
        }
    };
    let _ = writeln!(s, "    no_load_torque_nmm: {t0}");
}

fn crowning(c: &RawCrowning) -> String {
    flow(&[
        ("kind", Some(c.kind.clone())),
        ("radius_mm", c.radius_mm.map(num)),
        ("start_mm", c.start_mm.map(num)),
        ("design_load_n", c.design_load_n.map(num)),
        ("end_drop_mm", c.end_drop_mm.map(num)),
        ("load_coefficient", c.load_coefficient.map(num)),
        ("crowned_fraction", c.crowned_fraction.map(num)),
    ])
}

fn scene(s: &mut String, c: &RawScene) {
    let _ = writeln!(s, "  - name: {}", c.name);
    line(s, "    output_torque_nm", c.output_torque_nm.map(num));
    line(s, "    input_speed_rpm", c.input_speed_rpm.map(num));
    if let Some(bins) = &c.duty_cycle {
        let _ = writeln!(s, "    duty_cycle:");
        for b in bins {
            let bin = flow(&[
                ("output_torque_nm", Some(num(b.output_torque_nm))),
                ("input_speed_rpm", Some(num(b.input_speed_rpm))),
                ("time_share", Some(num(b.time_share))),
            ]);
            let _ = writeln!(s, "      - {bin}");
        }
    }
    if let Some(t) = &c.torque_sweep {
        let sweep = flow(&[
            ("rated_nm", Some(num(t.rated_nm))),
            ("steps", Some(t.steps.to_string())),
        ]);
        let _ = writeln!(s, "    torque_sweep: {sweep}");
    }
    let crank = flow(&[
        ("from_deg", Some(num(c.crank.from_deg))),
        ("to_deg", Some(num(c.crank.to_deg))),
        ("steps", Some(c.crank.steps.to_string())),
    ]);
    let _ = writeln!(s, "    crank: {crank}");
    if let Some(m) = &c.misalignment {
        let tilt = flow(&[
            ("about_x_mrad", Some(num(m.about_x_mrad))),
            ("about_y_mrad", Some(num(m.about_y_mrad))),
        ]);
        let _ = writeln!(s, "    misalignment: {tilt}");
    }
    line(s, "    face_slices", c.face_slices.map(|n| n.to_string()));
    let _ = writeln!(s, "    effects: [{}]", c.effects.join(", "));
}
