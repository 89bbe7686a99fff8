//! Output pins that bend (issue 29, `reducer.output_pins.support`) and the structure's
//! compliance (`reducer.structure_compliance_arcmin_per_knm`): the pin's bending in series with
//! its contact against closed forms computed here (cantilever a³/(3EI), superposition of point
//! loads on a cantilever for two discs), the torsional rigidity against the series formula,
//! the structure's c·T, and bad values refused at their key.

use crate::common::{scene_item, PaperSpec};
use cycloid::contact::law::{johnson_approach_mm, LineContact};
use cycloid::model::results::SceneResult;
use cycloid::spec::Spec;
use std::f64::consts::{PI, TAU};

/// The paper's design (Table 1): E 206 GPa, ν 0.3 for every body, L = B = 8 mm, 6 pins of
/// radius 3 mm on rw = 18 mm, nc = 9.
const E_MPA: f64 = 206_000.0;
const NU: f64 = 0.3;
const FACE_MM: f64 = 8.0;
const RW_MM: f64 = 18.0;
const PIN_RADIUS_MM: f64 = 3.0;
const PINS: usize = 6;
const TEETH: f64 = 9.0;

/// The pin contact's linear stiffness (paper Eq. 9), (π/4)·E*·L, E* = E/(2(1 − ν²)) for two
/// bodies of one steel, N/mm.
fn contact_stiffness() -> f64 {
    0.25 * PI * E_MPA / (2.0 * (1.0 - NU * NU)) * FACE_MM
}

/// EI of the paper's pin, I = π·d⁴/64 with d = 6 mm, N·mm².
fn bending_stiffness() -> f64 {
    E_MPA * PI * (2.0 * PIN_RADIUS_MM).powi(4) / 64.0
}

/// A cantilever clamped at z = 0: deflection at z = a per unit force at z = b (Gere, Table
/// G-1 case 5, written out here from the beam's equation, not read from the crate):
/// a²(3b − a)/(6EI) for a ≤ b, b²(3a − b)/(6EI) beyond the load.
fn cantilever(a: f64, b: f64) -> f64 {
    let ei = bending_stiffness();
    if a <= b {
        a * a * (3.0 * b - a) / (6.0 * ei)
    } else {
        b * b * (3.0 * a - b) / (6.0 * ei)
    }
}

/// The paper's design with `support` (YAML flow mapping, or none) and `extra` reducer keys,
/// and `scenes`.
fn spec(discs: usize, support: Option<&str>, extra: &str, scenes: &str) -> Spec {
    let mut s = PaperSpec::new();
    if let Some(support) = support {
        s = s.edit(
            "\n  material:",
            &format!("\n    support: {support}\n  material:"),
        );
    }
    let mut head = format!("  discs: {discs}\n");
    head += extra;
    s = s.edit("  output_pins:\n", &format!("{head}  output_pins:\n"));
    s.scenes(scenes).parse("pins.yaml")
}

use crate::common::run_first_scene as run;

/// A loaded scene of 10 N·m over `steps` angles of 0°–108° with `effects` and `law`, first-
/// order geometry (the pin gaps −βo·a_j of MODEL.md "Equilibrium", exact in it).
fn loaded(law: &str, effects: &str, steps: usize) -> String {
    let crank = format!("{{ from_deg: 0.0, to_deg: 108.0, steps: {steps} }}");
    scene_item("rated", 10.0, &crank, effects)
        + &format!("    geometry: first_order\n    contact_law: {law}\n")
}

/// Ideal first-order arm of pin j of disc k (MODEL.md "Several discs"):
/// rw·sin(2πj/M − φ/nc + βk − φk), φk = φ + 2πk/N.
fn arm(j: usize, phi: f64, k: usize, discs: usize, beta: f64) -> f64 {
    let phi_k = phi + TAU * k as f64 / discs as f64;
    RW_MM * (TAU * j as f64 / PINS as f64 - phi / TEETH + beta - phi_k).sin()
}

/// One disc, the paper's linear law, a cantilever pin with the disc 10 mm from the flange: the
/// output lag is βo = T/(k_eff·Σ a²) over the loaded pins (a > 0), with the series stiffness
/// k_eff = 1/(1/k + a³/(3EI)) (MODEL.md "Equilibrium": F_j = k_eff·βo·a_j with ideal holes),
/// at every angle. The arms are the ideal ones at the solved roller lag β (read from the
/// results, as the pins' arms depend on it). Tolerance 1e-9 relative: the pin balance is
/// solved to ~1e-11 of the torque, the arms are sums of a few doubles.
#[test]
fn one_disc_output_lag_is_the_torque_over_the_series_stiffness() {
    let a = 10.0;
    let s = spec(
        1,
        Some("{ kind: cantilever, length_mm: 14.0, disc_positions_mm: [10.0] }"),
        "",
        &loaded("paper_linear", "roller_contact, output_pins", 30),
    );
    let r = run(&s);
    let k_eff = 1.0 / (1.0 / contact_stiffness() + a * a * a / (3.0 * bending_stiffness()));
    let beta = &r.discs[0].loaded.rollers.as_ref().unwrap().lag_rad;
    let pins = r.discs[0].loaded.pins.as_ref().unwrap();
    let t = 10_000.0;
    for (i, &phi) in r.crank_rad.iter().enumerate() {
        let sum: f64 = (0..PINS)
            .map(|j| arm(j, phi, 0, 1, beta[i]))
            .filter(|a| *a > 0.0)
            .map(|a| a * a)
            .sum();
        let expected = t / (k_eff * sum);
        let got = pins.output_lag_rad[i];
        assert!(
            (got - expected).abs() <= 1e-9 * expected,
            "crank {phi}: βo {got} vs T/(k_eff Σa²) {expected}"
        );
    }
}

/// Johnson's law in series with the cantilever: every loaded pin's closing βo·a_j is shared
/// by the contact's approach (Johnson's formula, evaluated by the crate's own function, which
/// `tests/it/contact.rs` checks against the book) and the pin's bending F·a³/(3EI). 1e-9
/// relative: the series force is solved to ~1e-14 in ln F, the balance to ~1e-11.
#[test]
fn with_johnsons_law_the_closing_is_the_contacts_approach_plus_the_bending() {
    let a = 10.0;
    let s = spec(
        1,
        Some("{ kind: cantilever, length_mm: 14.0, disc_positions_mm: [10.0] }"),
        "",
        &loaded("hertz_nonlinear", "roller_contact, output_pins", 12),
    );
    let r = run(&s);
    let c = a * a * a / (3.0 * bending_stiffness());
    let hole = PIN_RADIUS_MM + 2.0;
    let contact = LineContact {
        contact_modulus_mpa: E_MPA / (2.0 * (1.0 - NU * NU)),
        compliance_per_mpa: [(1.0 - NU * NU) / E_MPA; 2],
        length_mm: FACE_MM,
        radii_mm: [hole, PIN_RADIUS_MM],
        effective_radius_mm: 1.0 / (1.0 / PIN_RADIUS_MM - 1.0 / hole),
    };
    let beta = &r.discs[0].loaded.rollers.as_ref().unwrap().lag_rad;
    let pins = r.discs[0].loaded.pins.as_ref().unwrap();
    let mut loaded = 0;
    for (i, &phi) in r.crank_rad.iter().enumerate() {
        for (j, f) in pins.force_n.iter().enumerate() {
            let closing = pins.output_lag_rad[i] * arm(j, phi, 0, 1, beta[i]);
            if f[i] == 0.0 {
                assert!(
                    closing <= 1e-12,
                    "pin {j} closed by {closing} without force"
                );
                continue;
            }
            loaded += 1;
            let shared = johnson_approach_mm(&contact, f[i]).0 + c * f[i];
            assert!(
                (shared - closing).abs() <= 1e-9 * closing,
                "crank {phi}, pin {j}: approach + bending {shared} vs closing {closing}"
            );
        }
    }
    assert!(loaded >= r.crank_rad.len(), "pins carried load");
}

/// Two discs on one cantilever pin (mid-planes 6 and 16 mm from the flange, the pin 20 mm
/// long): at every angle and every pin, each disc's contact closes by what is left of its
/// rigid closing βo,k·a_kj (βo,k its output lag) after the pin's deflection at its plane, the superposition of
/// the two discs' point loads on a cantilever (Gere, computed here):
///   F_kj/k + Σ_m c(a_k, a_m)·F_mj·(û_k·û_m) = βo,k·a_kj for a loaded pin,
///   ≤ for a pin without force,
/// with û_k = −e_φk the first-order pin direction of disc k (opposite for two discs). With
/// these positions the far disc's plane deflects by 2.7 times more per unit load at the near
/// disc than the near disc's own series compliance, so pins carry both discs and a solve that
/// ignores the coupling fails the equation. The shares add up to T through the pins:
/// Σ_k Σ_j F_kj·a_kj = T. Tolerances: 1e-8 of the angle's largest closing (the fixed point
/// stops at 1e-9 of the largest coupling gap; the balances at ~1e-11), 1e-8 of T.
#[test]
fn two_discs_on_one_pin_deflect_it_as_superposed_point_loads() {
    let pos = [6.0, 16.0];
    let s = spec(
        2,
        Some("{ kind: cantilever, length_mm: 20.0, disc_positions_mm: [6.0, 16.0] }"),
        "",
        &loaded("paper_linear", "roller_contact, output_pins", 36),
    );
    let r = run(&s);
    let k = contact_stiffness();
    let mut shared_pins = 0;
    for (i, &phi) in r.crank_rad.iter().enumerate() {
        let mut moment = 0.0;
        // The fixed point stops within 1e-9 of its largest coupling gap, of the order of the
        // largest closing at the angle: every pin's equation holds to 1e-8 of that.
        let scale = (0..PINS)
            .flat_map(|j| (0..2).map(move |d| (j, d)))
            .map(|(j, d)| {
                let p = r.discs[d].loaded.pins.as_ref().unwrap();
                let b = r.discs[d].loaded.rollers.as_ref().unwrap().lag_rad[i];
                (p.output_lag_rad[i] * arm(j, phi, d, 2, b)).abs()
            })
            .fold(0.0, f64::max);
        for j in 0..PINS {
            let force = |d: usize| r.discs[d].loaded.pins.as_ref().unwrap().force_n[j][i];
            let beta = |d: usize| r.discs[d].loaded.rollers.as_ref().unwrap().lag_rad[i];
            let lag = |d: usize| r.discs[d].loaded.pins.as_ref().unwrap().output_lag_rad[i];
            if force(0) > 0.0 && force(1) > 0.0 {
                shared_pins += 1;
            }
            for d in 0..2 {
                let a_dj = arm(j, phi, d, 2, beta(d));
                let closing = lag(d) * a_dj;
                // û_d·û_m = cos(φd − φm): 1 for itself, −1 for the other disc.
                let bending: f64 = (0..2)
                    .map(|m| {
                        let dot = if m == d { 1.0 } else { -1.0 };
                        cantilever(pos[d], pos[m]) * force(m) * dot
                    })
                    .sum();
                let lhs = force(d) / k + bending;
                if force(d) > 0.0 {
                    assert!(
                        (lhs - closing).abs() <= 1e-8 * scale,
                        "crank {phi}, disc {d}, pin {j}: contact + bending {lhs} vs closing {closing}"
                    );
                } else {
                    assert!(
                        bending >= closing - 1e-8 * scale,
                        "crank {phi}, disc {d}, pin {j}: open pin closed: {bending} < {closing}"
                    );
                }
                moment += force(d) * a_dj;
            }
        }
        assert!(
            (moment - 10_000.0).abs() <= 1e-8 * 10_000.0,
            "crank {phi}: Σ F·a {moment} vs T"
        );
    }
    assert!(shared_pins > 0, "some pin carries both discs");
}

/// A torsion scene (one disc, the paper's linear law, first-order geometry) of `effects`.
fn torsion(support: Option<&str>, effects: &str, extra: &str) -> SceneResult {
    let item = format!(
        "  - name: torsion\n    torque_sweep: {{ rated_nm: 20.0, steps: 4 }}\n    \
         crank: {{ from_deg: 0.0, to_deg: 36.0, steps: 3 }}\n    effects: [{effects}]\n    \
         geometry: first_order\n"
    );
    run(&spec(1, support, extra, &item))
}

/// Torsional rigidity with the pins bending, against the series formula. With a rigid crank
/// bearing the rollers balance T alone, so the lag β(T) is the same with or without pins and
/// the arms with it; the pins add βo = T/(k·Σa²), and bending multiplies it by
/// k/k_eff = 1 + k·a³/(3EI) exactly. Three runs (rollers alone: γ = β; rigid pins; bending
/// pins) give, at every torque, γ_bent − γ_rollers = (γ_rigid − γ_rollers)·k/k_eff, hence the
/// rigidities 1/K_bent = 1/K_rollers + (1/K_rigid − 1/K_rollers)·k/k_eff, and K_bent < K_rigid.
/// 1e-8 relative: each γ is solved to ~1e-11, and the pins' part is a tenth of γ.
#[test]
fn the_rigidity_falls_to_the_series_formula_when_the_pins_bend() {
    let a = 10.0;
    let support = "{ kind: cantilever, length_mm: 14.0, disc_positions_mm: [10.0] }";
    let rollers = torsion(None, "roller_contact", "");
    let rigid = torsion(None, "roller_contact, output_pins", "");
    let bent = torsion(Some(support), "roller_contact, output_pins", "");
    let ratio = 1.0 + contact_stiffness() * a * a * a / (3.0 * bending_stiffness());
    let t = |r: &SceneResult| r.reducer.torsion.clone().unwrap();
    let (tr, tg, tb) = (t(&rollers), t(&rigid), t(&bent));
    for k in 0..tr.figures.len() {
        for m in 0..tr.torque_nmm.len() {
            let (g0, g1, g2) = (
                tr.torsion_rad[k][m],
                tg.torsion_rad[k][m],
                tb.torsion_rad[k][m],
            );
            let expected = g0 + (g1 - g0) * ratio;
            assert!(
                (g2 - expected).abs() <= 1e-8 * expected.abs(),
                "angle {k}, torque {}: γ {g2} vs series {expected}",
                tr.torque_nmm[m]
            );
        }
        let (k0, k1, k2) = (
            tr.figures[k].rigidity(),
            tg.figures[k].rigidity(),
            tb.figures[k].rigidity(),
        );
        let series = 1.0 / (1.0 / k0 + (1.0 / k1 - 1.0 / k0) * ratio);
        assert!(k2 < k1, "rigidity falls: {k2} vs {k1}");
        assert!(
            (k2 - series).abs() <= 1e-8 * series,
            "angle {k}: rigidity {k2} vs series formula {series}"
        );
    }
}

/// The structure's compliance c (0.75 arcmin per kN·m, converted here: × π/10800 rad/arcmin
/// ÷ 10⁶ N·mm per kN·m) adds c·T to every point of the torsion curve, and 1/K' = 1/K + c to
/// the rigidity. Tolerance: the sum γ + c·T rounds to an ulp of γ (4ε·|γ|); the rigidity's
/// reciprocal to 1e-12 (a quotient of such sums).
#[test]
fn the_structure_adds_c_times_t_to_the_torsion_angle() {
    let without = torsion(None, "bearing", "");
    let with = torsion(
        None,
        "bearing",
        "  structure_compliance_arcmin_per_knm: 0.75\n",
    );
    let c = 0.75 * (PI / 10_800.0) / 1e6;
    let (a, b) = (
        without.reducer.torsion.unwrap(),
        with.reducer.torsion.unwrap(),
    );
    let (rated, steps) = (20_000.0, 4);
    for k in 0..a.figures.len() {
        for (m, &t) in a.torque_nmm.iter().enumerate() {
            // T = 0 on the loop is solved at ∓1e-6·rated (the rising branch from below,
            // `engine::torsion::ZERO_SIDE`): the torque the structure then carries.
            let t = match (t, m <= 2 * steps) {
                (0.0, true) => -1e-6 * rated,
                (0.0, false) => 1e-6 * rated,
                _ => t,
            };
            let (g, h) = (a.torsion_rad[k][m], b.torsion_rad[k][m]);
            let expected = g + c * t;
            assert!(
                (h - expected).abs() <= 4.0 * f64::EPSILON * (g.abs() + (c * t).abs()),
                "angle {k}, T {t}: {h} vs γ + c·T {expected}"
            );
        }
        let (k0, k1) = (a.figures[k].rigidity(), b.figures[k].rigidity());
        let expected = 1.0 / (1.0 / k0 + c);
        assert!(
            (k1 - expected).abs() <= 1e-12 * expected,
            "angle {k}: rigidity {k1} vs 1/(1/K + c) {expected}"
        );
    }
    assert!(b.compliances.structure_rad_per_nmm == c);
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

/// Bad values of the new keys are refused with the key's file:line:column and a message, never
/// accepted: a length ≤ 0, a position outside (0, L], a count of positions other than the
/// discs', two discs closer than the face width, a negative structure compliance, an unknown
/// support kind.
#[test]
fn bad_values_are_refused_at_their_key() {
    let scenes = &loaded("paper_linear", "roller_contact, output_pins", 4);
    let cases: [(usize, &str, &str, &str, &str); 6] = [
        (
            1,
            "support:\n      kind: cantilever\n      length_mm: -2.0\n      disc_positions_mm: [1.0]",
            "length_mm: -2.0",
            "length_mm",
            "positive",
        ),
        (
            1,
            "support:\n      kind: cantilever\n      length_mm: 10.0\n      disc_positions_mm: [12.0]",
            "disc_positions_mm: [12.0]",
            "12.0",
            "outside the pin",
        ),
        (
            2,
            "support:\n      kind: both_ends\n      length_mm: 30.0\n      disc_positions_mm: [10.0]",
            "disc_positions_mm: [10.0]",
            "disc_positions_mm",
            "1 position(s) for 2 disc(s)",
        ),
        (
            1,
            "support:\n      kind: cantilever\n      length_mm: 10.0\n      disc_positions_mm: [0.0]",
            "disc_positions_mm: [0.0]",
            "0.0",
            "outside the pin",
        ),
        (
            2,
            "support:\n      kind: cantilever\n      length_mm: 30.0\n      disc_positions_mm: [10.0, 14.0]",
            "disc_positions_mm: [10.0, 14.0]",
            "14.0",
            "overlap",
        ),
        (
            1,
            "support:\n      kind: cantilevered\n      length_mm: 10.0\n      disc_positions_mm: [5.0]",
            "kind: cantilevered",
            "kind",
            "cantilever",
        ),
    ];
    for (discs, support, line, token, message) in cases {
        let text = PaperSpec::new()
            .edit("\n  material:", &format!("\n    {support}\n  material:"))
            .edit(
                "  output_pins:\n",
                &format!("  discs: {discs}\n  output_pins:\n"),
            )
            .scenes(scenes);
        let err = cycloid::spec::parse("pins.yaml", text.text())
            .expect_err(support)
            .to_string();
        let (l, c) = place(text.text(), line, token);
        assert!(
            err.starts_with(&format!("pins.yaml:{l}:{c}: ")) && err.contains(message),
            "{support}: {err} (expected at {l}:{c}, saying `{message}`)"
        );
    }
    let text = PaperSpec::new()
        .edit(
            "  output_pins:\n",
            "  structure_compliance_arcmin_per_knm: -0.5\n  output_pins:\n",
        )
        .scenes(scenes);
    let err = cycloid::spec::parse("pins.yaml", text.text())
        .expect_err("negative compliance")
        .to_string();
    let (l, c) = place(
        text.text(),
        "structure_compliance_arcmin_per_knm: -0.5",
        "structure_compliance",
    );
    assert!(
        err.starts_with(&format!("pins.yaml:{l}:{c}: ")) && err.contains("zero or positive"),
        "{err} (expected at {l}:{c})"
    );
}
