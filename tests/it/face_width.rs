//! The contact along the face width (MODEL.md "Along the face width"; issue 29): crowning, a
//! tilt of the disc against the housing, and the face cut into slices.
//!
//! Expected values come from the model's definition, not from the code: the 2-D model (n = 1)
//! is the limit of a uniform face; a pure tilt makes the approach linear in z; a symmetric
//! crown a symmetric one; Winkler slices integrate to the roller force; the closed form is
//! the limit of fine slices; and the balance holds whatever the face.

use cycloid::contact::face_width::FaceWidth;
use cycloid::contact::law::{self, LineContact};
use cycloid::equilibrium::loaded::Model;
use cycloid::model::results::{FaceLoads, LoadedSweep};
use cycloid::model::{ContactLaw, Crowning, Face, Misalignment, Plan};
use cycloid::spec::Spec;

/// The paper's design (specs/reducer-loaded.yaml) with `extra` keys in its one scene and
/// `modification` keys after its modification, over `steps` crank angles of one mesh period.
fn spec(modification: &str, scene: &str, steps: usize) -> String {
    format!(
        "name: face\n\
         reducer:\n  teeth: 9\n  rollers: 10\n  eccentricity_mm: 2.0\n  \
         roller_circle_radius_mm: 30.0\n  roller_radius_mm: 3.0\n  face_width_mm: 8.0\n  \
         output_pins: {{ count: 6, circle_radius_mm: 18.0, pin_radius_mm: 3.0 }}\n  \
         material: {{ youngs_modulus_gpa: 206.0, poisson_ratio: 0.3 }}\n\
         modification:\n  shift_mm: 0.125\n  equidistant_mm: 0.1593\n{modification}\
         scenes:\n  - name: rated\n    output_torque_nm: 10.0\n    \
         crank: {{ from_deg: 0.0, to_deg: 36.0, steps: {steps} }}\n    effects: [bearing]\n{scene}"
    )
}

fn parse(text: &str) -> Spec {
    cycloid::spec::parse("face.yaml", text).unwrap_or_else(|e| panic!("{e}"))
}

/// The loaded sweep of the spec's one scene (rollers, pins, bearing).
fn run(spec: &Spec) -> LoadedSweep {
    let scene = &spec.scenes[0];
    let plan = Plan::for_scene(scene);
    let model = Model::new(&spec.design, &spec.modification, scene, &plan);
    crate::common::one_disc_sweep(&model, &scene.crank_rad, true)
        .unwrap_or_else(|f| panic!("{f:?}"))
        .0
}

fn face_of(l: &LoadedSweep) -> &FaceLoads {
    l.rollers.as_ref().unwrap().face.as_ref().unwrap()
}

/// The linear law's stiffness per unit length k/B = (π/4)·E*, N/mm per mm (paper Eq. 9).
fn k_per_mm() -> f64 {
    let e = 206000.0 / (2.0 * (1.0 - 0.09));
    0.25 * std::f64::consts::PI * e
}

/// Slices on a straight, aligned disc are the 2-D model bit for bit, and every slice carries
/// the roller's mean line load F/B (n = 1 is today's model; a uniform face has no z).
#[test]
fn slices_without_crown_or_tilt_equal_the_2d_model() {
    for law in ["paper_linear", "hertz_nonlinear"] {
        let plain = parse(&spec("", &format!("    contact_law: {law}\n"), 36));
        let sliced = parse(&spec(
            "",
            &format!("    contact_law: {law}\n    face_slices: 8\n"),
            36,
        ));
        let (a, b) = (run(&plain), run(&sliced));
        let (ra, rb) = (a.rollers.as_ref().unwrap(), b.rollers.as_ref().unwrap());
        assert_eq!(ra.lag_rad, rb.lag_rad, "{law}");
        assert_eq!(ra.force_n, rb.force_n, "{law}");
        assert_eq!(ra.pressure_mpa, rb.pressure_mpa, "{law}");
        assert_eq!(
            a.pins.as_ref().unwrap().force_n,
            b.pins.as_ref().unwrap().force_n
        );
        assert!(ra.face.is_none());
        let face = face_of(&b);
        for i in 0..face.line_load_n_per_mm.len() {
            for (k, q) in face.angles(i).enumerate() {
                assert_eq!(q.len(), 8);
                let mean = rb.force_n[i][k] / 8.0;
                assert!(
                    q.iter().all(|&v| v == mean),
                    "{law} roller {i} angle {k}: {q:?}"
                );
            }
        }
        for (k, &f) in face.face_load_factor.iter().enumerate() {
            assert!((f - 1.0).abs() < 1e-12, "{law} angle {k}: factor {f}");
        }
    }
}

/// A pure tilt about x: the approach along the face is d + t·z, so over the slices where a
/// roller's contact is closed throughout its line load (the slice's mean) is linear in z (zero
/// second difference, to round-off of the line loads themselves), with slope (k/B)·t,
/// t = n_i·(θy, −θx) = −θx·n_y. The slice where the contact opens is loaded over part of its
/// width only and left out. With n_i taken as the
/// first-order normal (from the pitch point e·np·e_φ to the roller centre, MODEL.md) the slope
/// is predicted within 5 %: the modified profile's normal at the loaded pose turns from it by
/// a few degrees at most on this design (ΔRp, ΔRrp of 0.13–0.16 mm against e = 2 mm).
#[test]
fn a_pure_tilt_gives_a_line_load_linear_in_z() {
    let theta_x = 0.5e-3;
    let s = parse(&spec(
        "",
        "    misalignment: { about_x_mrad: 0.5 }\n    face_slices: 40\n",
        12,
    ));
    let l = run(&s);
    let face = face_of(&l);
    let h = 8.0 / 40.0;
    let mut checked = 0;
    for i in 0..face.line_load_n_per_mm.len() {
        let unit = (std::f64::consts::TAU * i as f64 / 10.0).sin_cos();
        for (k, q) in face.angles(i).enumerate() {
            // The loaded slices but the one where the contact opens (a linear approach
            // crosses zero once: the loaded slices are consecutive).
            let loaded: Vec<usize> = (0..40)
                .filter(|&s| {
                    q[s] > 0.0 && (s == 0 || q[s - 1] > 0.0) && (s == 39 || q[s + 1] > 0.0)
                })
                .collect();
            // Only rollers loaded over three slices or more show a slope and a curvature.
            if loaded.len() < 3 || loaded.len() < 40 && loaded.len() < 6 {
                continue;
            }
            let peak = q.iter().copied().fold(0.0, f64::max);
            for w in loaded.windows(3) {
                if w[2] - w[0] != 2 {
                    continue;
                }
                let second = q[w[0]] - 2.0 * q[w[1]] + q[w[2]];
                assert!(
                    second.abs() <= 1e-9 * peak,
                    "roller {i} angle {k}: second difference {second:e} of {peak}"
                );
            }
            let slope = (q[loaded[1]] - q[loaded[0]]) / h;
            let phi = s.scenes[0].crank_rad[k];
            let (ex, ey) = (phi.cos(), phi.sin());
            let (nx, ny) = (30.0 * unit.1 - 20.0 * ex, 30.0 * unit.0 - 20.0 * ey);
            let n_y = ny / nx.hypot(ny);
            let predicted = k_per_mm() * (-theta_x * n_y);
            assert!(
                (slope - predicted).abs()
                    <= 0.05 * predicted.abs().max(1e-3 * k_per_mm() * theta_x),
                "roller {i} angle {k}: slope {slope} N/mm², predicted {predicted}"
            );
            checked += 1;
        }
    }
    assert!(checked > 10, "only {checked} contacts checked");
}

/// The circular crown of `radius` flat over |z| ≤ `start` (MODEL.md), written out here.
fn crown(z: f64, radius: f64, start: f64) -> f64 {
    let w = (z.abs() - start).max(0.0);
    w * w / (2.0 * radius)
}

fn contact(length_mm: f64) -> LineContact {
    let e = 206000.0 / (2.0 * (1.0 - 0.09));
    LineContact {
        contact_modulus_mpa: e,
        compliance_per_mpa: [(1.0 - 0.09) / 206000.0; 2],
        length_mm,
        radii_mm: [30.0, 3.0],
        effective_radius_mm: 1.0 / (1.0 / 30.0 + 1.0 / 3.0),
    }
}

/// The slices' line loads where the loaded interval ends exactly on a slice edge, inside a
/// slice, and with one slice, against their means worked by hand: a straight face B = 8 mm,
/// t = 1e-3, a(z) = d + t·z. With d = 0 the contact opens at z = 0 (an edge of 4 slices of
/// 2 mm): slices [0, 2] and [2, 4] carry the means t·1 and t·3, the others nothing; with d = 2t
/// at z = −2 (an edge): t, 3t, 5t over the three slices from −2; with d = t at z = −1 (inside
/// a slice): ∫ t·(z + 1) dz over [−1, 0] / 2 = t/4, then 2t and 4t; one slice: the face's mean
/// (t/B)·∫ (z + 4) dz over [−4, 4] = 4t with d = 4t (loaded end to end but for z = −4).
/// Each times k/B. Round-off of a few terms of size t·B: 1e-12 relative.
#[test]
fn line_loads_where_the_contact_opens_on_a_slice_edge_inside_one_and_with_one_slice() {
    let c = contact(8.0);
    let per_mm = law::paper_linear_stiffness(&c) / 8.0;
    let t = 1e-3;
    for (d, slices, expected) in [
        (0.0, 4, vec![0.0, 0.0, 1.0, 3.0]),
        (2.0 * t, 4, vec![0.0, 1.0, 3.0, 5.0]),
        (t, 4, vec![0.0, 0.25, 2.0, 4.0]),
        (4.0 * t, 1, vec![4.0]),
    ] {
        let face = Face {
            slices,
            ..Face::default()
        };
        let fw = FaceWidth::new(&face, 8.0, c.contact_modulus_mpa);
        let mut q = vec![f64::NAN; slices];
        let peak = fw.line_loads(ContactLaw::PaperLinear, &c, d, t, &mut q);
        for (s, (&got, want)) in q.iter().zip(&expected).enumerate() {
            let want = want * t * per_mm;
            assert!(
                (got - want).abs() <= 1e-12 * per_mm * t * 8.0,
                "d {d} n {slices} slice {s}: {got} vs {want}"
            );
        }
        let top = expected.iter().copied().fold(0.0, f64::max) * t * per_mm;
        assert!(
            (peak - top).abs() <= 1e-12 * per_mm * t * 8.0,
            "peak {peak} vs {top}"
        );
    }
}

/// With the linear law the closed form is the limit of fine Winkler slices: the force equals a
/// midpoint sum over 100,000 slices written out here (the sum's error is O(h²) on each smooth
/// piece and at the clip's two corners, h = 8e-5 mm: below 1e-7 of the force), for straight,
/// crowned and flat-middle crowns, tilts of both signs, contacts open at one end, at both and
/// closed over the whole face; and its stiffness equals a central finite difference of its
/// force (step 1e-8 mm, error O(step²·F''') and the force's round-off ~1e-16·F/step: 1e-6).
#[test]
fn the_closed_form_equals_fine_slices_and_its_stiffness_the_derivative() {
    let width = 8.0;
    let c = contact(width);
    let k = law::paper_linear_stiffness(&c);
    let cases = [
        // (radius, start, d mm, t rad)
        (f64::INFINITY, 0.0, 0.5e-3, 0.3e-3),
        (f64::INFINITY, 0.0, 0.2e-3, -0.4e-3),
        (1000.0, 2.0, 1.0e-3, 0.1e-3),
        (1000.0, 2.0, 0.5e-3, -0.3e-3),
        (500.0, 0.0, 4.0e-3, 0.2e-3),
        (200.0, 1.0, 0.1e-3, 0.05e-3),
        (1000.0, 3.5, -0.2e-3, 0.3e-3),
    ];
    for &(radius, start, d, t) in &cases {
        let crowning = if radius.is_finite() {
            Crowning::Circular {
                radius_mm: radius,
                start_mm: start,
            }
        } else {
            Crowning::None
        };
        let face = Face {
            crowning,
            misalignment: Misalignment::default(),
            slices: 20,
        };
        let fw = FaceWidth::new(&face, width, c.contact_modulus_mpa);
        let closed = fw.force(ContactLaw::PaperLinear, &c, d, t);
        let n = 100_000;
        let h = width / n as f64;
        let crowned = |z: f64| {
            if radius.is_finite() {
                crown(z, radius, start)
            } else {
                0.0
            }
        };
        let sum: f64 = (0..n)
            .map(|s| {
                let z = -0.5 * width + (s as f64 + 0.5) * h;
                (k / n as f64) * (d - crowned(z) + t * z).max(0.0)
            })
            .sum();
        assert!(
            (closed.force_n - sum).abs() <= 1e-7 * sum.max(1e-3),
            "R {radius} z0 {start} d {d} t {t}: closed {} slices {sum}",
            closed.force_n
        );
        let step = 1e-8;
        let fd = (fw.force(ContactLaw::PaperLinear, &c, d + step, t).force_n
            - fw.force(ContactLaw::PaperLinear, &c, d - step, t).force_n)
            / (2.0 * step);
        assert!(
            (closed.stiffness_n_per_mm - fd).abs() <= 1e-6 * k,
            "R {radius} z0 {start} d {d} t {t}: stiffness {} finite difference {fd}",
            closed.stiffness_n_per_mm
        );
    }
}

/// Johnson's law per unit length: its approach depends on F/L alone (the half-width does), so
/// n slices of length B/n at the same approach carry F(B, d) together: on a uniform face the
/// sum over slices is the 2-D law (to the inversion's tolerance, 1e-12 relative).
#[test]
fn johnson_slices_of_a_uniform_face_sum_to_the_2d_law() {
    let c = contact(8.0);
    for &d in &[1e-5, 1e-4, 1e-3] {
        let face = Face {
            slices: 13,
            ..Face::default()
        };
        let fw = FaceWidth::new(&face, 8.0, c.contact_modulus_mpa).by_slices();
        let sliced = fw.force(ContactLaw::HertzNonlinear, &c, d, 0.0);
        let whole = law::force(ContactLaw::HertzNonlinear, &c, d);
        assert!(
            (sliced.force_n - whole.force_n).abs() <= 1e-12 * whole.force_n,
            "d {d}: {} vs {}",
            sliced.force_n,
            whole.force_n
        );
    }
}

/// A crown symmetric about the middle of the face (circular with a flat middle, and
/// logarithmic) without a tilt gives a line load symmetric about the middle: slice s and slice
/// n − 1 − s sit at ±z (to the rounding of their centres, 1e-12 of the peak).
#[test]
fn a_symmetric_crown_gives_a_symmetric_line_load() {
    for (crowning, law) in [
        (
            "  crowning: { kind: circular, radius_mm: 500.0, start_mm: 1.5 }\n",
            "paper_linear",
        ),
        (
            "  crowning: { kind: logarithmic, design_load_n: 400.0, end_drop_mm: 0.004 }\n",
            "hertz_nonlinear",
        ),
    ] {
        let s = parse(&spec(
            crowning,
            &format!("    contact_law: {law}\n    face_slices: 15\n"),
            12,
        ));
        let l = run(&s);
        let face = face_of(&l);
        let mut crowned = false;
        for i in 0..face.line_load_n_per_mm.len() {
            for q in face.angles(i) {
                let peak = q.iter().copied().fold(0.0, f64::max);
                for s in 0..15 {
                    assert!((q[s] - q[14 - s]).abs() <= 1e-12 * peak, "{law}: {q:?}");
                }
                crowned |= peak > 0.0 && q[0] < 0.99 * peak;
            }
        }
        assert!(crowned, "{law}: the crown never showed in the line load");
    }
}

/// The line loads times the slice width sum to the roller force (MODEL.md: a slice's line load
/// is its force/(B/n)): to round-off (1e-12 of the force: a sum of 24 terms, each a few ulp)
/// for Johnson's law, whose force is the sum of its slices, and for the linear law's closed
/// form, whose slices are the face's integral over each slice; on a crowned disc tilted about
/// both axes.
#[test]
fn line_loads_times_slice_width_sum_to_the_roller_force() {
    let crowning = "  crowning: { kind: circular, radius_mm: 800.0, start_mm: 1.0 }\n";
    for law in ["paper_linear", "hertz_nonlinear"] {
        let s = parse(&spec(
            crowning,
            &format!(
                "    contact_law: {law}\n    misalignment: {{ about_x_mrad: 0.3, about_y_mrad: -0.2 }}\n    face_slices: 24\n"
            ),
            12,
        ));
        let l = run(&s);
        let r = l.rollers.as_ref().unwrap();
        let face = face_of(&l);
        let h = 8.0 / 24.0;
        for i in 0..face.line_load_n_per_mm.len() {
            for (k, q) in face.angles(i).enumerate() {
                let sum: f64 = q.iter().map(|v| v * h).sum();
                let f = r.force_n[i][k];
                let tol = 1e-12 * f;
                assert!(
                    (sum - f).abs() <= tol,
                    "{law} roller {i} angle {k}: Σq·h {sum} vs F {f} (tolerance {tol:e})"
                );
            }
        }
    }
}

/// The closed form against the Winkler model of 200 slices it is the limit of, over the whole
/// balance (rollers, pins, bearing; the pins see no tilt, the flange tilting with the disc) on a crowned disc tilted about both axes and on a pure
/// tilt: the targets, lag within 0.05 arcsec, face load factor within 1 % and roller
/// forces within 0.2 % of the largest force.
#[test]
fn the_closed_form_balance_matches_200_winkler_slices() {
    for (crowning, tilt) in [
        (
            "  crowning: { kind: circular, radius_mm: 1000.0, start_mm: 2.0 }\n",
            "{ about_x_mrad: 0.3, about_y_mrad: 0.3 }",
        ),
        ("", "{ about_x_mrad: 0.3 }"),
    ] {
        let s = parse(&spec(
            crowning,
            &format!("    misalignment: {tilt}\n    face_slices: 200\n"),
            36,
        ));
        let scene = &s.scenes[0];
        let plan = Plan::for_scene(scene);
        let closed_model = Model::new(&s.design, &s.modification, scene, &plan);
        let mut sliced_model = closed_model.clone();
        sliced_model.rollers = sliced_model
            .rollers
            .map(|r| r.with_face_by_slices(&scene.face));
        let go = |m: &Model| {
            crate::common::one_disc_sweep(m, &scene.crank_rad, true)
                .unwrap_or_else(|f| panic!("{f:?}"))
        };
        let (closed, sliced) = (go(&closed_model), go(&sliced_model));
        let (rc, rs) = (closed.0.rollers.unwrap(), sliced.0.rollers.unwrap());
        let arcsec = 180.0 / std::f64::consts::PI * 3600.0;
        let peak = rc.force_n.iter().flatten().copied().fold(0.0, f64::max);
        for k in 0..scene.crank_rad.len() {
            let lag = (rc.lag_rad[k] - rs.lag_rad[k]).abs() * arcsec;
            assert!(lag <= 0.05, "{tilt} angle {k}: lags differ by {lag} arcsec");
            for i in 0..10 {
                let df = (rc.force_n[i][k] - rs.force_n[i][k]).abs();
                assert!(
                    df <= 2e-3 * peak,
                    "{tilt} roller {i} angle {k}: {df} N of {peak}"
                );
            }
            let (fc, fs) = (
                rc.face.as_ref().unwrap().face_load_factor[k],
                rs.face.as_ref().unwrap().face_load_factor[k],
            );
            assert!(
                (fc - fs).abs() <= 0.01 * fs,
                "{tilt} angle {k}: factor {fc} vs {fs}"
            );
        }
    }
}

/// The balance holds with a tilt: the residual of the paper's Eqs. 12–14, evaluated
/// independently of the solve (`equilibrium::residual`), stays at the solver's 1e-9 with the
/// linear law, Johnson's slices, a compliant bearing and two discs; no force is NaN.
#[test]
fn the_balance_holds_with_a_tilt() {
    let crowning = "  crowning: { kind: circular, radius_mm: 1000.0, start_mm: 2.0 }\n";
    for extra in [
        "",
        "    contact_law: hertz_nonlinear\n",
        "    bearing_stiffness_n_per_mm: 2.0e5\n",
    ] {
        let s = parse(&spec(
            crowning,
            &format!(
                "{extra}    misalignment: {{ about_x_mrad: 0.3, about_y_mrad: 0.3 }}\n    face_slices: 10\n"
            ),
            24,
        ));
        let l = run(&s);
        let worst = largest_residual(&l);
        assert!(worst <= 1e-9, "{extra}: residual {worst:e}");
        let r = l.rollers.as_ref().unwrap();
        assert!(r.force_n.iter().flatten().all(|f| f.is_finite()));
    }
    // Two discs share the torque through the same pins, each tilted alike.
    let two = spec(
        crowning,
        "    misalignment: { about_x_mrad: 0.3, about_y_mrad: 0.3 }\n    face_slices: 10\n",
        24,
    )
    .replace(
        "  face_width_mm: 8.0\n",
        "  face_width_mm: 8.0\n  discs: 2\n",
    );
    let s = parse(&two);
    let plan = Plan::for_scene(&s.scenes[0]);
    let r = cycloid::engine::scene::run(&s, &s.scenes[0], &plan, &Default::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.discs.len(), 2);
    for disc in &r.discs {
        let worst = largest_residual(&disc.loaded);
        assert!(worst <= 1e-9, "two discs: residual {worst:e}");
        assert!(disc.loaded.rollers.as_ref().unwrap().face.is_some());
    }
}

/// At zero output torque a tilted disc rests free in its backlash: MODEL.md reports the limit
/// T → 0⁺, the lag at which the nearest contact just closes. With a rigid bearing and no torque
/// the rollers' moment Σ F·l must be zero, and on the loaded flank every arm has one sign, so
/// every roller force is zero (the 2-D model's answer too) and the balance's residual is
/// round-off; and the limit T → 0⁺ is continuous: at 1e-12 N·m the lag has moved from the
/// touching lag by about sqrt(T) of a triangular contact (~1e-5 arcsec here, the sqrt of 1e-3
/// of the 2.6e-4 arcsec a 1e-9 N·m load moves it), so 1e-3 arcsec separates them. Before, the
/// zero-torque solve put the disc at the 2-D touching lag (the gaps at the middle of the
/// face), 17.2 arcsec past the tilted face's first contact: rollers pressed with 250 N at no
/// torque, the residual 1.
#[test]
fn a_tilted_disc_at_zero_torque_touches_and_carries_nothing() {
    let crowning = "  crowning: { kind: circular, radius_mm: 1000.0, start_mm: 2.0 }\n";
    let log = "  crowning: { kind: logarithmic, design_load_n: 500.0, end_drop_mm: 0.002 }\n";
    let tilt = "    misalignment: { about_x_mrad: 0.3, about_y_mrad: 0.2 }\n    face_slices: 8\n";
    for (modification, law) in [
        ("", ""),
        (crowning, ""),
        (log, ""),
        ("", "    contact_law: hertz_nonlinear\n"),
    ] {
        let at = |torque: &str| {
            let text = spec(modification, &format!("{law}{tilt}"), 12).replace(
                "output_torque_nm: 10.0",
                &format!("output_torque_nm: {torque}"),
            );
            run(&parse(&text))
        };
        let (zero, tiny) = (at("0.0"), at("1.0e-12"));
        let what = format!("{modification}{law}");
        let rollers = zero.rollers.as_ref().unwrap();
        let most = rollers
            .force_n
            .iter()
            .flatten()
            .copied()
            .fold(0.0, f64::max);
        assert!(
            most <= 1e-9,
            "{what}: a roller carries {most} N at zero torque"
        );
        let residual = largest_residual(&zero);
        assert!(
            residual <= 1e-9,
            "{what}: residual {residual:e} at zero torque"
        );
        let near = tiny.rollers.as_ref().unwrap();
        for (a, (l0, l1)) in rollers.lag_rad.iter().zip(&near.lag_rad).enumerate() {
            let arcsec = (l0 - l1).abs().to_degrees() * 3600.0;
            assert!(
                arcsec <= 1e-3,
                "{what}: angle {a}: lag at 0 off that at 0⁺ by {arcsec} arcsec"
            );
        }
    }
}

/// Bad values are refused at their key's file:line:column with the rule, exit 2.
#[test]
fn bad_face_values_are_refused_where_they_are_written() {
    let cases = [
        (
            "  crowning: { kind: circular, radius_mm: 0.0 }\n",
            "    face_slices: 4\n",
            "modification.crowning.radius_mm",
            "positive",
        ),
        (
            "  crowning: { kind: circular, radius_mm: 100.0, start_mm: 4.0 }\n",
            "    face_slices: 4\n",
            "modification.crowning.start_mm",
            "[0, B/2)",
        ),
        (
            "  crowning: { kind: circular, radius_mm: 100.0, start_mm: -1.0 }\n",
            "    face_slices: 4\n",
            "modification.crowning.start_mm",
            "[0, B/2)",
        ),
        (
            "  crowning: { kind: barrel, radius_mm: 100.0 }\n",
            "    face_slices: 4\n",
            "modification.crowning.kind",
            "unknown crowning",
        ),
        (
            "  crowning: { kind: logarithmic, design_load_n: 400.0, end_drop_mm: 0.004, crowned_fraction: 1.5 }\n",
            "    face_slices: 4\n",
            "modification.crowning.crowned_fraction",
            "(0, 1]",
        ),
        ("", "    face_slices: 0\n", "scenes[0].face_slices", "from 1 to"),
        (
            "",
            "    misalignment: { about_x_mrad: .nan }\n    face_slices: 4\n",
            "scenes[0].misalignment.about_x_mrad",
            "finite",
        ),
        (
            "",
            "    misalignment: { about_y_mrad: .inf }\n    face_slices: 4\n",
            "scenes[0].misalignment.about_y_mrad",
            "finite",
        ),
        (
            "",
            "    misalignment: { about_x_mrad: 0.3 }\n",
            "scenes[0].misalignment",
            "face_slices: 2",
        ),
        (
            "  crowning: { kind: circular, radius_mm: 100.0 }\n",
            "    contact_law: hertz_nonlinear\n    face_slices: 1\n",
            "scenes[0].face_slices",
            "face_slices: 2",
        ),
        // A golden of a face quantity in a scene that does not resolve the face: the rule
        // with one space before its key (the message once held a run of 22 spaces).
        (
            "",
            "golden:\n  - scene: rated\n    quantity: face_load_factor\n    \
             file: face_load_factor.csv\n    tolerance: { abs: 0.01 }\n",
            "golden[0].quantity",
            "face width; give it `face_slices: 2` or more",
        ),
    ];
    let dir = crate::common::Scratch::new("face-bad");
    for (modification, scene, key, rule) in cases {
        let text = spec(modification, scene, 12);
        crate::common::assert_refused_at(&dir, "face.yaml", &text, key, rule);
    }
}

/// The sweep's shortcuts (warm starts, rollers proven out of reach and not evaluated) give
/// the answer of each angle solved alone with every roller evaluated (`solve_angle`): on a
/// tilted face a roller whose 2-D gap is open may still touch at one end of the face, which the
/// proof of reach must count. Lags agree to the solver's tolerance (1e-9 of the lag's scale,
/// 1e-12 rad here), forces to 1e-6 of the largest.
#[test]
fn the_sweep_matches_each_angle_solved_alone_on_a_tilted_face() {
    use cycloid::equilibrium::angle::solve_angle;
    use cycloid::equilibrium::loaded::AngleSolution;
    let s = parse(&spec(
        "",
        "    misalignment: { about_x_mrad: 1.0, about_y_mrad: -1.0 }\n    face_slices: 10\n",
        72,
    ));
    let scene = &s.scenes[0];
    let plan = Plan::for_scene(scene);
    let model = Model::new(&s.design, &s.modification, scene, &plan);
    let swept = crate::common::one_disc_sweep(&model, &scene.crank_rad, true).unwrap();
    let r = swept.0.rollers.unwrap();
    let peak = r.force_n.iter().flatten().copied().fold(0.0, f64::max);
    for (k, &phi) in scene.crank_rad.iter().enumerate() {
        let alone = solve_angle(&model, phi, &AngleSolution::default()).unwrap();
        let lag = alone.lag_rad.unwrap();
        assert!(
            (lag - r.lag_rad[k]).abs() <= 1e-12,
            "angle {k}: {lag} vs {}",
            r.lag_rad[k]
        );
        for (i, st) in alone.rollers.iter().enumerate() {
            assert!(
                (st.force_n - r.force_n[i][k]).abs() <= 1e-6 * peak,
                "angle {k} roller {i}: {} vs {}",
                st.force_n,
                r.force_n[i][k]
            );
        }
    }
}

/// The face load factor is at least 1 (MODEL.md: the peak slice's line load over its roller's
/// mean F/B): a slice's line load is its force/(B/n) for every law, so the n line loads times
/// B/n sum to F, their mean is F/B and their largest is at least that. Checked on the linear
/// law's closed form (slices the face's integral over each slice) and on Johnson's slices, on
/// 3,000 random crowns, tilts, approaches and slice counts (contacts open at one end, at both,
/// loaded over a sliver of one slice), the closed form's F checked against a fine midpoint sum
/// written out here; the line loads' sum is F to round-off: 1e-12 of the
/// approach's scale (|d| + |t|·B/2 + the crown's end drop) times k, every integral being
/// formed from terms that large. Read at the slice centres instead, a contact loaded over
/// less than half its end slice has no line load at all and a factor of 0.
#[test]
fn the_face_load_factor_is_at_least_one() {
    let width = 8.0;
    let c = contact(width);
    let k = law::paper_linear_stiffness(&c);
    let mut uniform = uniform_sequence(0x9e37_79b9_7f4a_7c15);
    let mut slivers = 0;
    for case in 0..3000 {
        let radius = 100.0 + 2000.0 * uniform();
        let start = 4.0 * uniform();
        let crowned = uniform() < 0.7;
        let t = (uniform() - 0.5) * 2e-3;
        let slices = 2 + (uniform() * 30.0) as usize;
        let drop = if crowned {
            (4.0 - start).powi(2) / (2.0 * radius)
        } else {
            0.0
        };
        // From open but for a sliver at one end to closed over the whole face.
        let d = -t.abs() * 4.0 + (t.abs() * 8.0 + drop + 2e-3) * uniform().powi(3);
        let face = Face {
            crowning: if crowned {
                Crowning::Circular {
                    radius_mm: radius,
                    start_mm: start,
                }
            } else {
                Crowning::None
            },
            misalignment: Misalignment::default(),
            slices,
        };
        let law = if case % 3 == 2 {
            ContactLaw::HertzNonlinear
        } else {
            ContactLaw::PaperLinear
        };
        let fw = FaceWidth::new(&face, width, c.contact_modulus_mpa);
        let f = fw.force(law, &c, d, t).force_n;
        let mut q = vec![f64::NAN; slices];
        let top = fw.line_loads(law, &c, d, t, &mut q);
        let h = width / slices as f64;
        let sum: f64 = q.iter().map(|v| v * h).sum();
        let tol = 1e-12 * k * (d.abs() + t.abs() * 0.5 * width + drop) + 1e-12 * f;
        let what = format!("{law:?} R {radius} z0 {start} d {d} t {t} n {slices}");
        assert!((sum - f).abs() <= tol, "{what}: Σq·h {sum} vs F {f}");
        if law == ContactLaw::PaperLinear {
            // The closed form against a midpoint sum over m = 20,000 sections written out
            // here: its error is at most (k/B)·(B·h²/24·max|a''| + 2·(h²/8)·max|a'|) (the
            // smooth parts and the two corners where the contact opens), h = B/m,
            // |a''| ≤ 2c = 1/Rc, |a'| ≤ |t| + (B/2 − z0)/Rc.
            let m = 20_000;
            let hm = width / m as f64;
            let fine: f64 = (0..m)
                .map(|j| {
                    let z = -0.5 * width + (j as f64 + 0.5) * hm;
                    (k / m as f64) * (d - face_crown(&face, z) + t * z).max(0.0)
                })
                .sum();
            let curvature = if crowned { 1.0 / radius } else { 0.0 };
            let slope = t.abs() + curvature * (0.5 * width - start);
            let bound =
                (k / width) * (width * hm * hm / 24.0 * curvature + hm * hm / 4.0 * slope) + tol;
            assert!(
                (f - fine).abs() <= bound,
                "{what}: F {f} vs fine sum {fine}"
            );
            // Each slice's line load against a midpoint sum over its own 400 sections, the
            // same bound per slice of width h (sections hs = h/400), divided by h.
            let ms = 400;
            let hs = h / ms as f64;
            for (j, &qj) in q.iter().enumerate() {
                let lo = -0.5 * width + j as f64 * h;
                let fine: f64 = (0..ms)
                    .map(|i| {
                        let z = lo + (i as f64 + 0.5) * hs;
                        (d - face_crown(&face, z) + t * z).max(0.0)
                    })
                    .sum::<f64>()
                    * (k / width)
                    / ms as f64;
                let bound = (k / width)
                    * (hs * hs / 24.0 * curvature + hs * hs / (4.0 * h) * slope)
                    + tol / h;
                assert!(
                    (qj - fine).abs() <= bound,
                    "{what}: slice {j} line load {qj} vs fine mean {fine}"
                );
            }
        }
        let peak = q.iter().copied().fold(0.0, f64::max);
        assert!(
            peak * width >= f - tol,
            "{what}: peak line load {peak} below the mean {}",
            f / width
        );
        // The peak line_loads returns is the largest of the loads it wrote, exactly.
        assert_eq!(peak, top, "{what}");
        // Contacts loaded only within the end slice's outer half.
        let centre = |z: f64| d - face_crown(&face, z) + t * z;
        if f > 0.0 && centre(0.5 * width - 0.5 * h) <= 0.0 && centre(-0.5 * width + 0.5 * h) <= 0.0
        {
            slivers += 1;
        }
    }
    assert!(
        slivers > 20,
        "only {slivers} contacts loaded between slice centres"
    );
}

/// The closing a tilt can add to the 2-D approach (`FaceWidth::reach_mm`, from which the sweep
/// proves a roller out of contact and does not evaluate it) is the largest of
/// |θ|·|z| − crown(z) over the face: not below it (a roller touching at one end would be
/// skipped) and above it by no more than sampling misses (a looser bound evaluates rollers
/// that cannot touch). On 2,000 random circular crowns (some starting beyond the face's end),
/// straight faces and tilts, against 40,001 points of the face: the closing's slope is at most
/// |θ| (crown' ≥ 0 for z ≥ 0), so the sample just below its peak is within |θ|·Δz of it;
/// 1e-15 mm covers round-off.
#[test]
fn the_reach_of_a_tilt_is_the_largest_closing_over_the_face() {
    let width = 8.0;
    let mut uniform = uniform_sequence(0x2545_f491_4f6c_dd1d);
    let m = 40_000;
    let dz = width / m as f64;
    for _ in 0..2000 {
        let crowning = if uniform() < 0.8 {
            Crowning::Circular {
                radius_mm: 50.0 + 5000.0 * uniform(),
                start_mm: 5.0 * uniform(),
            }
        } else {
            Crowning::None
        };
        let misalignment = Misalignment {
            about_x_rad: (uniform() - 0.5) * 4e-3,
            about_y_rad: (uniform() - 0.5) * 4e-3,
        };
        let theta = misalignment.about_x_rad.hypot(misalignment.about_y_rad);
        let face = Face {
            crowning,
            misalignment,
            slices: 10,
        };
        let reach = FaceWidth::new(&face, width, 100_000.0).reach_mm;
        let sampled = (0..=m)
            .map(|j| {
                let z = -0.5 * width + j as f64 * dz;
                theta * z.abs() - face_crown(&face, z)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            reach >= sampled - 1e-15 && reach <= sampled + theta * dz + 1e-15,
            "{crowning:?} θ {theta}: reach {reach} vs the sampled largest closing {sampled}"
        );
    }
}

/// xorshift64 from `seed`: a fixed sequence of uniform numbers in [0, 1).
fn uniform_sequence(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The crown of `face` at z (`crown`, or 0 for a straight disc).
fn face_crown(face: &Face, z: f64) -> f64 {
    match face.crowning {
        Crowning::Circular {
            radius_mm,
            start_mm,
        } => crown(z, radius_mm, start_mm),
        _ => 0.0,
    }
}

/// The logarithmic crown is Fujiwara & Kawase's profile (NTN Technical Review 75, 2007; Trans.
/// JSME C 72, 2006), with a = B/2 and y = |z|:
///   crown(y) = A·ln(1 / (1 − (1 − e^{−z_m/A})·((y − (1 − K2)·a)/(K2·a))²)), y > (1 − K2)·a,
///   A = 2·K1·Q/(π·B·E'), 2/E' = (1 − ν1²)/E1 + (1 − ν2²)/E2 (E' = 2·E*),
/// and K2 = 1, z_m → ∞ is Johns & Gohar's A·ln(1/(1 − (2z/B)²)). Values worked by hand for
/// Q = 1000 N, K1 = 1, B = 8 mm, E* = 100 000 MPa: A = 2000/(π·8·200 000) mm
/// = 3.978873577297384e-4 mm.
/// - K2 = 0.5, z_m = 5 µm: flat for |z| ≤ 2 mm; z_m/A = 12.566, so 1 − e^{−z_m/A}
///   = 0.9999965126576438; at z = ±3 mm the ratio is ½, ln(1/(1 − 0.99999651·¼)) = 0.28768
///   and the crown 1.144645971511779e-4 mm; at z = 3.5 mm (ratio ¾) 3.289231691623118e-4 mm;
///   at the face's ends exactly z_m.
/// - K2 = 1, z_m = 1 mm (e^{−2513} = 0): Johns & Gohar's A·ln(4/3) = 1.1446505967405424e-4 mm at
///   z = 2 mm.
///
/// Tolerance 1e-13 mm (1e-10 µm): the round-off of 1 − (1 − e^{−z_m/A}) at the face's ends,
/// ε·A/e^{−z_m/A} ≈ 1.3e-14 mm; inside, the logarithm's argument is near ¾ and the round-off
/// is ε·A ≈ 1e-19 mm.
#[test]
fn the_logarithmic_crown_is_fujiwara_and_kawases_profile_by_hand() {
    let crown = |k2: f64, end_drop_mm: f64| {
        let face = Face {
            crowning: Crowning::Logarithmic {
                design_load_n: 1000.0,
                end_drop_mm,
                load_coefficient: 1.0,
                crowned_fraction: k2,
            },
            misalignment: Misalignment::default(),
            slices: 20,
        };
        FaceWidth::new(&face, 8.0, 100_000.0)
    };
    let fk = crown(0.5, 0.005);
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-13;
    for z in [0.0, 1.0, -2.0, 2.0] {
        assert_eq!(fk.crown_mm(z), 0.0, "flat middle at z = {z}");
    }
    for (z, expected) in [
        (3.0, 1.144645971511779e-4),
        (-3.0, 1.144645971511779e-4),
        (3.5, 3.289231691623118e-4),
        (4.0, 0.005),
        (-4.0, 0.005),
    ] {
        let got = fk.crown_mm(z);
        assert!(
            near(got, expected),
            "z = {z}: {got:e} mm, by hand {expected:e} mm"
        );
    }
    let jg = crown(1.0, 1.0);
    let got = jg.crown_mm(2.0);
    assert!(
        near(got, 1.1446505967405424e-4),
        "Johns & Gohar at z = 2: {got:e}"
    );
}

/// The face-width spec with `reducer.deviations.misalignment: {tilt}` (the tilt as built).
fn built_with_tilt(text: &str, tilt: &str) -> String {
    let with = text.replacen(
        "modification:\n",
        &format!("  deviations:\n    misalignment: {tilt}\nmodification:\n"),
        1,
    );
    assert_ne!(with, text, "the tilt as built is in the spec");
    with
}

/// `cycloid check --json` of `text`: the results JSON, checked free of NaN and infinities,
/// without `spec_sha256` (the hash of the spec's text, which differs by construction).
fn results_json(name: &str, text: &str) -> String {
    let dir = crate::common::Scratch::new(name);
    dir.write("spec.yaml", text);
    let run = crate::common::cycloid(&dir.path, &["check", "spec.yaml", "--json", "r.json"]);
    assert!(run.code() == 0 || run.code() == 1, "{name}: {}", run.stderr);
    let json = dir.read("r.json");
    assert!(
        !json.contains("NaN") && !json.contains("Infinity"),
        "{json}"
    );
    let mut doc: serde_json::Value = serde_json::from_str(&json).expect("results.json is JSON");
    doc.as_object_mut()
        .unwrap()
        .remove("spec_sha256")
        .expect("spec_sha256");
    doc.to_string()
}

/// The first place where two JSON texts differ (a short message, not the whole documents).
fn same_json(a: &str, b: &str, what: &str) {
    if a != b {
        let at = a.bytes().zip(b.bytes()).take_while(|(x, y)| x == y).count();
        let from = at.saturating_sub(120);
        panic!(
            "{what}: differ at byte {at}:\n  {}\n  {}",
            &a[from..(at + 80).min(a.len())],
            &b[from..(at + 80).min(b.len())]
        );
    }
}

/// A tilt as built θ (`reducer.deviations.misalignment`) on an aligned scene is that scene
/// tilted by θ (`scenes[].misalignment`): the same numbers enter the model (θ_scene + θ_dev with
/// θ_scene = 0 is θ_dev exactly, and both are 1e-3·mrad of the same value), so every output
/// of the results JSON is the same, bit for bit. The tilt is not a no-op: the tilted results
/// differ from the aligned scene's.
#[test]
fn a_tilt_as_built_is_the_scene_tilted_by_it() {
    let tilt = "{ about_x_mrad: 0.3, about_y_mrad: -0.2 }";
    let slices = "    face_slices: 10\n";
    let aligned = spec("", slices, 12);
    let in_scene = spec("", &format!("    misalignment: {tilt}\n{slices}"), 12);
    let as_built = built_with_tilt(&aligned, tilt);
    let scene_json = results_json("tilt-scene", &in_scene);
    let built_json = results_json("tilt-built", &as_built);
    same_json(&scene_json, &built_json, "the tilt as built is the scene's");
    assert_ne!(
        results_json("tilt-none", &aligned),
        built_json,
        "the tilt as built changes the results"
    );
    // The model itself: the same face, line loads bit for bit.
    let (a, b) = (run(&parse(&in_scene)), run(&parse(&as_built)));
    assert_eq!(
        face_of(&a).line_load_n_per_mm,
        face_of(&b).line_load_n_per_mm
    );
}

/// The scene's tilt θ1 and the tilt as built θ2 add: the scene tilted by θ1 + θ2 (small tilts
/// add, u(z) = z·(θy, −θx) is linear in θ). The values are chosen so the sum is exact in
/// floating point: 1e-3·θ for θ a power of two is 1e-3 scaled exactly, and the sum of two such
/// is the exact product 1e-3·(θ1 + θ2) before the one rounding both sides share; so the same
/// number enters the model, and the JSON is the same bit for bit.
#[test]
fn the_scene_tilt_and_the_tilt_as_built_add() {
    let slices = "    face_slices: 10\n";
    let split = built_with_tilt(
        &spec(
            "",
            &format!("    misalignment: {{ about_x_mrad: 0.25, about_y_mrad: -0.5 }}\n{slices}"),
            12,
        ),
        "{ about_x_mrad: 0.5, about_y_mrad: 0.25 }",
    );
    let summed = spec(
        "",
        &format!("    misalignment: {{ about_x_mrad: 0.75, about_y_mrad: -0.25 }}\n{slices}"),
        12,
    );
    same_json(
        &results_json("tilt-split", &split),
        &results_json("tilt-summed", &summed),
        "θ1 in the scene + θ2 as built = the scene tilted by θ1 + θ2",
    );
}

/// A tilt as built is validated as a scene's (finite, at its key) and, with a scene that loads
/// its contacts on one slice, refused at `reducer.deviations.misalignment` with the rule and
/// the number of slices; file:line:column of the key as written, exit 2. A scene that loads
/// nothing (clearance only) may keep one slice.
#[test]
fn a_bad_tilt_as_built_is_refused_where_it_is_written() {
    let cases = [
        (
            "{ about_x_mrad: .nan }",
            "    face_slices: 4\n",
            "reducer.deviations.misalignment.about_x_mrad",
            "finite",
        ),
        (
            "{ about_y_mrad: .inf }",
            "    face_slices: 4\n",
            "reducer.deviations.misalignment.about_y_mrad",
            "finite",
        ),
        (
            "{ about_x_mrad: 0.3 }",
            "",
            "reducer.deviations.misalignment",
            "face_slices 1",
        ),
        (
            "{ about_y_mrad: 0.3 }",
            "    face_slices: 1\n",
            "reducer.deviations.misalignment",
            "face_slices: 2",
        ),
    ];
    let dir = crate::common::Scratch::new("tilt-bad");
    for (tilt, scene, key, rule) in cases {
        let text = built_with_tilt(&spec("", scene, 12), tilt);
        crate::common::assert_refused_at(&dir, "face.yaml", &text, key, rule);
    }
    // Clearance only: no contact is loaded, one slice is allowed.
    let clearance = spec("", "", 12).replace("effects: [bearing]", "effects: [clearance]");
    parse(&built_with_tilt(&clearance, "{ about_x_mrad: 0.3 }"));
}

/// The review's face-width figure of a scene tilted only as built (`reducer.deviations`) is
/// that of the scene tilted by the same θ in its own `misalignment`: the same roller, angle and
/// tilted curve, and "designed" without either tilt, so the same untilted curve bit for bit
/// (the same numbers enter the same solve).
#[test]
fn the_review_draws_a_tilt_as_built_against_the_untilted_design() {
    use cycloid::engine::face_profile::face_profiles;
    use cycloid::engine::scene::{self, RunOptions};
    let tilt = "{ about_x_mrad: 0.3, about_y_mrad: -0.2 }";
    let slices = "    face_slices: 10\n";
    let profiles = |text: &str| {
        let spec = parse(text);
        let s = &spec.scenes[0];
        let plan = scene::plan(&spec, s, Default::default());
        let result = scene::run(&spec, s, &plan, &RunOptions::for_spec(&spec)).unwrap();
        face_profiles(&spec, &[result]).unwrap()
    };
    let in_scene = profiles(&spec(
        "",
        &format!("    misalignment: {tilt}\n{slices}"),
        12,
    ));
    let as_built = profiles(&built_with_tilt(&spec("", slices, 12), tilt));
    assert_eq!(
        in_scene.len(),
        1,
        "the scene tilted in its misalignment is drawn"
    );
    assert_eq!(
        as_built, in_scene,
        "the tilt as built is drawn as the scene's"
    );
    let p = &as_built[0];
    assert!(
        p.designed_n_per_mm.is_some(),
        "the untilted solve converges"
    );
    assert_ne!(p.designed_n_per_mm.as_ref(), Some(&p.tilted_n_per_mm));
}

/// The largest residual of the balance over a sweep's crank angles (`equilibrium::residual`).
fn largest_residual(loaded: &cycloid::model::results::LoadedSweep) -> f64 {
    let bearing = loaded.bearing.as_ref().unwrap();
    bearing.residual.iter().copied().fold(0.0, f64::max)
}
