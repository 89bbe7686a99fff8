//! The reducer's mass properties and the discs at speed in words (issue 42,
//! [`engine::mass_properties`](crate::engine::mass_properties)): the design table's rows, the
//! terminal's lines after the headline results, `check --explain`'s lines and the crank
//! bearing's plot at speed.

use crate::engine::mass_properties::{MassProperties, Unbalance};
use crate::geometry::mass_properties::DiscMass;
use crate::model::Scene;
use crate::numeric::number;
use crate::report::place::listed;
use crate::spec::Spec;
use crate::units;

/// Below this fraction of the size of the terms it is summed from, a centroid offset or a net
/// unbalance force is round-off and is said as none, not printed as a number. The centroid
/// S/A: `geometry::mass_properties::profile_moments` returns S once two trapezoid sums agree
/// within max(`PROFILE_MOMENTS_REL_TOL`, 8·√n·ε) ≤ 7.2e-13 (at its cap of 163,841 points) of
/// A·r_g, so S/A is off by at most ~1e-12·r_g (r_g the face's radius of gyration; the holes'
/// and the bore's closed forms add an ulp of their circle); the shipped discs show 3e-15 mm at
/// r_g ≈ 20 mm (1.6e-16). The net force Σ F_c·e_φk of evenly phased discs: each unit vector
/// within an ulp, so ≤ N·ε·F_c (1.2e-16·F_c seen). 1e-9 is 1,000 times the larger bound, and
/// 1e-9·r_g = 2e-8 mm on the shipped disc, 50,000 times below a micrometre, so an offset from a
/// real deviation (a form error, micrometres) is still printed. A profile integrated as its
/// polygon (K1 near 1, within `SECTION_TOLERANCE_MM`) is not round-off: its offset is printed.
const ROUND_OFF: f64 = 1e-9;

/// `value` unless it is round-off of terms of size `scale` (`ROUND_OFF`).
fn resolved(value: f64, scale: f64) -> Option<f64> {
    (value > ROUND_OFF * scale).then_some(value)
}

/// "centroid on the centre", or "centroid 0.001234 mm off it" (`ROUND_OFF` of the face's
/// radius of gyration √(J/A)).
fn centroid(d: &DiscMass) -> String {
    let radius_of_gyration_mm = (d.face.polar_mm4 / d.face.area_mm2).sqrt();
    match resolved(d.centroid_offset_mm, radius_of_gyration_mm) {
        Some(offset) => format!("centroid {} mm off it", number(offset)),
        None => "centroid on the centre".to_string(),
    }
}

/// The net unbalance force of `discs` discs on the crank, N, or none when it is round-off of
/// their `discs`·F_c (`ROUND_OFF`): evenly phased discs cancel.
fn net_force_n(u: &Unbalance, discs: usize) -> Option<f64> {
    resolved(u.force_n, discs as f64 * u.disc_force_n)
}

/// What J_in includes, as the design table and the terminal say it.
fn included(m: &MassProperties) -> String {
    let mut parts = vec!["the discs' orbit and turning"];
    if m.output_kgmm2 > 0.0 {
        parts.push("the output");
    }
    let mut left_out = vec!["the crank shaft", "its bearings"];
    match m.rollers_kgmm2 > 0.0 {
        true => parts.push("the rollers' spin"),
        false => left_out.push("the rollers"),
    }
    format!("{}; not {}", listed(&parts, "and"), listed(&left_out, "or"))
}

/// The design table's rows (what, value): one disc's mass properties and the inertia at the
/// input.
pub fn design_rows(spec: &Spec, m: &MassProperties) -> Vec<(&'static str, String)> {
    let d = &m.disc;
    vec![
        (
            "mass properties (each disc)",
            format!(
                "mass {} kg at density ρ {} kg/m³, polar inertia J_c {} kg·m² about its \
                 centre, {}",
                number(d.mass_kg),
                number(units::kg_per_m3(spec.design.density_kg_per_mm3)),
                number(units::kgm2(d.inertia_kgmm2)),
                centroid(d)
            ),
        ),
        (
            "inertia at the input J_in",
            format!(
                "{} kg·m²: {}",
                number(units::kgm2(m.input_inertia_kgmm2)),
                included(m)
            ),
        ),
    ]
}

/// The terminal's lines after the headline results: the mass and inertia at the input, and
/// each scene's unbalance at speed.
pub fn headlines(spec: &Spec, m: &MassProperties, unbalance: &[Unbalance]) -> String {
    let mut out = format!(
        "mass: each disc {} kg, J_c {} kg·m²; inertia at the input J_in {} kg·m² ({})\n",
        number(m.disc.mass_kg),
        number(units::kgm2(m.disc.inertia_kgmm2)),
        number(units::kgm2(m.input_inertia_kgmm2)),
        included(m)
    );
    for u in unbalance {
        let force = match net_force_n(u, spec.design.discs) {
            Some(f) => format!("unbalance on the crank {} N", number(f)),
            None => "no unbalance force on the crank (the discs' forces cancel)".to_string(),
        };
        out += &format!(
            "scene `{}` at {} rpm: each disc's centripetal force {} N; {force}, couple {} N·m\n",
            spec.scenes[u.scene].name,
            number(u.input_speed_rpm),
            number(u.disc_force_n),
            number(units::nm(u.moment_nmm))
        );
    }
    out
}

/// The title's addition to the crank-bearing force plot of a scene at speed: "at 3000 rpm,
/// includes m·(e+de)·ω² = 17.58 N".
pub fn bearing_plot_note(u: &Unbalance) -> String {
    format!(
        "at {} rpm, includes m·(e+de)·ω² = {} N",
        number(u.input_speed_rpm),
        number(u.disc_force_n)
    )
}

/// The scene section's note on a scene at speed: the centripetal force in the crank bearing
/// and the unbalance the discs leave on the crank (a duty cycle's at its fastest bin).
pub fn scene_note(spec: &Spec, u: &Unbalance) -> String {
    let fastest = match spec.scenes[u.scene].duty_cycle {
        Some(_) => "the fastest bin's ",
        None => "",
    };
    let mut s = format!(
        "At {fastest}{} rpm each disc's crank bearing also pulls the disc's centre onto its orbit with \
         F_c = m·(e+de)·ω² = {} N (effect inertia): in the bearing's force at every angle, its \
         life and static safety; the contacts are those without it.",
        number(u.input_speed_rpm),
        number(u.disc_force_n)
    );
    if spec.design.discs > 1 {
        let force = match net_force_n(u, spec.design.discs) {
            Some(f) => format!("an unbalance force of {} N", number(f)),
            None => "no unbalance force (their forces cancel)".to_string(),
        };
        s += &format!(
            " The {} discs leave on the crank {force} and a couple of {} N·m.",
            spec.design.discs,
            number(units::nm(u.moment_nmm))
        );
    }
    s
}

/// `check --explain`'s lines on the design's mass: the disc's mass properties and
/// J_in = Σ(m·e² + J_c/nc²) + J_out/i² with its numbers (i = nc, the output turning at ω/nc).
pub fn explain_design(spec: &Spec, m: &MassProperties) -> String {
    let d = &spec.design;
    let kgm2 = |x: f64| number(units::kgm2(x));
    // The orbit is the crank's as built; named e + de only when the crank has a deviation.
    let orbit = match d.deviations.eccentricity_mm == 0.0 {
        true => "e",
        false => "e + de",
    };
    let rollers = match m.rollers_kgmm2 > 0.0 {
        true => format!(
            " + J_r·⟨Σ(Ωᵢ/ω)²⟩ {} (the rollers' spin, J_r {} kg·m² each, rolling on the disc at \
             Ωᵢ = (ω/nc)·(|Cᵢ − I| − Rrp)/Rrp)",
            kgm2(m.rollers_kgmm2),
            kgm2(d.roller_inertia_kgmm2)
        ),
        false => String::new(),
    };
    format!(
        "mass (density ρ {} kg/m³): each disc {} kg from its exact profile less the pin holes \
         and the bore, J_c {} kg·m² about its centre\n  inertia at the input \
         J_in = Σ(m·e² + J_c/nc²) + J_out/i² = {} × ({} + {}) + {}{rollers} = {} kg·m² (m·e² at \
         {orbit} {} mm, nc = i = {}, J_out {} kg·m²); {}\n",
        number(units::kg_per_m3(d.density_kg_per_mm3)),
        number(m.disc.mass_kg),
        kgm2(m.disc.inertia_kgmm2),
        d.discs,
        kgm2(m.disc.orbit_inertia_kgmm2(d.built_eccentricity_mm())),
        kgm2(m.disc.turning_inertia_kgmm2(d.teeth)),
        kgm2(m.output_kgmm2),
        kgm2(m.input_inertia_kgmm2),
        number(d.built_eccentricity_mm()),
        d.teeth,
        kgm2(d.output_inertia_kgmm2),
        included(m)
    )
}

/// `check --explain`'s lines on `scene` computing `inertia`: F_c = m·(e+de)·ω² with its
/// numbers for `disc` at the scene's speed (each duty bin at its own), where it enters, and the
/// discs' `unbalance` on the crank (`engine::mass_properties::unbalances`, the scene's).
pub fn explain_scene(
    spec: &Spec,
    scene: &Scene,
    disc: &DiscMass,
    unbalance: Option<&Unbalance>,
) -> String {
    let d = &spec.design;
    let e = d.built_eccentricity_mm();
    let bins = scene.duty_cycle.iter().flatten().map(|b| b.input_speed_rpm);
    let forces: Vec<String> = (scene.input_speed_rpm.into_iter().chain(bins))
        .map(|rpm| {
            let w = units::rad_per_s(rpm);
            format!(
                "{} kg × {} m × ({} rad/s)² = {} N at {} rpm",
                number(disc.mass_kg),
                number(units::m_from_mm(e)),
                number(w),
                number(disc.centripetal_force_n(e, w)),
                number(rpm)
            )
        })
        .collect();
    let mut out = format!(
        "  note    inertia: each disc's centripetal force F_c = m·(e+de)·ω² = {}, pulled by \
         its crank bearing toward the crank (−e_φ): in the crank bearing's force at every \
         angle, its life and (with strength) its static safety; the contacts, lags and TE are \
         those without it\n",
        forces.join("; ")
    );
    if let (true, Some(u)) = (d.discs > 1, unbalance) {
        let force = match net_force_n(u, d.discs) {
            Some(f) => format!("a force of {} N", number(f)),
            None => "no force (their forces cancel)".to_string(),
        };
        out += &format!(
            "  note    unbalance at {} rpm: the {} discs leave on the crank {force} and a couple \
             of {} N·m about their mean mid-plane\n",
            number(u.input_speed_rpm),
            d.discs,
            number(units::nm(u.moment_nmm))
        );
    }
    out
}
