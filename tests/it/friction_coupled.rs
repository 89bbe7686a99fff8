//! The coupled friction model (MODEL.md "Friction, efficiency and heat";
//! `equilibrium::coupling`): friction inside the disc's balance, the input torque from
//! the crank's balance.
//!
//! What is checked comes from outside the solver: the energy identity of the disc's virtual
//! power (P_in = P_out + Σ losses + the normal forces' work), with every term recomputed from
//! the forces as vectors, their points and the rigid-body velocity field; the limit μ → 0
//! (frictionless, bit for bit at μ = 0); the O(μ²) difference of the loss and coupled models.

use crate::common::{self, cases, Case};
use cycloid::equilibrium::angle::solve_angle;
use cycloid::equilibrium::coupling::{Coupling, Energy};
use cycloid::equilibrium::loaded::{AngleSolution, Model};
use cycloid::model::{
    BearingFriction, ContactLaw, Design, Effect, Friction, FrictionModel, GeometryMode,
    Modification, PinFriction, PinMode, Plan, RollerFriction, RollerMode, Scene,
};
use proptest::prelude::*;

/// Friction at every path: rollers (fixed or rotating on a bore of 0.4·Rrp), pins (fixed or
/// sleeves on a bore of 0.6 of the pin), a crank bearing of bore 0.4·Rp.
fn friction(design: &Design, mu: f64, rotating: bool, sleeves: bool) -> Friction {
    Friction {
        model: FrictionModel::Coupled,
        rollers: Some(RollerFriction {
            mode: if rotating {
                RollerMode::Rotating {
                    bore_radius_mm: 0.4 * design.roller_radius_mm,
                }
            } else {
                RollerMode::Fixed
            },
            mu,
        }),
        output_pins: Some(PinFriction {
            mode: if sleeves {
                PinMode::Sleeve {
                    bore_radius_mm: 0.6 * design.pins.pin_radius_mm,
                }
            } else {
                PinMode::Fixed
            },
            mu,
        }),
        crank_bearing: Some(BearingFriction {
            mu,
            bore_diameter_mm: 0.4 * design.roller_circle_radius_mm,
        }),
        no_load_torque_nmm: cycloid::model::NoLoadTorque::constant(0.0),
    }
}

/// A loaded scene of rollers, pins and bearing over one mesh period in `steps` angles.
fn scene(design: &Design, torque_nmm: f64, steps: usize, geometry: GeometryMode) -> Scene {
    let period = design.mesh_period_rad();
    Scene {
        name: "efficiency".to_string(),
        output_torque_nmm: torque_nmm,
        crank_rad: (0..steps)
            .map(|k| period * k as f64 / steps as f64)
            .collect(),
        crank_from_deg: 0.0,
        crank_to_deg: period.to_degrees(),
        effects: vec![],
        contact_law: ContactLaw::PaperLinear,
        geometry,
        bearing_stiffness_n_per_mm: None,
        torque_sweep: None,
        input_speed_rpm: None,
        duty_cycle: None,
        face: Default::default(),
    }
}

fn model(design: &Design, m: &Modification, scene: &Scene) -> Model {
    let plan = Plan::of(
        &scene.name,
        &[Effect::RollerContact, Effect::OutputPins, Effect::Bearing],
    );
    Model::new(design, m, scene, &plan)
}

/// Every angle of `scene` solved in order, each warm-started from the last.
fn solutions(model: &Model, scene: &Scene) -> Vec<AngleSolution> {
    let mut last = AngleSolution::default();
    scene
        .crank_rad
        .iter()
        .map(|&phi| {
            last = solve_angle(model, phi, &last)
                .unwrap_or_else(|e| panic!("{}° : {e}", phi.to_degrees()));
            last.clone()
        })
        .collect()
}

/// The power terms of every angle of a solved scene under `coupling`.
fn energies(coupling: &Coupling, scene: &Scene, sols: &[AngleSolution]) -> Vec<Energy> {
    scene
        .crank_rad
        .iter()
        .zip(sols)
        .map(|(&phi, s)| coupling.energy(phi, s, scene.output_torque_nmm))
        .collect()
}

fn losses(e: &Energy) -> f64 {
    e.rollers + e.output_pins + e.crank_bearing
}

/// Mean efficiency P_out / (P_out + mean loss) (MODEL.md).
fn mean_efficiency(es: &[Energy]) -> f64 {
    let n = es.len() as f64;
    let out = es.iter().map(|e| e.output).sum::<f64>() / n;
    let loss = es.iter().map(losses).sum::<f64>() / n;
    out / (out + loss)
}

fn paper() -> (Design, Modification) {
    paper_modified(0.0, 0.0)
}

/// The paper's design with the modification (ΔRp, ΔRrp), mm.
fn paper_modified(shift_mm: f64, equidistant_mm: f64) -> (Design, Modification) {
    let spec = common::paper_spec(shift_mm, equidistant_mm);
    (spec.design, spec.modification)
}

/// μ = 0 at every path is the frictionless model: every lag, force and bearing force bit for
/// bit (the coupled balance with zero coefficients is the frictionless one: `Model::coupled`
/// is none, and the sweep takes the same path).
#[test]
fn zero_friction_is_the_frictionless_balance_bit_for_bit() {
    let (design, m) = paper_modified(0.02, 0.03);
    let s = scene(&design, 20_000.0, 12, GeometryMode::Exact);
    let plain = model(&design, &m, &s);
    let zero = plain
        .clone()
        .with_friction(&friction(&design, 0.0, false, false), &design);
    assert!(zero.coupling.is_none());
    let (a, b) = (solutions(&plain, &s), solutions(&zero, &s));
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x.lag_rad, y.lag_rad);
        assert_eq!(x.output_lag_rad, y.output_lag_rad);
        assert_eq!(x.rollers, y.rollers);
        assert_eq!(x.pins, y.pins);
        assert_eq!(x.bearing_force_n, y.bearing_force_n);
    }
}

/// The coupled balance is continuous at μ = 0: at μ = 1e-9 every roller force and the bearing
/// force are within 1e-6 of the frictionless ones (relative to the largest force). The change is
/// of order μ times the friction's arms over the normal arms (≲ 10 for these designs): 1e-8,
/// plus the balances' own 1e-11; 1e-6 leaves room and still catches a friction term entering
/// at O(1) (a sign or a factor missing where μ multiplies).
#[test]
fn tiny_friction_moves_the_balance_by_little() {
    let (design, m) = paper();
    let s = scene(&design, 20_000.0, 12, GeometryMode::Exact);
    let plain = model(&design, &m, &s);
    let tiny = plain
        .clone()
        .with_friction(&friction(&design, 1e-9, false, false), &design);
    assert!(tiny.coupling.is_some());
    for (x, y) in solutions(&plain, &s).iter().zip(&solutions(&tiny, &s)) {
        let scale = x.rollers.iter().map(|r| r.force_n).fold(0.0, f64::max);
        for (p, q) in x.rollers.iter().zip(&y.rollers) {
            assert!((p.force_n - q.force_n).abs() <= 1e-6 * scale);
        }
        let (fb0, fb1) = (x.bearing_force_n.unwrap(), y.bearing_force_n.unwrap());
        assert!((fb0 - fb1).norm() <= 1e-6 * fb0.norm());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(64)
    ))]

    /// The energy identity of the coupled balance at every angle, for random designs,
    /// modifications, μ ∈ [0, 0.2], torques of both signs and every roller/pin mode, in two parts
    /// (`Energy`): the disc's virtual power P_in = P_flange + Σ losses + W_n + W_b and the flange's
    /// P_flange = T/nc + W_p, every term recomputed from the forces as vectors at their points and
    /// the rigid-body velocities (`Coupling::energy`). P_in comes from the crank's balance
    /// (T_in = E × Fb + M_b) and Fb from the disc's force balance, so the first holds only if the
    /// disc's moment balance carries every friction moment with the losses' signs (the disc's
    /// virtual power is zero only in equilibrium); the second only if the pins' balance carries
    /// their friction's moment about the axis.
    /// Tolerance: the balances converge to 1e-11 of their moment scale (`Settings::rel_tol`): the
    /// rollers' Σ|F·l̃| + c_b·|Fb|, which with friction arms of both signs and a bearing friction that
    /// dominates (a bore of 0.4·Rp at μ 0.2 under a light torque) is up to ~100× the largest power
    /// term; the identity's error is that residual moment times the disc's speed 1/nc. 1e-8 of the
    /// largest term keeps a margin of ~10 over the worst case seen (1.0e-9) and is 1e6 below what a
    /// friction moment missing from a balance leaves (O(μ) of the powers). Under a strong preload
    /// the rollers' normal moments, which cancel, dwarf every power term: the scale is then their
    /// sum Σ|F·l| over nc (a committed regression: nc 3, ΔRrp −0.3 mm, μ 4.7e-5, 11 N·mm).
    #[test]
    fn energy_identity_at_every_angle(
        case in cases(),
        mu in 0.0f64..0.2,
        load in -1.0f64..1.0,
        rotating in any::<bool>(),
        sleeves in any::<bool>(),
        first_order in any::<bool>(),
    ) {
        identity_holds(&case, mu, load, rotating, sleeves, first_order)?;
    }
}

fn identity_holds(
    case: &Case,
    mu: f64,
    load: f64,
    rotating: bool,
    sleeves: bool,
    first_order: bool,
) -> Result<(), TestCaseError> {
    let design = &case.design;
    // 0.5 N·m at Rp = 30 mm, scaled with Rp² (the discs tests' moderate load), of either sign.
    let rp = design.roller_circle_radius_mm;
    let torque = 500.0 * (rp / 30.0).powi(2) * if load.abs() < 0.05 { 0.05 } else { load };
    let geometry = if first_order {
        GeometryMode::FirstOrder
    } else {
        GeometryMode::Exact
    };
    let s = scene(design, torque, 6, geometry);
    let f = friction(design, mu, rotating, sleeves);
    let coupled = model(design, &case.m, &s).with_friction(&f, design);
    let mut last = AngleSolution::default();
    for &phi in &s.crank_rad {
        last = match solve_angle(&coupled, phi, &last) {
            Ok(sol) => sol,
            // A random design may be beyond its contact model's capacity, or float in its
            // backlash: that is the frictionless solver's answer too, not this test's subject.
            Err(_) => return Err(TestCaseError::reject("no balance")),
        };
        let Some(c) = coupled.coupling.as_ref() else {
            return Ok(());
        };
        let e = c.energy(phi, &last, torque);
        // The balances' residual moment is 1e-11 of their moment scale, which a strong preload
        // (interference) makes far larger than the torque's power: that scale times the disc's
        // speed 1/nc bounds the identity's round-off too.
        let moments: f64 = last
            .rollers
            .iter()
            .map(|r| (r.force_n * r.arm_mm).abs())
            .sum::<f64>()
            + last
                .pins
                .iter()
                .map(|p| (p.force_n * p.arm_mm).abs())
                .sum::<f64>();
        let scale = e.scale().max(moments / design.teeth as f64);
        prop_assert!(
            e.imbalance().abs() <= 1e-8 * scale,
            "φ {}°: {e:?}, imbalance {:e}",
            phi.to_degrees(),
            e.imbalance()
        );
        prop_assert!(
            e.flange_imbalance().abs() <= 1e-8 * scale,
            "φ {}°: {e:?}, flange {:e}",
            phi.to_degrees(),
            e.flange_imbalance()
        );
    }
    Ok(())
}

/// In first-order geometry with the nominal eccentricity and a rigid bearing every roller's
/// normal passes through the pitch point I and every pin force is along −e_φ: the normal forces
/// do no work under the nominal kinematics (W_n = 0) and the pins' moments about the axis and
/// the disc centre agree (W_c = 0), so P_in = P_out + Σ losses exactly, whatever the profile's
/// modification. Tolerance: 1e-9 of the largest power, as in `energy_identity_at_every_angle`.
#[test]
fn first_order_input_power_is_output_plus_losses() {
    let (design, m) = paper_modified(0.1, 0.13);
    let s = scene(&design, 30_000.0, 18, GeometryMode::FirstOrder);
    for mu in [0.02, 0.1] {
        let c = model(&design, &m, &s).with_friction(&friction(&design, mu, false, false), &design);
        let coupling = c.coupling.unwrap();
        for e in energies(&coupling, &s, &solutions(&c, &s)) {
            assert!(e.normal_work.abs() <= 1e-9 * e.input, "{e:?}");
            assert!(e.bearing_offset.abs() <= 1e-9 * e.input, "{e:?}");
            assert!(e.pin_convention.abs() <= 1e-9 * e.input, "{e:?}");
            assert!(e.flange_imbalance().abs() <= 1e-9 * e.input, "{e:?}");
            assert!(
                (e.input - e.output - losses(&e)).abs() <= 1e-9 * e.input,
                "{e:?}"
            );
        }
    }
}

/// The loss model (frictionless forces, losses μ·F·v) and the coupled model differ by O(μ²) in
/// the mean efficiency: both are 1 − a·μ + O(μ²) with the same a (the loss model is the
/// coupled one's first order). Halving μ divides the difference by 4 up to the O(μ³) term:
/// between μ = 0.01 and 0.005 the ratio of the differences is 4·(1 − c·μ) with c the relative
/// weight of the third-order term, of the order of the loss fraction per unit μ (fixed rollers
/// lose ≈ (|P − I| − Rrp)/l ≈ 1–5 per unit μ here); the band [3.5, 4.5] holds for |c| ≤ 12 and
/// rejects a first-order difference (ratio 2) or none.
#[test]
fn loss_and_coupled_models_differ_as_mu_squared() {
    let (design, m) = paper();
    let s = scene(&design, 20_000.0, 36, GeometryMode::Exact);
    let plain = model(&design, &m, &s);
    let frictionless = solutions(&plain, &s);
    let difference = |mu: f64| {
        let c = plain
            .clone()
            .with_friction(&friction(&design, mu, false, false), &design);
        let coupling = c.coupling.unwrap();
        let loss = mean_efficiency(&energies(&coupling, &s, &frictionless));
        let coupled = mean_efficiency(&energies(&coupling, &s, &solutions(&c, &s)));
        loss - coupled
    };
    let (d1, d2) = (difference(0.01), difference(0.005));
    let ratio = d1 / d2;
    assert!(d1.abs() > 1e-6, "the models differ: {d1:e}");
    assert!((3.5..=4.5).contains(&ratio), "{d1:e} / {d2:e} = {ratio}");
}

// ---------------------------------------------------------------------------------------------
// Through the engine: the shipped efficiency spec with the coupled model.
// ---------------------------------------------------------------------------------------------

/// specs/reducer-efficiency.yaml with the coupled model, its text edited by `edits` (each
/// `from` must occur once).
fn efficiency_spec(edits: &[(&str, &str)]) -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/specs/reducer-efficiency.yaml");
    let mut text = std::fs::read_to_string(path).unwrap();
    let model = text
        .lines()
        .find(|l| l.trim_start().starts_with("model:"))
        .unwrap()
        .to_string();
    text = text.replacen(&model, "    model: coupled", 1);
    for (from, to) in edits {
        assert_eq!(text.matches(from).count(), 1, "`{from}` once");
        text = text.replacen(from, to, 1);
    }
    text
}

fn run_efficiency(text: &str) -> cycloid::model::results::SceneResult {
    let spec = cycloid::spec::parse("coupled.yaml", text).unwrap_or_else(|e| panic!("{e}"));
    let scene = &spec.scenes[0];
    let plan = Plan::for_scene(scene);
    cycloid::engine::scene::run(&spec, scene, &plan, &Default::default())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Through the engine, in first-order geometry (where the normal forces do no work:
/// `first_order_input_power_is_output_plus_losses`), one and two discs: the input torque from
/// the crank's balance, T_in = Σ E × Fb + μ_b·|Fb|·d/2 + T0, equals T/nc + the losses that the
/// loss function (`friction::loss`, shared with the loss model) measures on the coupled forces,
/// at every angle. Two independent routes: the crank's moment and the contacts' Σ μ·F·v.
/// Tolerance 1e-8 of the input torque: the balances' 1e-11, and the bearing force passing
/// through the sweep's magnitude and angle columns (a few ulp each).
#[test]
fn engine_input_torque_is_output_plus_losses_in_first_order_geometry() {
    for discs in ["", "  discs: 2\n"] {
        let text = efficiency_spec(&[
            (
                "effects: [efficiency]",
                "effects: [efficiency]\n    geometry: first_order",
            ),
            ("  face_width_mm:", &format!("{discs}  face_width_mm:")),
            ("steps: 1080", "steps: 108"),
        ]);
        let r = run_efficiency(&text);
        let e = r.reducer.efficiency.as_ref().unwrap();
        let reducer = e.reducer.as_ref().unwrap();
        let torque_per_nc = 20_000.0 / 9.0;
        for (t_in, loss) in reducer.input_torque_nmm.iter().zip(&e.loss_nmm) {
            let expected = torque_per_nc + loss.total();
            assert!(
                (t_in - expected).abs() <= 1e-8 * t_in,
                "discs `{discs}`: {t_in} against {expected}"
            );
        }
        assert!(reducer.self_locking_crank_rad.is_empty());
    }
}

/// A negative output torque (the output drives): with moderate friction the reducer back-drives
/// (the input torque is negative at every angle, no self-locking); with μ = 0.9 on the rollers'
/// pins and the sleeves the friction holds more than the output can drive: the input must
/// still push, and every angle is reported as self-locking, not a solver failure.
#[test]
fn back_driving_and_self_locking_are_reported() {
    let back = run_efficiency(&efficiency_spec(&[
        ("output_torque_nm: 20.0", "output_torque_nm: -20.0"),
        ("steps: 1080", "steps: 108"),
    ]));
    let reducer = back.reducer.efficiency.unwrap().reducer.unwrap();
    assert!(reducer.input_torque_nmm.iter().all(|t| *t < 0.0));
    assert!(reducer.self_locking_crank_rad.is_empty());
    let text = efficiency_spec(&[
        ("output_torque_nm: 20.0", "output_torque_nm: -20.0"),
        ("steps: 1080", "steps: 108"),
    ])
    .replace("mu: 0.06 ", "mu: 0.9 ");
    let locked = run_efficiency(&text)
        .reducer
        .efficiency
        .unwrap()
        .reducer
        .unwrap();
    assert!(locked.input_torque_nmm.iter().all(|t| *t > 0.0));
    assert_eq!(locked.self_locking_crank_rad.len(), 108);
}

/// The coupled model with a compliant crank bearing is refused at the scene's key (exit 2), not
/// run silently with another model.
#[test]
fn coupled_with_a_compliant_bearing_is_refused_at_its_key() {
    let text = efficiency_spec(&[(
        "effects: [efficiency]",
        "effects: [efficiency]\n    bearing_stiffness_n_per_mm: 1.0e5",
    )]);
    let e = cycloid::spec::parse("coupled.yaml", &text).unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains("scenes[0].bearing_stiffness_n_per_mm") && message.contains("rigid"),
        "{message}"
    );
}

/// A preloaded reducer running idle (T = 0, the coupled model): the preload's contacts slide,
/// so the input must supply their friction, T_in·ω = Σ losses (energy conservation with
/// P_out = 0). The expected input torque is computed here from the roller forces and MODEL.md's
/// closed-form sliding speed, Σ μ·F_i·(|P_i − I| − Rrp)/nc (I = e·np·e_φ the pitch point): in
/// first-order geometry every contact normal passes through I, so that is the disc's sliding
/// speed at the ideal pose. Before, the coupled model answered the crank's balance of the
/// frictionless forces, which holds no contact friction: T_in ≈ 1e-12 N·mm against ~4.3 N·m
/// (679 W lost, none entering). Tolerance 1e-3 of the expected torque: the idle lag (|β| below
/// 1e-5 rad: the TE fluctuation is under 1 arcsec) moves each contact point by at most
/// 2·(Rp + e·np)·|β| ≤ 1e-3 mm against |C − I| ≥ 20 mm.
#[test]
fn idle_preloaded_input_torque_pays_the_friction() {
    let text = "name: idle
reducer:
  teeth: 9
  rollers: 10
  eccentricity_mm: 2.0
  roller_circle_radius_mm: 30.0
  roller_radius_mm: 3.0
  face_width_mm: 8.0
  output_pins: { count: 6, circle_radius_mm: 18.0, pin_radius_mm: 3.0, hole_clearance_mm: 0.0 }
  material: { youngs_modulus_gpa: 206.0, poisson_ratio: 0.3 }
  friction:
    model: coupled
    rollers: { mode: fixed, mu: 0.1 }
modification: { shift_mm: 0.002, equidistant_mm: 0.0 }
scenes:
  - name: idle
    output_torque_nm: 0.0
    input_speed_rpm: 1500.0
    geometry: first_order
    crank: { from_deg: 0.0, to_deg: 36.0, steps: 36 }
    effects: [efficiency]
";
    let r = run_efficiency(text);
    let reducer = r
        .reducer
        .efficiency
        .as_ref()
        .unwrap()
        .reducer
        .as_ref()
        .unwrap();
    let forces = &r.discs[0].loaded.rollers.as_ref().unwrap().force_n;
    let (nc, np, e, rp, rrp, mu) = (9.0, 10usize, 2.0, 30.0, 3.0, 0.1);
    for (k, (phi, t_in)) in r
        .crank_rad
        .iter()
        .zip(&reducer.input_torque_nmm)
        .enumerate()
    {
        let pitch = (e * np as f64 * phi.cos(), e * np as f64 * phi.sin());
        let expected: f64 = (0..np)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / np as f64;
                let d = (rp * a.cos() - pitch.0).hypot(rp * a.sin() - pitch.1);
                mu * forces[i][k].max(0.0) * (d - rrp) / nc
            })
            .sum();
        assert!(expected > 1e3, "the preload loads the rollers: {expected}");
        assert!(
            (t_in - expected).abs() <= 1e-3 * expected,
            "crank {phi}: input torque {t_in} N·mm against the losses' {expected} N·mm"
        );
    }
}

/// A coupled balance that cannot be found names the scene's output torque, not the rollers'
/// target with the pins' friction in it (at μ 0.999999 back-driven at −20 N·m it read
/// "an output torque of −18.00124816 N·m"): the shipped efficiency spec with the coupled model
/// and every μ at 0.999999, −20 N·m.
#[test]
fn a_coupled_balance_beyond_reach_names_the_scenes_torque() {
    let shipped = include_str!("../../specs/reducer-efficiency.yaml");
    let text = shipped
        .replacen("model: loss", "model: coupled", 1)
        .replace("mu: 0.06 ", "mu: 0.999999 ")
        .replacen("mu: 0.0025 ", "mu: 0.999999 ", 1)
        .replacen("output_torque_nm: 20.0", "output_torque_nm: -20.0", 1);
    let spec = cycloid::spec::parse("mu.yaml", &text).unwrap();
    let run = cycloid::check(
        &spec,
        &cycloid::CheckOptions::default(),
        &cycloid::progress::Silent,
    );
    let Err(e) = run else {
        panic!("a balance at μ 0.999999")
    };
    let shown = e.to_string();
    assert!(
        shown.contains("cannot balance an output torque of -20 N·m"),
        "{shown}"
    );
}

/// Without `input_speed_rpm` an efficiency scene's losses have no watts and no temperature:
/// the run says so in a note (docs/effects/friction.md promised one; none was given), and
/// with the speed it does not.
#[test]
fn losses_without_a_speed_are_noted() {
    let shipped = include_str!("../../specs/reducer-efficiency.yaml");
    // Without the speed, and the limits that need it (watts, temperature, life in hours).
    let without: String = (shipped
        .replacen("    input_speed_rpm: 1500.0", "", 1)
        .lines())
    .filter(|l| {
        ![
            "max_power_loss_w",
            "max_temperature_c",
            "min_bearing_life_h",
        ]
        .iter()
        .any(|k| l.contains(k))
    })
    .map(|l| format!("{l}\n"))
    .collect();
    let notes = |text: &str| {
        let spec = cycloid::spec::parse("e.yaml", text).unwrap();
        let notes = cycloid::engine::scene::notes(&spec);
        notes
            .iter()
            .map(cycloid::report::explain::note)
            .collect::<Vec<_>>()
    };
    let said = "friction losses in watts (and the temperature) not given";
    assert!(notes(&without).iter().any(|n| n.contains(said)));
    assert!(!notes(shipped).iter().any(|n| n.contains(said)));
}
