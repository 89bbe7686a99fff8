//! Torsion under a locked input (the catalogue figures) and the crank bearing's rating life
//! (issue 14): the figures on curves known by hand, the physics of the torsion curve (monotone,
//! odd-symmetric, its slope against the ordinary loaded TE, preload, the dead band against the
//! unloaded backlash of the clearance effect), the bearing-life formula, and the CLI.

use crate::common;

use crate::common::{cycloid_here, PaperSpec, Scratch};
use cycloid::engine::bearing_life::{equivalent_load, life_h, relative_speed_rpm};
use cycloid::engine::scene::{self, Writes};
use cycloid::engine::torsion::{figures, FIGURE_TORQUES, ZERO_SIDE};
use cycloid::equilibrium::discs::{CoupledWork, Discs};
use cycloid::equilibrium::torsion::solve_point;
use cycloid::model::results::{SceneResult, TorsionCurves};
use cycloid::spec::Spec;
use cycloid::units;

/// A torsion scene `torsion` locked at `crank` (YAML flow mapping), rated `rated_nm`, with
/// `effects` and any `extra` scene keys.
fn torsion_item(rated_nm: f64, steps: usize, crank: &str, effects: &str, extra: &str) -> String {
    format!(
        "  - name: torsion\n    torque_sweep: {{ rated_nm: {rated_nm:?}, steps: {steps} }}\n    \
         crank: {crank}\n    effects: [{effects}]\n{extra}"
    )
}

/// The paper's design (0.125/0.1593 mm unless `modification` says otherwise) with one torsion
/// scene at 20 N·m rated.
fn torsion_spec(modification: Option<(f64, f64)>, crank: &str, effects: &str, extra: &str) -> Spec {
    let mut spec = PaperSpec::new();
    if let Some((shift, equidistant)) = modification {
        spec = spec.modification(shift, equidistant);
    }
    spec.scenes(&torsion_item(20.0, 8, crank, effects, extra))
        .parse("torsion.yaml")
}

use crate::common::run_first_scene as run;

fn curves(r: &SceneResult) -> &TorsionCurves {
    r.reducer
        .torsion
        .as_ref()
        .expect("a torsion scene computes torsion")
}

/// γ(T) = ±b/2 + T/k1 up to half the rated torque R, then stiffer (k2 forward, k3 reverse):
/// a piecewise-linear curve whose figures are known by hand. Lost motion at ±3 %: b + 2·0.03R/k1;
/// backlash b; rigidity (R/2)/((R/2)/k2) = k2 forward, k3 reverse, the figure the smaller.
#[test]
fn the_figures_of_a_piecewise_linear_curve_are_the_hand_values() {
    let (r, b, k1, k2, k3) = (1000.0, 0.002, 1e5, 4e5, 3e5);
    let gamma = |t: f64| {
        let half = 0.5 * r;
        let (side, k_high) = if t >= 0.0 { (1.0, k2) } else { (-1.0, k3) };
        let low = t.abs().min(half);
        let high = (t.abs() - half).max(0.0);
        side * (b / 2.0 + low / k1 + high / k_high)
    };
    // The one-sided limits are at ±ZERO_SIDE·R: γ(0±) = ±b/2 exactly, as a curve with a dead
    // band has them.
    let mut at = [0.0; 8];
    for (g, f) in at.iter_mut().zip(FIGURE_TORQUES) {
        *g = if f.abs() == ZERO_SIDE {
            f.signum() * b / 2.0
        } else {
            gamma(f * r)
        };
    }
    let f = figures(r, &at).unwrap();
    // Sums and quotients of a few doubles: 1e-12 relative is many ulps.
    let close = |a: f64, e: f64| (a - e).abs() <= 1e-12 * e.abs();
    assert!(close(f.lost_motion_rad, b + 2.0 * 0.03 * r / k1), "{f:?}");
    assert!(close(f.backlash_rad, b), "{f:?}");
    assert!(close(f.rigidity_nmm_per_rad.0, k2), "{f:?}");
    assert!(close(f.rigidity_nmm_per_rad.1, k3), "{f:?}");
    assert!(
        close(f.rigidity(), k3),
        "the figure is the smaller direction"
    );
    // A curve that does not rise between 50 % and 100 % has no rigidity: an error, not ∞.
    let mut flat = at;
    flat[7] = flat[6];
    assert!(figures(r, &flat).is_err());
}

/// The loop at every locked angle, in exact geometry with the linear law and pins and a rigid
/// bearing, and in first-order geometry with Johnson's law and a compliant bearing: γ rises
/// strictly along the rising branch and falls strictly along the falling one, and the two
/// branches coincide (frictionless: the same torque gives the same γ; the two solves are
/// warm-started from opposite sides and agree to the solver's tolerance, 1e-11 of the balance,
/// ~1e-14 rad on γ ~ 4e-3 rad; 1e-12 rad allows for Newton stopping short on either side).
#[test]
fn torsion_curves_are_monotone_and_their_branches_coincide() {
    let crank = "{ from_deg: 0.0, to_deg: 36.0, steps: 4 }";
    let variants = [
        ("bearing", String::new()),
        (
            "bearing",
            "    geometry: first_order\n    contact_law: hertz_nonlinear\n    \
             bearing_stiffness_n_per_mm: 2.0e5\n"
                .to_string(),
        ),
        ("roller_contact", String::new()),
    ];
    for (effects, extra) in variants {
        let spec = torsion_spec(None, crank, effects, &extra);
        let r = run(&spec);
        let t = curves(&r);
        let steps = spec.scenes[0].torque_sweep.unwrap().steps;
        assert_eq!(t.torque_nmm.len(), 4 * steps + 1);
        for row in &t.torsion_rad {
            let (rising, falling) = row.split_at(2 * steps + 1);
            assert!(rising.windows(2).all(|w| w[1] > w[0]), "{effects} {extra}");
            let top = rising[2 * steps];
            assert!(falling[0] < top && falling.windows(2).all(|w| w[1] < w[0]));
            // The falling branch at T_m is the rising branch at the same torque, except at
            // T = 0 where the two one-sided limits differ by the dead band.
            for m in 1..2 * steps {
                if m != steps {
                    let (up, down) = (row[m], row[4 * steps - m]);
                    assert!((up - down).abs() <= 1e-12, "m {m}: {up} vs {down}");
                }
            }
            assert!(
                row[3 * steps] > row[steps],
                "γ(0⁺) above γ(0⁻) with clearance"
            );
        }
        assert!(t.figures.iter().all(|f| f.rigidity() > 0.0));
    }
}

/// At crank 0 the paper's design is mirror-symmetric about the x axis (rollers at 2πi/np, the
/// disc centre at (e, 0), the profile unturned, pins at 2πj/M with ideal holes): turning the
/// output by −T mirrors the equilibrium at +T, so γ(−T) = −γ(T) on the whole loop, the
/// one-sided limits included (γ(0⁻) = −γ(0⁺)). Tolerance: the solver's 1e-11 on the balance
/// and the closest-point round-off (1e-14 mm over arms of ~10 mm) are ~1e-14 rad; 1e-12 rad
/// allows for the exact geometry's Newton stopping short on either side.
#[test]
fn a_symmetric_design_has_an_odd_torsion_curve() {
    let spec = torsion_spec(
        None,
        "{ from_deg: 0.0, to_deg: 36.0, steps: 1 }",
        "bearing",
        "",
    );
    let r = run(&spec);
    let t = curves(&r);
    let steps = spec.scenes[0].torque_sweep.unwrap().steps;
    let row = &t.torsion_rad[0];
    for m in 0..=steps {
        // T_m and T_{2s−m} are opposite on the rising branch; at m = s the pair is γ(0⁻) on
        // the rising branch and γ(0⁺) on the falling one.
        let (minus, plus) = if m == steps {
            (row[steps], row[3 * steps])
        } else {
            (row[m], row[2 * steps - m])
        };
        assert_eq!(t.torque_nmm[m], -t.torque_nmm[2 * steps - m]);
        assert!((minus + plus).abs() <= 1e-12, "m {m}: {minus} vs {plus}");
    }
    let f = &t.figures[0];
    let (forward, reverse) = f.rigidity_nmm_per_rad;
    assert!(
        (forward - reverse).abs() <= 1e-6 * forward,
        "{forward} vs {reverse}"
    );
}

/// The torsion solve against the ordinary loaded scene at the same crank angle: γ(T) equals
/// the loaded TE at output torque T (the same equilibrium, reached by the crank sweep's own
/// code), and dγ/dT at the rated torque from the torsion solve equals the central difference
/// (te(T + h) − te(T − h))/2h of ordinary scenes. h = 1e-3·T: the curve's curvature over ±h
/// errs by h²·γ'''/6, ~1e-6 of the slope at most (the stiffness changes by tens of per cent
/// over the rated torque); the solves' round-off (1e-11 of the balance, ~1e-16 rad on the twist
/// 2h/k ~ 1e-7 rad) is 1e-9 of it: 1e-5 relative holds both with a margin.
///
/// Then the secant rigidity between 50 % and 100 % lies between the tangent stiffnesses there:
/// more rollers share the load as it grows (the clearances close), so the curve stiffens —
/// k(50 %) ≤ secant ≤ k(100 %) — checked as that, not in general.
///
/// For one, two and three discs (the coupled balance of `equilibrium::discs`: two share
/// equally, three at 120° do not, 10 rollers): the torsion loop and the crank sweep reach it
/// by different warm starts, and the slope is the reducer's, all discs together.
#[test]
fn the_slope_at_rated_torque_matches_differences_of_the_loaded_te() {
    for discs in 1..=3 {
        slope_matches_the_loaded_te(discs);
    }
}

fn slope_matches_the_loaded_te(discs: usize) {
    let crank = "{ from_deg: 9.0, to_deg: 45.0, steps: 1 }";
    let mut spec = torsion_spec(None, crank, "bearing", "");
    spec.design.discs = discs;
    let r = run(&spec);
    let t = curves(&r);
    let rated = spec.scenes[0].torque_sweep.unwrap().rated_nmm;
    let phi = spec.scenes[0].crank_rad[0];
    // The ordinary scene at output torque T over the same one crank angle.
    let te = |torque_nmm: f64| {
        let mut s = spec.scenes[0].clone();
        s.torque_sweep = None;
        s.output_torque_nmm = torque_nmm;
        s.effects = vec![cycloid::model::Effect::Bearing];
        let plan = cycloid::model::Plan::for_scene(&s);
        let r = scene::run(&spec, &s, &plan, &Default::default()).unwrap();
        r.reducer.transmission.unwrap().te_rad[0]
    };
    let top = *t.torsion_rad[0]
        .iter()
        .fold(&f64::MIN, |a, b| if b > a { b } else { a });
    // (1e-12 rad for one disc, where both solve the same balance from different starts;
    // several discs add the coupling's tolerance, 1e-10·T times the compliance, ~1e-13 rad.)
    assert!(
        (top - te(rated)).abs() <= 1e-12,
        "{discs} disc(s): γ(rated) {top} vs te {}",
        te(rated)
    );
    // dγ/dT by the torsion solve itself (`solve_point`) at T ± h.
    let plan = scene::plan(&spec, &spec.scenes[0], Writes::default());
    let model = scene::loaded_model(
        &spec.design,
        &spec.modification,
        &spec.scenes[0],
        &plan,
        &Default::default(),
    );
    let slope_torsion = |at: f64| {
        let h = 1e-3 * rated;
        let mut discs = Discs::new(&model, discs);
        let mut work = CoupledWork::new(&discs);
        let up = solve_point(&mut discs, phi, at + h, &mut work).unwrap();
        let down = solve_point(&mut discs, phi, at - h, &mut work).unwrap();
        (up - down) / (2.0 * h)
    };
    let h = 1e-3 * rated;
    let slope_te = (te(rated + h) - te(rated - h)) / (2.0 * h);
    let slope = slope_torsion(rated);
    assert!(
        (slope - slope_te).abs() <= 1e-5 * slope_te,
        "{discs} disc(s): {slope} vs {slope_te}"
    );
    let f = t.figures[0];
    let (k_half, k_rated) = (1.0 / slope_torsion(0.5 * rated), 1.0 / slope);
    let secant = f.rigidity_nmm_per_rad.0;
    assert!(
        k_half <= secant && secant <= k_rated,
        "{k_half} ≤ {secant} ≤ {k_rated}"
    );
}

/// Interference (ΔRp = 0.02 mm, ΔRrp = 0: a tip gap of −0.02 mm, every roller pressed into the
/// disc before any load, the preload of MODEL.md and `specs/hard/preload-zero-torque.yaml`)
/// gives a curve without a dead band: backlash 0 to the one-sided limits' elastic twist,
/// 2·1e-6·Trated/k₀ ≈ 2e-6·2e4 N·mm / 1e9 N·mm/rad = 4e-11 rad (k₀ of the preloaded mesh, every
/// roller in contact, is above the figure's rigidity, ~1e9 N·mm/rad here), checked as
/// < 1e-9 rad (2e-4 arcsec, against the clearance design's 25 arcmin); and a finite rigidity
/// larger than the clearance design's (all the rollers share the load at once). Lost motion
/// is then the elastic twist over ±3 % alone, under 1 % of the clearance design's.
#[test]
fn preload_gives_a_stiff_curve_without_backlash() {
    let crank = "{ from_deg: 0.0, to_deg: 36.0, steps: 2 }";
    let preload = run(&torsion_spec(Some((0.02, 0.0)), crank, "bearing", ""));
    let clearance = run(&torsion_spec(None, crank, "bearing", ""));
    let (p, c) = (curves(&preload), curves(&clearance));
    for (fp, fc) in p.figures.iter().zip(&c.figures) {
        assert!(fp.backlash_rad.abs() < 1e-9, "{fp:?}");
        assert!(
            fp.rigidity().is_finite() && fp.rigidity() > fc.rigidity(),
            "{fp:?} {fc:?}"
        );
        assert!(fp.lost_motion_rad > 0.0 && fp.lost_motion_rad < 0.01 * fc.lost_motion_rad);
    }
}

/// The dead band of the torsion curve is the unloaded lost motion of the clearance effect at
/// the same crank angle (pins ideal, rigid bearing: only the rollers' clearance is free play):
/// two independent computations, the closing lags of the unloaded mesh and the loaded solves
/// at ±1e-6·Trated. They differ by the elastic twist over ±1e-6·Trated, 2e-6·2e4 N·mm/k₀: with
/// k₀ at least one roller's k·l² ≈ 7.1e5 N/mm·(5 mm)² ≈ 1.8e7 N·mm/rad, at most 2.3e-9 rad =
/// 4.6e-4 arcsec (measured: 7e-5 arcsec), and the closing lags' own tolerance (~1e-13 rad);
/// 1e-3 arcsec holds both and is far inside what the figure shows (0.01 arcmin = 0.6 arcsec).
#[test]
fn the_dead_band_is_the_unloaded_lost_motion_of_the_clearance_effect() {
    let crank = "{ from_deg: 0.0, to_deg: 36.0, steps: 5 }";
    let spec = torsion_spec(None, crank, "clearance, bearing", "");
    let s = &spec.scenes[0];
    let writes = Writes {
        json: true,
        report: false,
    };
    let r = scene::run(
        &spec,
        s,
        &scene::plan(&spec, s, writes),
        &Default::default(),
    )
    .unwrap();
    let lost = &r.discs[0]
        .clearance
        .as_ref()
        .unwrap()
        .backlash
        .as_ref()
        .unwrap()
        .lost_motion_rad;
    for (f, l) in curves(&r).figures.iter().zip(lost) {
        let (band, unloaded) = (units::arcsec(f.backlash_rad), units::arcsec(*l));
        assert!(
            (band - unloaded).abs() <= 1e-3,
            "{band} vs {unloaded} arcsec"
        );
    }
}

/// ISO 281 on a constant load, by hand: C = 12 000 N, F = 1000 N, p = 10/3: L10 = 12^(10/3)
/// = e^(8.28302·) = 3956.13 million revolutions; n = 1500 rpm, nc = 9: the crank turns at
/// 1500·10/9 rpm relative to the disc, 60·1500·10/9 = 100 000 revolutions an hour, so
/// L10h = 39 561.3 h. 1e-5 relative: the hand value's six digits.
#[test]
fn the_rating_life_of_a_constant_load_is_the_hand_value() {
    let force = vec![1000.0; 7];
    let p = equivalent_load(&force, 10.0 / 3.0);
    let life = life_h(p, 12_000.0, 10.0 / 3.0, 1500.0, 9);
    assert!((p - 1000.0).abs() <= 1e-9, "{p}");
    assert!((life - 39_561.3).abs() <= 1e-5 * 39_561.3, "{life}");
    // No load, no finite life: the unbounded life (the largest double), not ∞ in the outputs.
    assert_eq!(
        life_h(equivalent_load(&[0.0; 3], 3.0), 12_000.0, 3.0, 1500.0, 9),
        cycloid::model::results::UNBOUNDED_LIFE_H
    );
    // No samples: P = 0 as documented, not the mean's 0/0 (NaN).
    assert_eq!(equivalent_load(&[], 10.0 / 3.0), 0.0);
}

/// The speed is that of the crank relative to the disc, n·(1 + 1/nc): with one tooth (nc = 1)
/// the disc turns back at the crank's speed, so the life in hours is (1 + 1/9)/(1 + 1) of nc = 9.
#[test]
fn the_life_is_at_the_crank_speed_relative_to_the_disc() {
    assert_eq!(relative_speed_rpm(900.0, 9), 1000.0);
    let life = |nc| life_h(equivalent_load(&[2000.0], 3.0), 10_000.0, 3.0, 1000.0, nc);
    let ratio = life(1) / life(9);
    assert!((ratio - (10.0 / 9.0) / 2.0).abs() <= 1e-12, "{ratio}");
}

/// The equivalent load of a two-level load is the p-mean, not the mean: half the cycle at
/// 1000 N and half at 2000 N with p = 3 give P = ((1e9 + 8e9)/2)^(1/3) = 1650.964 N (the mean
/// would be 1500 N), and with p = 10/3 ((1000^p + 2000^p)/2)^(1/p) = 1000·((1 + 2^(10/3))/2)^0.3
/// = 1000·(5.53968)^0.3 = 1000·e^(0.3·1.711930) = 1671.27 N.
#[test]
fn the_equivalent_load_of_a_two_level_load_is_the_p_mean() {
    let cycle: Vec<f64> = (0..10)
        .map(|k| if k < 5 { 1000.0 } else { 2000.0 })
        .collect();
    let p3 = equivalent_load(&cycle, 3.0);
    assert!((p3 - 1650.964).abs() <= 1e-3, "{p3}");
    let p10 = equivalent_load(&cycle, 10.0 / 3.0);
    assert!((p10 - 1671.27).abs() <= 1e-2, "{p10}");
}

/// A spec with the paper's design, `reducer_extra` under `reducer:`, `scenes` and `limits`.
fn spec_text(reducer_extra: &str, scenes: &str, limits: &str) -> String {
    let mut spec = PaperSpec::new();
    if !reducer_extra.is_empty() {
        spec = spec.edit(
            "modification:\n",
            &format!("{reducer_extra}modification:\n"),
        );
    }
    spec.scenes(scenes).with(limits).text().to_string()
}

const ONE_ANGLE: &str = "{ from_deg: 0.0, to_deg: 36.0, steps: 1 }";
const BEARING: &str = "  crank_bearing: { dynamic_load_rating_n: 12000.0 }\n";

/// A loaded scene over the loaded period with a speed (`speed` is the YAML line, or empty).
fn loaded_item(speed: &str) -> String {
    format!(
        "  - name: rated\n    output_torque_nm: 10.0\n{speed}    crank: {{ from_deg: 0.0, \
         to_deg: 108.0, steps: 108 }}\n    effects: [bearing]\n"
    )
}

/// Each bad input is exit 2 naming its key (file:line:column) and the rule.
#[test]
fn bad_torsion_and_bearing_inputs_are_refused_with_the_rule() {
    let dir = Scratch::new("torsion-bad");
    let torsion = |rated: &str, steps: &str, extra: &str| {
        format!(
            "  - name: torsion\n    torque_sweep: {{ rated_nm: {rated}, steps: {steps} }}\n    \
             crank: {ONE_ANGLE}\n    effects: [bearing]\n{extra}"
        )
    };
    let life = "limits:\n  min_bearing_life_h: 1000.0\n";
    let cases: Vec<(String, &str, &str)> = vec![
        (
            spec_text("", &torsion("0.0", "4", ""), ""),
            "scenes[0].torque_sweep.rated_nm",
            "must be a positive number, got 0",
        ),
        (
            spec_text("", &torsion("20.0", "0", ""), ""),
            "scenes[0].torque_sweep.steps",
            "must be at least 1, got 0",
        ),
        (
            spec_text("", &torsion("20.0", "4", "    output_torque_nm: 5.0\n"), ""),
            "scenes[0].output_torque_nm",
            "give either `torque_sweep` or `output_torque_nm`, not both",
        ),
        (
            spec_text(
                "  crank_bearing: { dynamic_load_rating_n: 12000.0, life_exponent: 0.0 }\n",
                &loaded_item(""),
                "",
            ),
            "reducer.crank_bearing.life_exponent",
            "must be between 1 and 10, got 0",
        ),
        (
            spec_text(
                "  crank_bearing: { dynamic_load_rating_n: -1.0 }\n",
                &loaded_item(""),
                "",
            ),
            "reducer.crank_bearing.dynamic_load_rating_n",
            "must be a positive number, got -1",
        ),
        (
            spec_text(BEARING, &loaded_item("    input_speed_rpm: 0.0\n"), ""),
            "scenes[0].input_speed_rpm",
            "must be a positive number, got 0",
        ),
        (
            spec_text("", &loaded_item("    input_speed_rpm: 1500.0\n"), life),
            "limits.min_bearing_life_h",
            "a bearing life needs the bearing's rating",
        ),
        (
            spec_text(BEARING, &loaded_item(""), life),
            "scenes[0]",
            "it needs `input_speed_rpm`",
        ),
        (
            spec_text(
                BEARING,
                &loaded_item("    input_speed_rpm: 1500.0\n").replace("108.0,", "100.0,"),
                life,
            ),
            "scenes[0].crank",
            "is not a whole number of loaded periods (108.0°)",
        ),
    ];
    // An effect read off the loaded curves over the crank angle, which a locked input does
    // not turn through: it computed nothing and said nothing (the explanation listed it).
    let cases: Vec<(String, &str, &str)> = (cases.into_iter())
        .chain(["efficiency", "strength", "inertia"].map(|e| {
            let item = torsion("20.0", "4", "    input_speed_rpm: 1500.0\n");
            (
                spec_text(
                    "",
                    &item.replace("[bearing]", &format!("[bearing, {e}]")),
                    "",
                ),
                "scenes[0].effects",
                "which a scene with `torque_sweep` does not compute",
            )
        }))
        .collect();
    for (k, (text, key, rule)) in cases.iter().enumerate() {
        let name = format!("bad-{k}.yaml");
        dir.write(&name, text);
        let run = common::cycloid(&dir.path, &["check", &name]);
        let (code, _, err) = run.parts();
        assert_eq!(code, 2, "case {k}: {err}");
        assert!(err.contains(key) && err.contains(rule), "case {k}: {err}");
        assert!(
            err.starts_with(&format!("{name}:")),
            "case {k}: located: {err}"
        );
    }
}

/// `min_torsional_rigidity_nm_per_arcmin` fails a design below it (exit 1) and passes one
/// above (exit 0): the limit is set 10 % either side of the figure the same scene reports in
/// its results JSON, so the test checks the comparison and its direction, not the figure.
#[test]
fn a_rigidity_limit_fails_and_passes_as_expected() {
    let dir = Scratch::new("torsion-limit");
    let scenes = "  - name: torsion\n    torque_sweep: { rated_nm: 20.0, steps: 4 }\n    crank: \
                  { from_deg: 0.0, to_deg: 36.0, steps: 4 }\n    effects: [bearing]\n";
    dir.write("spec.yaml", spec_text("", scenes, ""));
    let run = common::cycloid(&dir.path, &["check", "spec.yaml", "--json", "r.json"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
    let json: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let figure = json["scenes"][0]["min_torsional_rigidity_nm_per_arcmin"]
        .as_f64()
        .expect("the scene's smallest rigidity");
    for (limit, code) in [(1.1 * figure, 1), (0.9 * figure, 0)] {
        let text = spec_text(
            "",
            scenes,
            &format!("limits:\n  min_torsional_rigidity_nm_per_arcmin: {limit:?}\n"),
        );
        dir.write("spec.yaml", &text);
        let (got, out, err) = common::cycloid(&dir.path, &["check", "spec.yaml"]).parts();
        assert_eq!(got, code, "limit {limit}: {out}{err}");
        assert!(
            out.contains("torsion/min_torsional_rigidity_nm_per_arcmin"),
            "{out}"
        );
        assert!(
            out.contains("hysteresis loss 0"),
            "the terminal says so: {out}"
        );
    }
    let (code, out, _) = cycloid_here(&["check", "specs/reducer-torsion.yaml"]).parts();
    assert_eq!(code, 0, "{out}");
    // The accuracy ladder sweeps the crank angle: a torsion scene is refused, not laddered.
    let args = [
        "accuracy",
        "specs/reducer-torsion.yaml",
        "--scene",
        "torsion",
    ];
    let (code, _, err) = cycloid_here(&args).parts();
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("is a torsion scene"), "{err}");
}
