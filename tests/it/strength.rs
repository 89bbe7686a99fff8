//! The `strength` effect (issue 41): the output pins' bending and shear stresses against the
//! beam's closed forms written out here (cantilever, propped cantilever, two discs as vectors),
//! the S–N law with hand-worked numbers, the passes per crank turn counted over nc·np crank
//! turns of a simulation, the static safety, and bad values refused at their key.

use crate::common::{scene_item, PaperSpec};
use cycloid::contact::fatigue;
use cycloid::model::results::UNBOUNDED_LIFE_H;
use cycloid::model::strength::ContactFatigue;
use cycloid::spec::Spec;
use std::f64::consts::{PI, TAU};

/// The paper's pin: d = 6 mm; 6 pins; nc = 9, np = 10.
const PIN_DIAMETER_MM: f64 = 6.0;
const PINS: usize = 6;
const TEETH: usize = 9;

/// The paper's design with `support` (a YAML flow mapping) under its pins, `discs` discs,
/// `material` lines added to the disc's material, `reducer` lines added to the reducer, and
/// `scenes`.
fn spec_text(discs: usize, support: Option<&str>, extra: (&str, &str), scenes: &str) -> String {
    let (material, reducer) = extra;
    let mut s = PaperSpec::new();
    if let Some(support) = support {
        s = s.edit(
            "\n  material:",
            &format!("\n    support: {support}\n  material:"),
        );
    }
    s = s.edit(
        "    poisson_ratio: 0.3           # nu\n",
        &format!("    poisson_ratio: 0.3           # nu\n{material}{reducer}"),
    );
    s = s.edit(
        "  output_pins:\n",
        &format!("  discs: {discs}\n  output_pins:\n"),
    );
    s.scenes(scenes).text().to_string()
}

fn parse(text: &str) -> Spec {
    cycloid::spec::parse("strength.yaml", text).unwrap()
}

use crate::common::run_first_scene as run;

/// A first-order scene of 10 N·m over 0°–108° (the loaded period) in `steps` angles, with the
/// strength effect (which brings the rollers, the pins and the bearing) and `more` lines.
fn loaded(steps: usize, more: &str) -> String {
    let crank = format!("{{ from_deg: 0.0, to_deg: 108.0, steps: {steps} }}");
    scene_item("rated", 10.0, &crank, "strength")
        + "    geometry: first_order\n    contact_law: paper_linear\n"
        + more
}

/// 32·M/(π·d³), the outer-fibre stress of a round pin, MPa (written out, not the crate's).
fn sigma(moment_nmm: f64) -> f64 {
    32.0 * moment_nmm / (PI * PIN_DIAMETER_MM.powi(3))
}

/// One disc on a pin 14 mm long, its mid-plane at a = 10 mm. Cantilever: the moment is
/// largest at the clamp, F·a, and the shear is F all along the loaded part: σ = 32·F·a/(π·d³),
/// τ = 4F/(3A). Propped (`both_ends`), by the beam's equation (Roark, Table 8.1 case 1c): the
/// prop carries R = F·a²(3L − a)/(2L³); the clamp's moment is F·a(L − a)(2L − a)/(2L²) =
/// 1.837·F mm, the moment under the load R·(L − a) = 2.332·F mm, the larger; the shear is the
/// larger of F − R and R. Each pin's force is the run's own. Tolerance 1e-12 relative: both
/// sides are a few roundings of the same products.
#[test]
fn one_disc_pin_stress_is_the_beams_closed_form_for_both_supports() {
    let (l, a): (f64, f64) = (14.0, 10.0);
    for kind in ["cantilever", "both_ends"] {
        let support = format!("{{ kind: {kind}, length_mm: 14.0, disc_positions_mm: [10.0] }}");
        let r = run(&parse(&spec_text(
            1,
            Some(&support),
            ("", ""),
            &loaded(30, ""),
        )));
        let forces = &r.discs[0].loaded.pins.as_ref().unwrap().force_n;
        let stress = r.reducer.pin_stress.as_ref().expect("pin stress computed");
        let r_share = a * a * (3.0 * l - a) / (2.0 * l * l * l);
        let (moment_arm, shear_share) = match kind {
            "cantilever" => (a, 1.0),
            _ => {
                let clamp = a * (l - a) * (2.0 * l - a) / (2.0 * l * l);
                let under = r_share * (l - a);
                assert!(under > clamp, "the load's section governs here");
                (clamp.max(under), (1.0 - r_share).max(r_share))
            }
        };
        let area = PI * PIN_DIAMETER_MM * PIN_DIAMETER_MM / 4.0;
        let mut loaded_pins = 0;
        for (j, pin) in forces.iter().enumerate() {
            for (k, &f) in pin.iter().enumerate() {
                let want = sigma(f * moment_arm);
                let got = stress.bending_stress_mpa[j][k];
                assert!(
                    (got - want).abs() <= 1e-12 * want.max(1.0),
                    "{kind} pin {j} at {k}: {got} vs {want}"
                );
                let tau = 4.0 * f * shear_share / (3.0 * area);
                let got = stress.shear_stress_mpa[j][k];
                assert!(
                    (got - tau).abs() <= 1e-12 * tau.max(1.0),
                    "{kind} shear {j} {k}: {got} vs {tau}"
                );
                loaded_pins += usize::from(f > 0.0);
            }
        }
        assert!(loaded_pins > 0);
    }
}

/// The coupled friction model puts the hole's Coulomb force on each pin beside its normal
/// force (MODEL.md "Friction: the coupled model": the hole slides over its pin along
/// τ = ẑ × e_φ, its friction on the disc is −c_p·F·τ, so on the pin +c_p·F·τ, c_p = μ for fixed
/// pins). Both act at the disc's mid-plane, so the pin bends under their resultant,
/// F·sqrt(1 + μ²) in the first-order geometry, where the normal force lies along e_φ exactly
/// and τ is perpendicular to it. One disc, cantilever at a = 10 mm, μ = 0.3:
/// σ = 32·F·a·sqrt(1.09)/(π·d³) and τ = 4·F·sqrt(1.09)/(3A) with F each pin's recorded normal
/// force (Coulomb's law and Roark Table 8.1 case 1a, written out here). The normal force alone
/// would be 4.4 % low. Tolerance 1e-12 relative: a few roundings of the same products.
#[test]
fn coupled_friction_on_the_pins_bends_them_with_the_normal_force() {
    let support = "{ kind: cantilever, length_mm: 14.0, disc_positions_mm: [10.0] }";
    let friction = "  friction:\n    model: coupled\n    output_pins: { mode: fixed, mu: 0.3 }\n";
    let crank = "{ from_deg: 0.0, to_deg: 108.0, steps: 30 }";
    let scene = scene_item("rated", 10.0, crank, "strength, efficiency")
        + "    geometry: first_order\n    contact_law: paper_linear\n";
    let spec = parse(&spec_text(1, Some(support), ("", friction), &scene));
    let r = run(&spec);
    // --explain says so, with c_p = μ of fixed pins.
    let explained = cycloid::report::explain::explain(&spec, Default::default(), false);
    assert!(
        explained.contains("Coulomb force c_p·F along ẑ × e_φk, c_p = 0.3000"),
        "{explained}"
    );
    let forces = &r.discs[0].loaded.pins.as_ref().unwrap().force_n;
    let stress = r.reducer.pin_stress.as_ref().expect("pin stress computed");
    let resultant = (1.0f64 + 0.3 * 0.3).sqrt();
    let area = PI * PIN_DIAMETER_MM * PIN_DIAMETER_MM / 4.0;
    let mut loaded_pins = 0;
    for (j, pin) in forces.iter().enumerate() {
        for (k, &f) in pin.iter().enumerate() {
            let want = sigma(f * resultant * 10.0);
            let got = stress.bending_stress_mpa[j][k];
            assert!(
                (got - want).abs() <= 1e-12 * want.max(1.0),
                "pin {j} at {k}: {got} vs {want}"
            );
            let tau = 4.0 * f * resultant / (3.0 * area);
            let got = stress.shear_stress_mpa[j][k];
            assert!(
                (got - tau).abs() <= 1e-12 * tau.max(1.0),
                "shear {j} {k}: {got} vs {tau}"
            );
            loaded_pins += usize::from(f > 0.0);
        }
    }
    assert!(loaded_pins > 0);
}

/// Two discs at crank phases 0 and π on a cantilever 20 mm long at 6 and 16 mm: disc k's pin
/// force lies along its own eccentric direction (MODEL.md "Several discs"), so the two discs
/// push a pin they share in opposite directions. Superposed (Roark Table 8.1 case 1a, point
/// loads): M(0) = F0·6 − F1·16, M(6) = −F1·(16 − 6), M(16) = 0; the largest |M| is at one of
/// them. A sum of magnitudes (F0·6 + F1·16) would be wrong wherever both discs load the pin,
/// which the test requires to happen. Tolerance 1e-12 relative: a few roundings.
#[test]
fn two_discs_on_one_pin_superpose_as_vectors() {
    let support = "{ kind: cantilever, length_mm: 20.0, disc_positions_mm: [6.0, 16.0] }";
    let r = run(&parse(&spec_text(
        2,
        Some(support),
        ("", ""),
        &loaded(36, ""),
    )));
    let stress = r
        .reducer
        .pin_stress
        .as_ref()
        .expect("the reducer's pin stress");
    let force =
        |d: usize, j: usize, k: usize| r.discs[d].loaded.pins.as_ref().unwrap().force_n[j][k];
    let mut shared = 0;
    for j in 0..PINS {
        for k in 0..r.crank_rad.len() {
            let (f0, f1) = (force(0, j, k), force(1, j, k));
            let want = sigma((f0 * 6.0 - f1 * 16.0).abs().max(f1 * 10.0));
            let got = stress.bending_stress_mpa[j][k];
            assert!(
                (got - want).abs() <= 1e-12 * want.max(1.0),
                "pin {j} at {k}: {got} vs {want}"
            );
            if f0 > 0.0 && f1 > 0.0 {
                shared += 1;
                assert!(got < sigma(f0 * 6.0 + f1 * 16.0) * (1.0 - 1e-6));
            }
        }
    }
    assert!(shared > 0, "some pin carries both discs");
}

/// Two discs as above in the exact geometry, where a hole no longer pushes its pin along the
/// disc's eccentric direction: the hole's centre H sits off its pin's centre Q by d = H − Q,
/// written here from MODEL.md ("Equilibrium", "Several discs"): H = e·e_φk + rw·e^{iγj},
/// Q = rw·e^{i(γj + βo,k)}, γj = 2πj/M − φ/nc + βk (disc k's holes are bored so that the pins
/// sit centred at its ideal pose, its arms rw·sin(γj − φk)), with disc k's recorded lags;
/// the hole pushes the pin with F·d/|d| (ideally d = e·e_φk). The stress is the beam's sum of
/// these vectors. Along e_φk instead, the sum differs
/// by the output lag's turn rw·βo/e (~1e-4 rad here) wherever both discs load a pin (the
/// test requires one). Tolerance 1e-10 of the larger term's stress: d is formed from lengths
/// of rw = 18 mm to a few ulp, |d| = e = 2 mm, a direction error of ~1e-14 rad on each term.
#[test]
fn two_discs_in_the_exact_geometry_sum_the_recorded_directions() {
    let support = "{ kind: cantilever, length_mm: 20.0, disc_positions_mm: [6.0, 16.0] }";
    let crank = "{ from_deg: 0.0, to_deg: 108.0, steps: 36 }";
    let scene = scene_item("rated", 10.0, crank, "strength") + "    contact_law: paper_linear\n";
    let r = run(&parse(&spec_text(2, Some(support), ("", ""), &scene)));
    let stress = r
        .reducer
        .pin_stress
        .as_ref()
        .expect("the reducer's pin stress");
    let (e, rw, nc) = (2.0, 18.0, TEETH as f64);
    // Disc d's force on pin j at angle k, N, as a vector: along its hole's offset from the pin.
    let load = |d: usize, j: usize, k: usize| {
        let disc = &r.discs[d].loaded;
        let pins = disc.pins.as_ref().unwrap();
        let phi = r.crank_rad[k] + PI * d as f64;
        let lag = disc.rollers.as_ref().unwrap().lag_rad[k];
        let gamma = TAU * j as f64 / PINS as f64 - r.crank_rad[k] / nc + lag;
        let beta_o = pins.output_lag_rad[k];
        let hole = [
            e * phi.cos() + rw * gamma.cos(),
            e * phi.sin() + rw * gamma.sin(),
        ];
        let pin = [rw * (gamma + beta_o).cos(), rw * (gamma + beta_o).sin()];
        let d = [hole[0] - pin[0], hole[1] - pin[1]];
        let f = pins.force_n[j][k] / d[0].hypot(d[1]);
        [f * d[0], f * d[1]]
    };
    let norm = |v: [f64; 2]| v[0].hypot(v[1]);
    let mut shared = 0;
    for j in 0..PINS {
        for k in 0..r.crank_rad.len() {
            let (f0, f1) = (load(0, j, k), load(1, j, k));
            // Cantilever, loads at 6 and 16 mm: M(0) = 6·F0 + 16·F1, M(6) = 10·F1, M(16) = 0.
            let clamp = [6.0 * f0[0] + 16.0 * f1[0], 6.0 * f0[1] + 16.0 * f1[1]];
            let want = sigma(norm(clamp).max(10.0 * norm(f1)));
            let scale = sigma(6.0 * norm(f0) + 16.0 * norm(f1));
            let got = stress.bending_stress_mpa[j][k];
            assert!(
                (got - want).abs() <= 1e-10 * scale.max(1.0),
                "pin {j} at {k}: {got} vs {want}"
            );
            shared += usize::from(norm(f0) > 0.0 && norm(f1) > 0.0);
        }
    }
    assert!(shared > 0, "some pin carries both discs");
}

/// N(p) = cycles·(p_ref/p)^k by hand: the law (1500 MPa, 1e8 cycles, k = 8) at 750 MPa gives
/// 1e8·2⁸ = 2.56e10 cycles; at 1500 rpm a lobe of a disc of nc = 9 is loaded 10/9 times per
/// crank turn, 1e5 times an hour: 2.56e5 h; a roller once per turn, 9e4 times an hour:
/// 284,444.4 h. At or below the endurance pressure, or unloaded, the life is unbounded, written
/// as the largest double (never ∞). 1e-12 relative: one powf and two products.
#[test]
fn the_s_n_law_by_hand() {
    let law = ContactFatigue {
        pressure_mpa: 1500.0,
        cycles: 1e8,
        exponent: 8.0,
        endurance_pressure_mpa: None,
    };
    assert!((fatigue::cycles_to_failure(&law, 750.0) / 2.56e10 - 1.0).abs() <= 1e-12);
    let disc = fatigue::life_h(
        &law,
        750.0,
        fatigue::disc_passes_per_crank_turn(TEETH),
        1500.0,
    );
    assert!((disc / 2.56e5 - 1.0).abs() <= 1e-12, "{disc}");
    let rollers = fatigue::life_h(&law, 750.0, fatigue::ROLLER_PASSES_PER_CRANK_TURN, 1500.0);
    assert!(
        (rollers / (2.56e10 / 9e4) - 1.0).abs() <= 1e-12,
        "{rollers}"
    );
    let endured = ContactFatigue {
        endurance_pressure_mpa: Some(750.0),
        ..law
    };
    assert_eq!(
        fatigue::life_h(&endured, 750.0, 1.0, 1500.0),
        UNBOUNDED_LIFE_H
    );
    assert!(fatigue::life_h(&endured, 751.0, 1.0, 1500.0) < UNBOUNDED_LIFE_H);
    assert_eq!(fatigue::life_h(&law, 0.0, 1.0, 1500.0), UNBOUNDED_LIFE_H);
}

/// The passes per crank turn, counted on a simulation: over nc·np = 90 crank turns (first
/// order, 2° steps) roller 0 carries a force in separate stretches, one per crank turn (the
/// load zone turns once in the housing); the lobe a loaded roller i meets is the tooth space
/// it sits in, in the disc's frame (the disc turned by −φ/nc, the roller at 2πi/np + φ/nc),
/// and lobe 0 is met in np/nc per turn stretches: np² = 100 over the 90 turns.
#[test]
fn the_passes_per_crank_turn_are_counted_on_a_simulation() {
    let turns = TEETH * (TEETH + 1);
    let steps = 180 * turns;
    let crank = format!(
        "{{ from_deg: 0.0, to_deg: {}.0, steps: {steps} }}",
        360 * turns
    );
    let scenes = scene_item("turns", 10.0, &crank, "roller_contact")
        + "    geometry: first_order\n    contact_law: paper_linear\n";
    let r = run(&parse(&spec_text(1, None, ("", ""), &scenes)));
    let forces = &r.discs[0].loaded.rollers.as_ref().unwrap().force_n;
    let np = forces.len();
    let rises = |flags: &[bool]| {
        // Stretches on the circle of the whole sweep (it spans whole turns).
        (0..flags.len())
            .filter(|&k| flags[k] && !flags[(k + flags.len() - 1) % flags.len()])
            .count()
    };
    let roller0: Vec<bool> = forces[0].iter().map(|&f| f > 0.0).collect();
    let per_turn = rises(&roller0) as f64 / turns as f64;
    assert_eq!(per_turn, fatigue::ROLLER_PASSES_PER_CRANK_TURN);
    let lobe0: Vec<bool> = (0..r.crank_rad.len())
        .map(|k| {
            let phi = r.crank_rad[k];
            (0..np).filter(|&i| forces[i][k] > 0.0).any(|i| {
                let alpha = (TAU * i as f64 / np as f64 + phi / TEETH as f64).rem_euclid(TAU);
                ((alpha * TEETH as f64 / TAU).floor() as usize).is_multiple_of(TEETH)
            })
        })
        .collect();
    let per_turn = rises(&lobe0) as f64 / turns as f64;
    assert_eq!(per_turn, fatigue::disc_passes_per_crank_turn(TEETH));
}

/// The scene's lives and static safety against the laws by hand, from the run's own largest
/// pressure and bearing force: life = N(p_max)/(passes·n·60), s0 = C0/max |Fb|; unloaded (0 N·m)
/// every figure is unbounded and written as the largest double, never ∞ or NaN.
#[test]
fn the_scenes_lives_and_static_safety() {
    let material = "    yield_strength_mpa: 1700.0\n    contact_fatigue: { pressure_mpa: 1500.0, cycles: 1.0e8, exponent: 8.0 }\n";
    let reducer =
        "  crank_bearing:\n    dynamic_load_rating_n: 12000.0\n    static_load_rating_n: 9000.0\n";
    let speed = "    input_speed_rpm: 1500.0\n";
    let support = "{ kind: cantilever, length_mm: 14.0, disc_positions_mm: [10.0] }";
    let text = spec_text(1, Some(support), (material, reducer), &loaded(30, speed));
    let r = run(&parse(&text));
    let p = r.discs[0]
        .loaded
        .rollers
        .as_ref()
        .unwrap()
        .pressure_mpa
        .iter()
        .flatten()
        .fold(0.0f64, |m, &x| m.max(x));
    let fb = r.discs[0]
        .loaded
        .bearing
        .as_ref()
        .unwrap()
        .force_n
        .iter()
        .fold(0.0f64, |m, &x| m.max(x));
    let n = 1e8 * (1500.0 / p).powi(8);
    let s = r.discs[0].loaded.strength.unwrap();
    let f = s.fatigue.unwrap();
    let disc = n / (10.0 / 9.0 * 1500.0 * 60.0);
    let rollers = n / (1500.0 * 60.0);
    assert!((f.disc_h.unwrap() / disc - 1.0).abs() <= 1e-12);
    assert!((f.rollers_h.unwrap() / rollers - 1.0).abs() <= 1e-12);
    let q = cycloid::model::quantity::find("min_contact_fatigue_life_h").unwrap();
    let shorter = q.scalar(&r).unwrap();
    assert_eq!(shorter.value, f.disc_h.unwrap());
    let words = cycloid::report::place::text(&shorter.at);
    assert!(words.starts_with("disc"), "{words}");
    let s0 = s.static_safety.unwrap().safety;
    assert!((s0 / (9000.0 / fb) - 1.0).abs() <= 1e-12);
    let q = cycloid::model::quantity::find("pin_bending_safety").unwrap();
    let pins = &r.reducer.pin_stress.as_ref().unwrap().bending_stress_mpa;
    let most = pins.iter().flatten().fold(0.0f64, |m, &x| m.max(x));
    assert!((q.scalar(&r).unwrap().value / (1700.0 / most) - 1.0).abs() <= 1e-12);

    let idle = text.replace("output_torque_nm: 10.0", "output_torque_nm: 0.0");
    let r = run(&parse(&idle));
    let s = r.discs[0].loaded.strength.unwrap();
    let f = s.fatigue.unwrap();
    assert_eq!(f.disc_h, Some(UNBOUNDED_LIFE_H));
    assert_eq!(f.rollers_h, Some(UNBOUNDED_LIFE_H));
    assert_eq!(s.static_safety.unwrap().safety, f64::MAX);
    let q = cycloid::model::quantity::find("pin_bending_safety").unwrap();
    assert_eq!(q.scalar(&r).unwrap().value, f64::MAX);
}

/// Where `key_line` (a line of the text, exactly, trimmed) starts, 1-based, and the column of
/// `token` on it.
fn place(text: &str, key_line: &str, token: &str) -> (usize, usize) {
    let (i, line) = text
        .lines()
        .enumerate()
        .find(|(_, l)| l.trim() == key_line)
        .unwrap_or_else(|| panic!("`{key_line}` in the text"));
    (i + 1, line.find(token).unwrap() + 1)
}

/// A bad-input case: the pin support, the material's lines, the scenes, the line the error
/// points at, the token it points at on that line, and what the message says.
type Case<'a> = (Option<&'a str>, String, String, &'a str, &'a str, &'a str);

/// Bad values are refused at their key with the rule and the value: an exponent ≤ 0 or above
/// 30, a pressure or cycles ≤ 0, a stress limit without a pin support, a safety without a yield
/// strength, a life without a speed, a static safety without C0, a life over part of a period.
#[test]
fn bad_values_are_refused_at_their_key() {
    let support = "{ kind: cantilever, length_mm: 14.0, disc_positions_mm: [10.0] }";
    let law = |body: &str| format!("    contact_fatigue: {{ {body} }}\n");
    let speed = "    input_speed_rpm: 1500.0\n";
    let cases: Vec<Case> = vec![
        (
            Some(support),
            law("pressure_mpa: 1500.0, cycles: 1.0e8, exponent: 0.0"),
            loaded(4, speed),
            "contact_fatigue: { pressure_mpa: 1500.0, cycles: 1.0e8, exponent: 0.0 }",
            "exponent",
            "must be in (0, 30], got 0",
        ),
        (
            Some(support),
            law("pressure_mpa: 1500.0, cycles: 1.0e8, exponent: 31.0"),
            loaded(4, speed),
            "contact_fatigue: { pressure_mpa: 1500.0, cycles: 1.0e8, exponent: 31.0 }",
            "exponent",
            "got 31",
        ),
        (
            Some(support),
            law("pressure_mpa: -1.0, cycles: 1.0e8, exponent: 8.0"),
            loaded(4, speed),
            "contact_fatigue: { pressure_mpa: -1.0, cycles: 1.0e8, exponent: 8.0 }",
            "pressure_mpa",
            "positive",
        ),
        (
            Some(support),
            law("pressure_mpa: 1500.0, cycles: 0.0, exponent: 8.0"),
            loaded(4, speed),
            "contact_fatigue: { pressure_mpa: 1500.0, cycles: 0.0, exponent: 8.0 }",
            "cycles",
            "positive",
        ),
        (
            None,
            String::new(),
            loaded(4, speed) + "limits:\n  max_pin_bending_stress_mpa: 300.0\n",
            "max_pin_bending_stress_mpa: 300.0",
            "max_pin_bending_stress_mpa",
            "output_pins.support",
        ),
        (
            Some(support),
            String::new(),
            loaded(4, speed) + "limits:\n  min_pin_bending_safety: 2.0\n",
            "min_pin_bending_safety: 2.0",
            "min_pin_bending_safety",
            "yield_strength_mpa",
        ),
        (
            Some(support),
            law("pressure_mpa: 1500.0, cycles: 1.0e8, exponent: 8.0"),
            loaded(4, "") + "limits:\n  min_contact_fatigue_life_h: 2000.0\n",
            "- name: rated",
            "name",
            "input_speed_rpm",
        ),
        (
            Some(support),
            String::new(),
            loaded(4, speed) + "limits:\n  min_static_safety: 2.0\n",
            "min_static_safety: 2.0",
            "min_static_safety",
            "static_load_rating_n",
        ),
        (
            Some(support),
            law("pressure_mpa: 1500.0, cycles: 1.0e8, exponent: 8.0"),
            loaded(4, speed).replace("to_deg: 108.0", "to_deg: 36.0")
                + "limits:\n  min_contact_fatigue_life_h: 2000.0\n",
            "crank: { from_deg: 0.0, to_deg: 36.0, steps: 4 }",
            "crank",
            "whole number of loaded periods",
        ),
    ];
    for (support, material, scenes, line, token, message) in cases {
        let text = spec_text(1, support, (&material, ""), &scenes);
        let err = cycloid::spec::parse("strength.yaml", &text)
            .expect_err(line)
            .to_string();
        let (l, c) = place(&text, line, token);
        assert!(
            err.starts_with(&format!("strength.yaml:{l}:{c}: ")) && err.contains(message),
            "{line}: {err} (expected at {l}:{c}, saying `{message}`)"
        );
    }
}

/// Miner over a duty cycle with the flanks apart: +10 N·m and −10 N·m at 1500 rpm for 40 % of
/// the time each, and a standstill under 5 N·m for the rest. Each loaded bin uses up
/// dᵢ = sᵢ·nᵢ·60·c/N(pᵢ) of a part per hour (c = 10/9 on the disc, 1 on a roller; pᵢ the bin's
/// largest pressure, read from its own pressure curves); the two bins load different flanks,
/// so the life is 1/max(d₊, d₋), about twice the 1/(d₊ + d₋) a single flank would give; the
/// standstill adds nothing. Each flank's shares: the loaded bin's 1, the standstill's 0.
/// Tolerance 1e-12 relative: one powf and a few products on each side.
#[test]
fn miner_over_a_duty_cycle_keeps_the_flanks_apart() {
    let material = "    contact_fatigue: { pressure_mpa: 1500.0, cycles: 1.0e8, exponent: 8.0 }\n";
    let scenes = "  - name: duty\n    duty_cycle:\n      \
        - { output_torque_nm: 10.0, input_speed_rpm: 1500.0, time_share: 0.4 }\n      \
        - { output_torque_nm: -10.0, input_speed_rpm: 1500.0, time_share: 0.4 }\n      \
        - { output_torque_nm: 5.0, input_speed_rpm: 0.0, time_share: 0.2 }\n    \
        crank: { from_deg: 0.0, to_deg: 108.0, steps: 108 }\n    \
        geometry: first_order\n    effects: [bearing, strength]\n\
        limits:\n  min_contact_fatigue_life_h: 1.0\n";
    let r = run(&parse(&spec_text(1, None, (material, ""), scenes)));
    let d = r.duty.as_ref().unwrap();
    let p = |j: usize| {
        let rollers = d.bins[j].result.discs[0].loaded.rollers.as_ref().unwrap();
        rollers
            .pressure_mpa
            .iter()
            .flatten()
            .fold(0.0f64, |m, &x| m.max(x))
    };
    let n = |p: f64| 1e8 * (1500.0 / p).powi(8);
    let rate = |j: usize, c: f64| 0.4 * 1500.0 * 60.0 * c / n(p(j));
    let f = &d.contact_fatigue[0];
    for (got, c, shares) in [
        (f.disc_h.unwrap(), 10.0 / 9.0, &f.disc_shares),
        (f.rollers_h.unwrap(), 1.0, &f.rollers_shares),
    ] {
        let (drive, coast) = (rate(0, c), rate(1, c));
        let want = 1.0 / drive.max(coast);
        assert!((got / want - 1.0).abs() <= 1e-12, "{got} vs {want}");
        assert!(got > 1.5 / (drive + coast), "the flanks wear apart");
        assert_eq!(shares, &vec![1.0, 1.0, 0.0]);
    }
    let q = cycloid::model::quantity::find("min_contact_fatigue_life_h").unwrap();
    assert_eq!(q.scalar(&r).unwrap().value, f.disc_h.unwrap());
}

/// A bin of no time turns no revolution and wears nothing, whatever its N(p) (Palmgren–Miner:
/// its damage is sᵢ·nᵢ·60·c/N = 0). Under the law N(p) = 1·(1e-9 MPa/p)^30 any pressure above
/// ~1e-8·10^10.8 MPa gives an N below the smallest double, 0 in f64 (at ~800 MPa here,
/// (1.25e-12)^30 ≈ 1e-356), so the turning bin's damage rate is infinite and its life 0 h, as
/// the scene alone would give (N/(c·n·60) = 0). The zero-time bin at twice the torque must
/// neither hide that (0·c/0 is NaN, which a max over the flanks drops: the life read
/// unbounded) nor make a share NaN (inf/inf: the results JSON then cannot be written). Exact:
/// 0 h, and the shares 1 and 0.
#[test]
fn a_bin_of_no_time_adds_no_damage_even_where_n_underflows() {
    let material = "    contact_fatigue: { pressure_mpa: 1.0e-9, cycles: 1.0, exponent: 30.0 }\n";
    let scenes = "  - name: duty\n    duty_cycle:\n      \
        - { output_torque_nm: 10.0, input_speed_rpm: 1500.0, time_share: 1.0 }\n      \
        - { output_torque_nm: 20.0, input_speed_rpm: 1500.0, time_share: 0.0 }\n    \
        crank: { from_deg: 0.0, to_deg: 108.0, steps: 108 }\n    \
        geometry: first_order\n    effects: [bearing, strength]\n\
        limits:\n  min_contact_fatigue_life_h: 1.0\n";
    let r = run(&parse(&spec_text(1, None, (material, ""), scenes)));
    let f = &r.duty.as_ref().unwrap().contact_fatigue[0];
    for (life, shares) in [
        (f.disc_h.unwrap(), &f.disc_shares),
        (f.rollers_h.unwrap(), &f.rollers_shares),
    ] {
        assert_eq!(life, 0.0, "the turning bin's life alone is 0 h");
        assert_eq!(shares, &vec![1.0, 0.0]);
    }
}

/// The shipped `specs/reducer-strength.yaml` with its static safety bound raised to 8 (its s0
/// is ~7.2), so that one strength check fails.
pub(crate) fn strength_failing() -> String {
    let text = include_str!("../../specs/reducer-strength.yaml");
    let from = "min_static_safety: 2.0 ";
    assert_eq!(text.matches(from).count(), 1);
    text.replace(from, "min_static_safety: 8.0 ")
}

/// The largest entry of a `[row][crank]` array of the results JSON: (value, row, crank).
fn json_max_entry(rows: &serde_json::Value) -> (f64, usize, usize) {
    let mut best = (f64::NEG_INFINITY, 0, 0);
    for (i, row) in rows.as_array().unwrap().iter().enumerate() {
        for (k, x) in row.as_array().unwrap().iter().enumerate() {
            let x = x.as_f64().unwrap();
            if x > best.0 {
                best = (x, i, k);
            }
        }
    }
    best
}

/// The strength figures of `strength_failing`'s scene and where each is governed, as the
/// reports must say them, recomputed from the forces and pressures of its results JSON (not its
/// strength figures): a cantilever pin of d = 6 mm loaded at a = 10 mm, σ = 32·F·a/(π·d³);
/// yield 1400 MPa; ISO 6336-2's N(p) = 5e7·(1500/p)^13.2 over np/nc = 10/9 passes per turn at
/// 1500 rpm (the disc's, the shorter); s0 = 14000 N / max |Fb|. `(key, value, where)`.
pub(crate) fn strength_places(results: &serde_json::Value) -> Vec<(&'static str, String, String)> {
    use cycloid::numeric::number;
    let scene = &results["scenes"][0];
    let crank = |k: usize| scene["crank_deg"][k].as_f64().unwrap();
    let (force, pin, k) = json_max_entry(&scene["pin_force_n"]);
    let sigma = 32.0 * force * 10.0 / (PI * 6f64.powi(3));
    let pin_at = format!("pin {pin} at crank {:.2}°", crank(k));
    let (p, roller, kp) = json_max_entry(&scene["contact_pressure_mpa"]);
    let life = 5e7 * (1500.0 / p).powf(13.2) / (10.0 / 9.0 * 1500.0 * 60.0);
    let bearing = serde_json::json!([scene["bearing_force_n"].clone()]);
    let (fb, _, kb) = json_max_entry(&bearing);
    vec![
        (
            "max_pin_bending_stress_mpa",
            format!("{} MPa", number(sigma)),
            pin_at.clone(),
        ),
        ("min_pin_bending_safety", number(1400.0 / sigma), pin_at),
        (
            "min_contact_fatigue_life_h",
            format!("{} h", number(life)),
            format!(
                "disc at {} MPa, roller {roller} at crank {:.2}°",
                number(p),
                crank(kp)
            ),
        ),
        (
            "min_static_safety",
            number(14000.0 / fb),
            format!("C0 / {} N at crank {:.2}°", number(fb), crank(kb)),
        ),
    ]
}

/// The terminal's check table and headlines and the design review's check table give each
/// strength figure with its governing part and place (`strength_places`, recomputed from the
/// results JSON's forces and pressures).
#[test]
fn the_headlines_and_the_check_tables_name_the_governing_part_and_place() {
    let dir = crate::common::Scratch::new("strength-places");
    dir.write("spec.yaml", strength_failing());
    let out = crate::common::cycloid(
        &dir.path,
        &[
            "check",
            "spec.yaml",
            "--json",
            "r.json",
            "--report",
            "review",
        ],
    );
    assert_eq!(out.code, Some(1), "{}{}", out.stdout, out.stderr);
    let results: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let review = dir.read("review/index.html");
    let labels = [
        "max pin bending stress",
        "pin bending safety (yield / stress)",
        "contact fatigue life (shorter of disc and rollers)",
        "crank-bearing static safety s0",
    ];
    for ((key, value, at), label) in strength_places(&results).into_iter().zip(labels) {
        let check = (out.stdout.lines())
            .find(|l| l.starts_with(&format!("rated/{key} ")))
            .unwrap_or_else(|| panic!("no check {key}:\n{}", out.stdout));
        let words: Vec<&str> = check.split_whitespace().collect();
        assert!(check.ends_with(&format!("  {at}")), "{check}\n{at}");
        assert_eq!(words[1], value.split(' ').next().unwrap(), "{check}");
        let verdict = if key == "min_static_safety" {
            "FAIL"
        } else {
            "pass"
        };
        assert!(words.contains(&verdict), "{check}");
        let headline = (out.stdout.lines())
            .find(|l| l.starts_with(&format!("  {label} ")))
            .unwrap_or_else(|| panic!("no headline {label}:\n{}", out.stdout));
        assert!(
            headline.ends_with(&format!("{value}  {at}")),
            "{headline}\n{value}  {at}"
        );
        let cell = format!("<td><code>rated/{key}</code></td>");
        let row = review
            .split(cell.as_str())
            .nth(1)
            .unwrap_or_else(|| panic!("{key}"));
        let row = row.split("</tr>").next().unwrap();
        assert!(row.contains(&format!("<td>{at}</td>")), "{key}: {row}");
    }
    // The static safety's C0 is in the review's design table beside the bearing's C, as the
    // spec gives it (read off the spec's text, not the code's figures).
    let spec = strength_failing();
    let c0 = (spec.lines())
        .find_map(|l| l.trim().strip_prefix("static_load_rating_n:"))
        .map(|v| v.split('#').next().unwrap().trim().parse::<f64>().unwrap())
        .expect("the spec gives C0");
    let row = (review.split("crank bearing (each disc)").nth(1))
        .and_then(|r| r.split("</tr>").next())
        .expect("the design table's bearing row");
    assert!(row.contains(&format!(", C0 {c0} N")), "{row}");
}

/// `cycloid tolerance` judges the strength limits on every sample: each sample's recorded
/// figures are those `check` finds on the sample written back (`--write-sample`), its static
/// safety C0 over the largest bearing force of that check's curves, and the failures
/// counted are the samples whose figures miss a limit.
#[test]
fn a_tolerance_study_judges_the_strength_limits_per_sample() {
    // The loaded period of parts as drawn is 3240° of crank (nine turns: the drawn pins and
    // holes break the pin period); 2° steps keep the study short.
    let mut text = include_str!("../../specs/reducer-strength.yaml")
        .replace("to_deg: 108.0, steps: 1080", "to_deg: 3240.0, steps: 1620");
    text += "tolerances:\n  scene: rated\n  distribution: normal\n  eccentricity_mm: 0.003\n  \
             roller_radial_mm: 0.003\n  pin_radial_mm: 0.003\n  hole_radial_mm: 0.003\n  \
             samples: 3\n  seed: 1\n  max_failure_rate: 0.0027\n";
    let dir = crate::common::Scratch::new("strength-tolerance");
    dir.write("t.yaml", &text);
    let run = |args: &[&str]| crate::common::cycloid(&dir.path, args);
    let study = run(&[
        "tolerance",
        "t.yaml",
        "--samples-csv",
        "s.csv",
        "--json",
        "t.json",
    ]);
    assert!(study.code() <= 1, "{study:?}");
    let csv = dir.read("s.csv");
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    // (limit, its quantity's column, bound, an upper bound)
    let limits = [
        (
            "max_pin_bending_stress_mpa",
            "max_pin_bending_stress_mpa",
            600.0,
            true,
        ),
        ("min_pin_bending_safety", "pin_bending_safety", 2.0, false),
        (
            "min_contact_fatigue_life_h",
            "min_contact_fatigue_life_h",
            2000.0,
            false,
        ),
        ("min_static_safety", "static_safety", 2.0, false),
    ];
    let mut failures = 0;
    for k in 0..3 {
        let row: Vec<f64> = (csv.lines().nth(k + 1).unwrap().split(','))
            .map(|x| x.parse().unwrap_or(f64::NAN))
            .collect();
        let (_, doc) = crate::common::replayed_sample(&dir.path, "t.yaml", k);
        let checked = |key: &str| {
            let checks = doc["checks"].as_array().unwrap();
            let c = checks
                .iter()
                .find(|c| c["id"] == format!("rated/{key}"))
                .unwrap();
            c["value"].as_f64().unwrap()
        };
        let mut fails = false;
        for (key, column, bound, max) in limits {
            let recorded = row[header.iter().position(|h| *h == column).unwrap()];
            // 1e-12 relative: the life has been seen one ulp apart between the study and the
            // replayed check (a ulp of the pressure is 13.2 ulps of the life); the others
            // agree to the bit.
            let replayed = checked(key);
            let close = (recorded / replayed - 1.0).abs() < 1e-12;
            assert!(close, "sample {k} {key}: {recorded} against {replayed}");
            fails |= if max {
                recorded > bound
            } else {
                recorded < bound
            };
        }
        failures += usize::from(fails);
        let fb = doc["scenes"][0]["bearing_force_n"]
            .as_array()
            .unwrap()
            .iter();
        let fb = fb.map(|x| x.as_f64().unwrap()).fold(0.0, f64::max);
        // 1e-12 relative: one division, against the check's own.
        let s0 = checked("min_static_safety");
        assert!(
            (s0 / (14000.0 / fb) - 1.0).abs() < 1e-12,
            "sample {k}: {s0}"
        );
    }
    let study: serde_json::Value = serde_json::from_str(&dir.read("t.json")).unwrap();
    assert_eq!(study["failures"].as_u64(), Some(failures as u64));
}
