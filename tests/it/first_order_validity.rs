//! The first-order geometry says when it is outside its validity (issue 26): it used to pass
//! the paper's design at 1e5 N·m, which the exact geometry refuses (its rollers hold ~8.5e4
//! N·m), with 69,583 MPa and 4 rollers in contact, and to print `inf N` at 1e300 N·m.
//!
//! The bound is `first_order::LagValidity`: the closed form keeps the arms of the ideal pose,
//! and over a lag β each arm moves by H·β, H = ∂²g/∂β² from the locus's curvature. Its H is
//! checked here against second differences of the exact gap; then the verdicts through the CLI.

use crate::common::{design, modification, PaperSpec, Scratch};
use cycloid::geometry::clearance::{Mesh, Pose};
use cycloid::geometry::first_order::LagValidity;

/// H_i = κ_C·(n·Q)² − n·Q against the exact gap's second difference in the lag, at the ideal
/// pose of the unmodified profile (whose rollers all touch it, where the expansion is made),
/// every roller away from the line of centres (at the root and tip the closest point has a
/// kink as a roller leaves it: |sin φi| > 0.05), at several crank angles, for the paper's
/// design and a 4-roller one. Step h = 1e-4 rad: the difference's truncation is h²·g''''/12,
/// ~1e-9·g''''; its round-off ~4·ε·Rp/h² = 3e-6 mm; 1e-4 of |H| + 1e-3 mm holds both.
/// The arm −∂g/∂β is checked the same way against the closed form's l_i (exact for the
/// unmodified profile) with h = 1e-6 rad, to 1e-6 mm: the central difference's truncation
/// h²·g'''/6 is ~2e-13·g''' (at 1e-4 rad it was 1.4e-4 mm on the 4-roller design, whose
/// g''' reaches ~1e5 mm/rad³), its round-off ε·Rp/h ~ 7e-9 mm.
#[test]
fn the_bend_is_the_second_derivative_of_the_exact_gap_in_the_lag() {
    for d in [design(10, 2.0, 30.0, 3.0), design(4, 5.0, 30.0, 6.0)] {
        let m = modification(0.0, 0.0, 0.0);
        let mesh = Mesh::new(&d, &m);
        let validity = LagValidity::new(&d, &m);
        let h = 1e-4;
        for crank in [0.1, 0.7, 2.3] {
            for i in 0..d.rollers {
                let phi_i = d.roller_angle(i) - crank;
                if phi_i.sin().abs() <= 0.05 {
                    continue;
                }
                let gap = |lag: f64| {
                    mesh.roller_gap(i, &Pose::lagging(crank, lag), None)
                        .unwrap()
                        .gap_mm
                };
                let (minus, zero, plus) = (gap(-h), gap(0.0), gap(h));
                let (arm, bend) = validity.arm_and_bend(phi_i.cos(), phi_i.sin());
                let second = (plus - 2.0 * zero + minus) / (h * h);
                assert!(
                    (second - bend).abs() <= 1e-4 * bend.abs() + 1e-3,
                    "{} rollers, crank {crank}, roller {i}: {second} vs {bend}",
                    d.rollers
                );
                let first = -(gap(1e-6) - gap(-1e-6)) / 2e-6;
                assert!((first - arm).abs() <= 1e-6, "roller {i}: {first} vs {arm}");
            }
        }
    }
}

/// The paper's design in first-order geometry over one mesh period: at 20 N·m its arms move
/// by a few per cent of the moment (the lag is 0.0037 rad), and the scene passes; at 1e5 N·m
/// (lag 0.18 rad) by more than the moment itself: exit 2 at the scene's `geometry`, naming
/// the crank angle, the lag and the share, and pointing to the exact geometry.
#[test]
fn an_overload_is_outside_the_first_order_validity() {
    let dir = Scratch::new("first-order-validity");
    let spec = |torque_nm: f64| {
        PaperSpec::new()
            .scenes(&format!(
                "  - name: overload\n    output_torque_nm: {torque_nm:?}\n    crank: {{ from_deg: \
                 0.0, to_deg: 36.0, steps: 36 }}\n    effects: [roller_contact, output_pins, \
                 bearing]\n    geometry: first_order\n"
            ))
            .text()
            .to_string()
    };
    dir.write("rated.yaml", spec(20.0));
    let run = crate::common::cycloid(&dir.path, &["check", "rated.yaml"]);
    assert_eq!(run.code(), 0, "{}{}", run.stdout, run.stderr);
    let parsed = cycloid::spec::parse("rated.yaml", &spec(20.0)).unwrap();
    let s = &parsed.scenes[0];
    let r = cycloid::engine::scene::run(
        &parsed,
        s,
        &cycloid::model::Plan::for_scene(s),
        &Default::default(),
    )
    .unwrap();
    let rollers = r.discs[0].loaded.rollers.as_ref().unwrap();
    let validity = LagValidity::new(&parsed.design, &parsed.modification);
    let worst = (0..s.crank_rad.len())
        .map(|k| {
            let forces: Vec<f64> = rollers.force_n.iter().map(|f| f[k]).collect();
            validity.moment_change(s.crank_rad[k], rollers.lag_rad[k], &forces)
        })
        .fold(0.0, f64::max);
    // Measured: 0.025.
    assert!(worst > 0.0 && worst < 0.05, "ε at 20 N·m: {worst}");

    dir.write("overload.yaml", spec(1e5));
    let run = crate::common::cycloid(&dir.path, &["check", "overload.yaml"]);
    assert_eq!(run.code(), 2, "{}{}", run.stdout, run.stderr);
    let e = run.stderr.trim();
    assert!(
        e.starts_with("overload.yaml:") && e.contains(": computation failed: scenes[0].geometry: "),
        "{e}"
    );
    for part in [
        "the first-order geometry is outside its validity: its lag β = 0.18",
        "the closed form holds below 100 %",
        "`geometry: exact`",
    ] {
        assert!(e.contains(part), "missing `{part}` in {e}");
    }
}

/// An output torque beyond what the first-order geometry can hold is refused at its key,
/// before any force is computed, with the bound by hand: np·k·Rrp·e·nc = 10 rollers ×
/// (π/4)·E*·L (E* = 206 GPa/(2·0.91) = 113 187 MPa, L = 8 mm: 7.1117e5 N/mm) × 3 mm × 18 mm =
/// 3.8403e8 N·mm = 384 034 N·m. Nothing printed is infinite.
#[test]
fn a_torque_that_would_overflow_the_forces_is_refused_with_the_bound() {
    let dir = Scratch::new("first-order-bound");
    let k = 0.25 * std::f64::consts::PI * 206_000.0 / (2.0 * (1.0 - 0.09)) * 8.0;
    let bound_nm = 10.0 * k * 3.0 * 18.0 / 1e3;
    assert_eq!(format!("{bound_nm:.0}"), "384034");
    for (torque, key) in [
        ("1.0e300", "scenes[0].output_torque_nm"),
        ("-4.0e5", "scenes[0].output_torque_nm"),
    ] {
        let text = PaperSpec::new()
            .scenes(&format!(
                "  - name: overload\n    output_torque_nm: {torque}\n    crank: {{ from_deg: 0.0, \
                 to_deg: 36.0, steps: 36 }}\n    effects: [bearing]\n    geometry: first_order\n"
            ))
            .text()
            .to_string();
        dir.write("s.yaml", &text);
        let run = crate::common::cycloid(&dir.path, &["check", "s.yaml"]);
        assert_eq!(run.code(), 2, "{}{}", run.stdout, run.stderr);
        let e = run.stderr.trim();
        assert!(e.starts_with("s.yaml:") && e.contains(key), "{e}");
        assert!(
            e.contains("is beyond what the first-order geometry can hold, 384034 N·m"),
            "{e}"
        );
        assert!(!e.contains("inf") && run.stdout.is_empty(), "{e}");
    }
}
