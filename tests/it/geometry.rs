//! Physics of the exact profile and the unloaded mesh (issue 2): contact of the unmodified
//! profile, gaps of the modifications, periodicity and symmetry of the mesh, the closest-point
//! search, the analytic derivatives, moment arms and the first-order model, the paper's cases,
//! the smallest convex radius of curvature and the backlash.
//!
//! Expected values come from closed forms derived in the comments, limit cases, symmetries of
//! the mesh and brute force, never from the code's own output.

use crate::common::*;
use approx::relative_eq;
use cycloid::geometry::clearance::{self, Mesh, Pose, Scope};
use cycloid::geometry::first_order;
use cycloid::geometry::profile::Profile;
use cycloid::geometry::{cross, Vec2};
use cycloid::model::{Design, FormTerm, Modification};
use cycloid::spec::rules as validity;
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

// ---------------------------------------------------------------------------------------------
// Helpers

fn np(d: &Design) -> f64 {
    d.rollers as f64
}

fn nc(d: &Design) -> f64 {
    d.teeth as f64
}

/// Gap of roller i at crank φ and lag β, exact geometry, default Newton start.
fn gap(mesh: &Mesh, i: usize, phi: f64, lag: f64) -> f64 {
    mesh.roller_gap(i, &Pose::lagging(phi, lag), None)
        .unwrap_or_else(|f| panic!("{f}"))
        .gap_mm
}

/// Roller angle from the eccentric direction, φi = 2πi/np − φ, and S = sqrt(1 + K1² − 2K1 cos φi).
fn phi_i_and_s(d: &Design, i: usize, phi: f64) -> (f64, f64) {
    let phi_i = TAU * i as f64 / np(d) - phi;
    let k1 = d.eccentricity_mm * np(d) / d.roller_circle_radius_mm;
    (phi_i, (1.0 + k1 * k1 - 2.0 * k1 * phi_i.cos()).sqrt())
}

/// Moment arm of the unmodified mesh from the instant centre (derivation in
/// `unmodified_arm_is_the_pitch_point_closed_form`): l = e·nc·sin φi / S.
fn arm_closed(d: &Design, i: usize, phi: f64) -> f64 {
    let (phi_i, s) = phi_i_and_s(d, i, phi);
    d.eccentricity_mm * nc(d) * phi_i.sin() / s
}

// ---------------------------------------------------------------------------------------------
// 0. The generated designs are valid

proptest! {
    /// The random designs of the property tests are valid by the project's own design rules
    /// (K1 < 1, no undercut, rollers not overlapping), so the physics below is asserted on
    /// designs `cycloid check` accepts. Only the output-pin hole layout, which no geometry here
    /// uses, is left out.
    #[test]
    fn generated_designs_pass_the_design_rules(c in rotated_cases()) {
        if let Err(e) = validity::check(&c.design, &c.m) {
            let key = e.key_path.clone().unwrap_or_default();
            prop_assert!(key.starts_with("reducer.output_pins"), "{e}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 1. Gaps of the unmodified and modified profile

proptest! {
    /// The unmodified disc is conjugate to the rollers: every roller centre lies on the locus
    /// C at its own parameter and the profile is the offset of C by exactly Rrp, so every roller
    /// touches the disc at every crank angle. This also pins the frame transformation (disc
    /// centre, disc rotation −φ/nc): a wrong sign puts the roller off the locus by ~e.
    #[test]
    fn unmodified_profile_touches_every_roller(c in unmodified_cases(), phi0 in 0.0..TAU) {
        let mesh = Mesh::new(&c.design, &c.m);
        for k in 0..24 {
            let phi = phi0 + k as f64 * TAU / 24.0;
            for i in 0..c.design.rollers {
                let g = gap(&mesh, i, phi, 0.0);
                // Round-off of coordinates of size Rp ≤ 120 mm (~1e-13 mm); the Newton stop at a
                // 1e-13 rad step enters the distance only to second order.
                prop_assert!(g.abs() < 1e-9, "roller {i} at φ = {phi}: gap {g:e} mm");
            }
        }
    }

    /// A pure equidistant modification moves Γ along its normal by ΔRrp; the roller centres still
    /// lie on C, so the gap is ΔRrp at every roller and every crank angle (the offset stays
    /// regular because Rrp + ΔRrp is below the smallest convex radius of curvature).
    #[test]
    fn equidistant_modification_gives_a_uniform_gap(c in cases(), phi0 in 0.0..TAU) {
        let m = modification(0.0, c.m.equidistant_mm, 0.0);
        let mesh = Mesh::new(&c.design, &m);
        for k in 0..24 {
            let phi = phi0 + k as f64 * TAU / 24.0;
            for i in 0..c.design.rollers {
                let g = gap(&mesh, i, phi, 0.0);
                // Same round-off budget as the unmodified contact.
                prop_assert!((g - m.equidistant_mm).abs() < 1e-9,
                    "roller {i} at φ = {phi}: gap {g} mm, ΔRrp {} mm", m.equidistant_mm);
            }
        }
    }

    /// At the root (t = 0 mod 2π/nc) and the tip (t = π/nc mod 2π/nc) the locus normal is radial:
    /// root C' = (R' − e)·u, tip C' = (R' + e)·u. The roller centre sits on the unshifted locus at
    /// the same place, p = C' − ΔRp·N, so its distance from Γ there is r' − ΔRp and the gap is
    /// ΔRrp − ΔRp. Roller i's locus parameter is τ = 2πi/np + φ/nc, so it is at a root when
    /// φ = −2πi·nc/np (mod 2π) and at a tip when φ = π − 2πi·nc/np (mod 2π).
    ///
    /// That place is the nearest point of Γ only while it is a minimum of the distance along the
    /// curve: d²/dt² ½|C'(t) − p|² = |C'|²(1 − ΔRp·κ) > 0, κ the signed curvature of C' there
    /// (root: (1 − K'np)/(R'(1 − K')²), concave when K'np > 1; tip: (1 + K'np)/(R'(1 + K')²)).
    /// A thinning shift (ΔRp < 0) deeper than a sharp concave root's radius lifts the roller out
    /// of the root bottom onto its two sides: the gap is then strictly smaller than ΔRrp − ΔRp
    /// (MODEL.md's "the gap at tip and root is ΔRrp − ΔRp" needs this condition).
    #[test]
    fn gap_at_tip_and_root_is_equidistant_minus_shift(c in cases()) {
        let d = &c.design;
        let mesh = Mesh::new(d, &c.m);
        let tooth = TAU / nc(d);
        let expected = c.m.equidistant_mm - c.m.shift_mm;
        let r = d.roller_circle_radius_mm + c.m.shift_mm;
        let k = d.eccentricity_mm * np(d) / r;
        let kappa_root = (1.0 - k * np(d)) / (r * (1.0 - k) * (1.0 - k));
        let kappa_tip = (1.0 + k * np(d)) / (r * (1.0 + k) * (1.0 + k));
        for i in 0..d.rollers {
            let base = -TAU * i as f64 * nc(d) / np(d);
            for (name, offset, phase, kappa) in [("root", 0.0, 0.0, kappa_root), ("tip", PI, 0.5, kappa_tip)] {
                let phi = (base + offset).rem_euclid(TAU);
                // Check the derivation: τ sits where it should within round-off.
                let tau = TAU * i as f64 / np(d) + phi / nc(d);
                let x = tau / tooth - phase;
                prop_assert!(((x - x.round()) * tooth).abs() < 1e-12);
                let g = mesh.roller_gap(i, &Pose::ideal(phi), None).unwrap();
                let seated = 1.0 - c.m.shift_mm * kappa;
                if seated > 1e-6 {
                    // Round-off (coordinates ~Rp·1e-16, τ ~1e-13 rad off the symmetry axis,
                    // where the gap is stationary).
                    prop_assert!((g.gap_mm - expected).abs() < 1e-9,
                        "roller {i} at its {name} (φ = {phi}): gap {} mm, expected {expected} mm", g.gap_mm);
                    // The foot is on the symmetry axis of the tooth.
                    let foot_phase = g.t.rem_euclid(tooth) / tooth;
                    let dist = (foot_phase - phase).abs().min((foot_phase - phase - 1.0).abs());
                    prop_assert!(dist < 1e-9, "{name} foot at tooth phase {foot_phase}");
                } else if seated < -1e-3 {
                    prop_assert!(g.gap_mm < expected,
                        "{name} sharper than the shift: gap {} mm must be below {expected} mm", g.gap_mm);
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 1d. Periodicity and mirror symmetry of the mesh

proptest! {
    /// In the disc frame roller i sits on the unshifted locus at τi(φ) = 2πi/np + φ/nc, and the
    /// profile is invariant under a turn by one tooth, 2π/nc (C(t + 2π/nc) = Rot(2π/nc)·C(t)).
    /// After one mesh period P = 2π/np, τi(φ + P) − τj(φ) = 2π(i − j)/np + 2π/(np·nc), a whole
    /// number k of teeth iff (i − j)·nc + 1 = k·np; with nc = np − 1, k = 1 gives j = i − 1.
    /// So gap_i(φ + P) = gap_{i−1}(φ): the pattern moves one roller forward (counter-clockwise)
    /// per mesh period, and NOT to roller i + 1. Holds for any modification including Δδ.
    #[test]
    fn gaps_repeat_with_the_mesh_period_one_roller_on(c in rotated_cases(), phi in 0.0..TAU) {
        let d = &c.design;
        let mesh = Mesh::new(d, &c.m);
        let period = d.mesh_period_rad();
        let n = d.rollers;
        for i in 0..n {
            let later = gap(&mesh, i, phi + period, 0.0);
            let earlier = gap(&mesh, (i + n - 1) % n, phi, 0.0);
            // Two independent Newton solves of the same geometry: round-off only.
            prop_assert!((later - earlier).abs() < 1e-9,
                "gap of roller {i} at φ + P = {later}, of roller {} at φ = {earlier}", (i + n - 1) % n);
        }
    }

    /// The same periodicity through `clearance::sweep`: gap arrays shift by one roller, and the
    /// backlash, reverse backlash and lost motion (extrema over the rollers) repeat exactly.
    #[test]
    fn sweep_is_periodic_in_the_mesh_period(c in rotated_cases(), phi0 in 0.0..TAU) {
        let d = &c.design;
        let mesh = Mesh::new(d, &c.m);
        let steps = 4;
        let period = d.mesh_period_rad();
        let crank: Vec<f64> = (0..2 * steps)
            .map(|k| phi0 + k as f64 * period / steps as f64)
            .collect();
        let s = clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent).unwrap_or_else(|f| panic!("{f}"));
        let b = s.backlash.as_ref().expect("backlash");
        let n = d.rollers;
        for k in 0..steps {
            for i in 0..n {
                prop_assert!((s.gap_mm[i][k + steps] - s.gap_mm[(i + n - 1) % n][k]).abs() < 1e-9);
            }
            // Closing lags converge to a relative step of 1e-12 or to the gap's round-off
            // (~1e-14·Rp mm) over the arm: allow 1e-9 relative and 1e-11 rad absolute.
            for (name, a) in [("backlash", &b.forward_rad), ("reverse", &b.reverse_rad),
                              ("lost motion", &b.lost_motion_rad)] {
                prop_assert!(relative_eq!(a[k], a[k + steps], epsilon = 1e-11, max_relative = 1e-9),
                    "{name} at φ = {} is {}, one period later {}", crank[k], a[k], a[k + steps]);
            }
        }
    }

    /// Without a profile rotation the mesh is mirror-symmetric about the line of centres at
    /// φ = 0: C(−t) is the mirror image of C(t), roller i at φ mirrors roller np − i at −φ, and
    /// moment arms change sign. So the reverse backlash at φ equals the forward backlash at −φ
    /// (≡ P − φ by periodicity), and gap_i(φ) = gap_{np−i}(−φ).
    #[test]
    fn reverse_backlash_mirrors_forward_backlash(c in cases(), phi in 0.0..TAU) {
        let d = &c.design;
        let mesh = Mesh::new(d, &c.m);
        let n = d.rollers;
        let steps = 6;
        let period = d.mesh_period_rad();
        let crank: Vec<f64> = (0..steps).map(|k| k as f64 * period / steps as f64).collect();
        let s = clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent).unwrap_or_else(|f| panic!("{f}"));
        let b = s.backlash.as_ref().expect("backlash");
        for k in 0..steps {
            let mirrored = (steps - k) % steps;
            // Closing-lag convergence, as in the periodicity test.
            prop_assert!(relative_eq!(b.reverse_rad[k], b.forward_rad[mirrored], epsilon = 1e-11, max_relative = 1e-9),
                "reverse backlash at φ_{k} = {}, forward at φ_{mirrored} = {}",
                b.reverse_rad[k], b.forward_rad[mirrored]);
        }
        for i in 0..n {
            let a = gap(&mesh, i, phi, 0.0);
            let b = gap(&mesh, (n - i) % n, -phi, 0.0);
            prop_assert!((a - b).abs() < 1e-9, "roller {i}: {a} vs mirrored {b}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        // A quarter of the run's count: each case evaluates the whole profile ~40,000 times.
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse::<u32>().ok()).map_or(16, |n| n.div_ceil(4))
    ))]

    /// The backlash each way is the first lag at which a roller touches the disc, by brute
    /// force: every roller's gap from the nearest point of the whole profile
    /// (`brute_force_signed_distance`, no closest-point search and no moment arm), at 23 lags
    /// short of the sweep's backlash (none may touch) and at it (one touches). A roller whose
    /// gap at β = 0 exceeds |p| times the backlash cannot touch before it (its centre turns on
    /// a circle of radius |p|, so its gap changes by at most |p| per radian) and is left out.
    /// Designs that interfere at β = 0 are left out: their backlash is negative that way.
    #[test]
    fn backlash_is_the_first_lag_at_which_a_roller_touches(c in cases(), phi in 0.0..TAU) {
        let mesh = Mesh::new(&c.design, &c.m);
        // φ = 0 puts roller 0 on the centreline of a tooth space, as near one side as the
        // other: where a roller closes first on the side it is not nearest.
        for phi in [0.0, phi] {
            first_touch_is_the_backlash(&mesh, phi)?;
        }
    }
}

/// A roller beside a root, its gap at β = 0 a micrometre and its arm −0.18 mm: its foot passes
/// the root at ~3e-5 rad of forward lag and it closes at 7.5e-5 rad, before every other roller
/// (found by an adversarial review with its own brute force). Steps proven free of a
/// micrometre over e·nc = 36.6 mm cannot get there in 64, and the roller was left out: the
/// forward backlash read 1.14e-4 rad (52 % high), and 2.29e-5 against 2.21e-5 with the second
/// modification. The brute force of `first_touch_is_the_backlash`, at ±φ (mirror images).
#[test]
fn a_roller_that_closes_after_its_foot_passes_a_root_counts() {
    let d = design(7, 6.096576197344774, 51.97582770190419, 2.3877038089533467);
    for (shift, equidistant, phi) in [(0.05, 0.050001000000000004, 1e-3), (0.01, 0.010001, 1e-4)] {
        let mesh = Mesh::new(&d, &modification(shift, equidistant, 0.0));
        for phi in [phi, -phi] {
            first_touch_is_the_backlash(&mesh, phi).unwrap();
        }
    }
}

/// `backlash_is_the_first_lag_at_which_a_roller_touches` at crank φ.
fn first_touch_is_the_backlash(mesh: &Mesh, phi: f64) -> Result<(), TestCaseError> {
    let s = clearance::sweep(mesh, &[phi], Scope::Backlash, &cycloid::progress::Silent)
        .unwrap_or_else(|f| panic!("{f}"));
    let b = s.backlash.as_ref().expect("backlash");
    let rollers = mesh.rollers;
    let brute = |i: usize, lag: f64| {
        let p = mesh.roller_in_disc(i, &Pose::lagging(phi, lag));
        brute_force_signed_distance(&mesh.profile, p, 4096).0 - mesh.roller_radius(i)
    };
    let at_zero: Vec<f64> = (0..rollers).map(|i| brute(i, 0.0)).collect();
    if at_zero.iter().any(|&g| g <= 0.0) {
        return Ok(());
    }
    let reach = PI / rollers as f64;
    for (sign, backlash) in [(1.0, b.forward_rad[0]), (-1.0, b.reverse_rad[0])] {
        let end = backlash.min(reach);
        let near: Vec<usize> = (0..rollers)
            .filter(|&i| {
                at_zero[i] <= mesh.roller_in_disc(i, &Pose::ideal(phi)).norm() * end * 1.01
            })
            .collect();
        let least = |lag: f64| {
            near.iter()
                .map(|&i| brute(i, lag))
                .fold(f64::INFINITY, f64::min)
        };
        for k in 1..24 {
            let lag = sign * end * k as f64 / 24.0;
            let g = least(lag);
            prop_assert!(g > 0.0, "sign {sign}: a roller touches at lag {lag} ({g} mm), before the backlash {backlash}");
        }
        if backlash.is_finite() {
            // The sweep stops within 32 ulp of Rp of closing; the brute force's distance is
            // good to its golden-section round-off (~1e-12 mm): 1e-9 mm covers both.
            let g = least(sign * backlash);
            prop_assert!(
                g.abs() <= 1e-9,
                "sign {sign}: least gap {g} mm at the backlash {backlash}"
            );
        }
    }
    Ok(())
}

proptest! {
    /// `Profile::arm_bound_mm` bounds the moment arm of every foot of Γ, the distance from the
    /// disc centre to Γ's normal |Γ(t) × n(t)|, at 2,000 points of random designs, with and
    /// without a random form error (up to two orders from 2 to 6, coefficients up to 5 µm).
    /// Without one the arm reaches e·nc where the normal is perpendicular to the pitch point's
    /// direction (cos(nc·t) = np·e/R'), so the bound is met to the sampling's 1 %.
    #[test]
    fn no_foot_has_an_arm_beyond_the_bound(
        c in rotated_cases(),
        form in prop::collection::vec((2usize..7, -5e-3f64..5e-3, -5e-3f64..5e-3), 0..3),
    ) {
        let terms: Vec<FormTerm> = form
            .iter()
            .map(|&(order, cos_mm, sin_mm)| FormTerm { order, cos_mm, sin_mm })
            .collect();
        let profile = Profile::new(&c.design, &c.m).with_form(&terms);
        let bound = profile.arm_bound_mm();
        let mut largest = 0.0f64;
        for k in 0..2000 {
            let t = k as f64 * TAU / 2000.0;
            let arm = cross(profile.point(t), profile.normal(t)).abs();
            prop_assert!(arm <= bound, "arm {arm} mm at t = {t} above the bound {bound} mm");
            largest = largest.max(arm);
        }
        if terms.is_empty() {
            prop_assert!(largest >= 0.99 * bound, "largest arm {largest} mm, bound {bound} mm");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 1e. The closest point is the global nearest point

/// Brute force: the nearest point of Γ to p over the whole closed curve (N samples, then a
/// golden-section refinement between the neighbours of the best sample), and whether p is
/// inside the disc by the crossing number of the sampled polygon (no normals involved).
fn brute_force_signed_distance(profile: &Profile, p: Vec2, samples: usize) -> (f64, f64) {
    let ts: Vec<f64> = (0..samples)
        .map(|k| k as f64 * TAU / samples as f64)
        .collect();
    let pts: Vec<Vec2> = ts.iter().map(|&t| profile.point(t)).collect();
    let (best, _) = pts
        .iter()
        .enumerate()
        .map(|(k, q)| (k, (q - p).norm()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    let h = TAU / samples as f64;
    let dist = |t: f64| (profile.point(t) - p).norm();
    let t = golden_section_min(dist, ts[best] - h, ts[best] + h);
    let mut inside = false;
    for k in 0..samples {
        let (u, v) = (pts[k], pts[(k + 1) % samples]);
        if (u.y > p.y) != (v.y > p.y) {
            let x = u.x + (p.y - u.y) / (v.y - u.y) * (v.x - u.x);
            if x > p.x {
                inside = !inside;
            }
        }
    }
    let d = dist(t);
    (if inside { -d } else { d }, t)
}

proptest! {
    /// Profile::closest_point from the roller's own parameter finds the globally nearest point
    /// of Γ, with the right sign, for roller centres at random poses (lags up to ±0.3·Rrp/Rp,
    /// which drive rollers into interference as well as clearance) and random modifications.
    #[test]
    fn closest_point_is_the_global_nearest_point(
        c in rotated_cases(),
        phi in 0.0..TAU,
        roller in 0.0..1.0f64,
        lag_frac in -1.0..1.0f64,
    ) {
        let d = &c.design;
        let mesh = Mesh::new(d, &c.m);
        let i = ((roller * np(d)) as usize).min(d.rollers - 1);
        let lag = lag_frac * 0.3 * d.roller_radius_mm / d.roller_circle_radius_mm;
        let pose = Pose::lagging(phi, lag);
        let p = mesh.roller_in_disc(i, &pose);
        let foot = mesh.profile.closest_point(p, mesh.locus_parameter(i, &pose))
            .unwrap_or_else(|f| panic!("closest point failed: {f:?}"));
        let (bf, t_bf) = brute_force_signed_distance(&mesh.profile, p, 200_000);
        // The brute force is refined to ~1e-15 rad in t; the distance is stationary at the foot,
        // so both sides are limited by round-off of coordinates ~Rp·1e-16 (~1e-13 mm).
        prop_assert!((foot.signed_distance_mm - bf).abs() < 1e-9,
            "closest_point {} mm, brute force {} mm (t {} vs {})",
            foot.signed_distance_mm, bf, foot.t, t_bf.rem_euclid(TAU));
        prop_assert!((foot.point - mesh.profile.point(foot.t)).norm() < 1e-12);
        // Stationarity with a finite-difference tangent (central, h = 1e-6/np: truncation
        // ~h²·|Γ'''| and round-off ~1e-16·Rp/h, both ≲ 1e-8 relative): the cosine of the angle
        // between Γ(t*) − p and Γ'(t*) vanishes.
        let h = 1e-6 / np(d);
        let tangent = (mesh.profile.point(foot.t + h) - mesh.profile.point(foot.t - h)) / (2.0 * h);
        let chord = foot.point - p;
        let cosine = chord.dot(&tangent) / (chord.norm() * tangent.norm());
        prop_assert!(cosine.abs() < 1e-6, "(Γ − p)·Γ' cosine {cosine:e}");
    }
}

// ---------------------------------------------------------------------------------------------
// 1f. Analytic derivatives against finite differences

/// Central difference of a vector function.
fn fd(f: impl Fn(f64) -> Vec2, t: f64, h: f64) -> Vec2 {
    (f(t + h) - f(t - h)) / (2.0 * h)
}

proptest! {
    /// locus_jet (C', C''), locus_d3, locus_curvature_derivative, tangent and the curvature of Γ
    /// against central differences. Step h = 1e-5/np (the locus varies on a t-scale of 1/np):
    /// truncation error ~h²/6·|f'''| and round-off ~1e-16·|f|/h are both below 1e-8 of the
    /// derivative's natural size, which sets the scale of each tolerance.
    #[test]
    fn analytic_derivatives_match_finite_differences(c in rotated_cases(), t in 0.0..TAU) {
        let d = &c.design;
        let p = Profile::new(d, &c.m);
        let n = np(d);
        let (r, e) = (p.locus_radius_mm, p.eccentricity_mm);
        let h = 1e-5 / n;
        // |C^(k)| ≤ R' + e·np^k.
        let scale = |k: i32| r + e * n.powi(k);
        let j = p.locus_jet(t);
        let tol = 1e-6;
        prop_assert!((j.d1 - fd(|s| p.locus_jet(s).c, t, h)).norm() <= tol * scale(1));
        prop_assert!((j.d2 - fd(|s| p.locus_jet(s).d1, t, h)).norm() <= tol * scale(2));
        prop_assert!((p.locus_d3(t) - fd(|s| p.locus_jet(s).d2, t, h)).norm() <= tol * scale(3));
        // Curvature varies on a t-scale of ~(1 − K1)/np near a sharp root: its derivative's size
        // is ~np·|κ|; h·np/(1 − K1) ≤ 1e-4, so truncation stays ≲ 1e-8 of that.
        let dk = p.locus_curvature_derivative(t);
        let dk_fd = (p.locus_curvature(t + h) - p.locus_curvature(t - h)) / (2.0 * h);
        prop_assert!((dk - dk_fd).abs() <= tol * (dk.abs() + n * p.locus_curvature(t).abs()),
            "dκ/dt {dk} vs finite difference {dk_fd}");
        // Γ' = |C'|(1 − r'κ)T; its size is at most |C'| + r'·|κ||C'| (|Γ'| itself), plus R' + e·np.
        let tangent = p.tangent(t);
        let tangent_fd = fd(|s| p.point(s), t, h);
        prop_assert!((tangent - tangent_fd).norm() <= tol * (tangent.norm() + scale(1)),
            "Γ' {tangent:?} vs finite difference {tangent_fd:?}");
        // The normal is the unit vector to the right of the (counter-clockwise) tangent.
        let normal = p.normal(t);
        prop_assert!((normal.norm() - 1.0).abs() < 1e-12);
        prop_assert!(normal.dot(&tangent_fd) .abs() <= tol * tangent_fd.norm());
        prop_assert!(cross(normal, tangent_fd) > 0.0);
        // Curvature of Γ from first and second central differences of Γ, h2 = 3e-4/np: the second
        // difference has round-off ~1e-16·Rp/h2² and truncation ~h2²/12·|Γ''''|, each ≲ 1e-6 of
        // |Γ''|; the curvature is then good to ~1e-5 of its size (|κ_Γ| + 1/R').
        let h2 = 3e-4 / n;
        let (a, b, m) = (p.point(t - h2), p.point(t + h2), p.point(t));
        let g1 = (b - a) / (2.0 * h2);
        let g2 = (b - 2.0 * m + a) / (h2 * h2);
        let kappa_fd = cross(g1, g2) / g1.norm().powi(3);
        let kappa = p.curvature(t);
        prop_assert!((kappa - kappa_fd).abs() <= 1e-4 * (kappa.abs() + 1.0 / r),
            "κ_Γ {kappa} vs finite difference {kappa_fd}");
    }

    /// Profile::min_convex_radius against the closed form of the curvature maximum (common.rs):
    /// the value, and the place within the half tooth [0, π/nc].
    #[test]
    fn min_convex_radius_matches_the_closed_form(c in cases()) {
        let d = &c.design;
        let p = Profile::new(d, &c.m);
        let (rho, t) = min_convex_radius_closed(d.rollers, d.eccentricity_mm, p.locus_radius_mm);
        let found = p.locus().min_convex_radius();
        // Golden-section refinement of a smooth maximum: the value to round-off (relative
        // 1e-12 allowed 1e-10); the place only to ~sqrt(1e-16) of the t-scale 1/np.
        prop_assert!((found.radius_mm - rho).abs() <= 1e-10 * rho,
            "min convex radius {} mm, closed form {rho} mm", found.radius_mm);
        prop_assert!((found.t - t).abs() <= 1e-6, "at t = {}, closed form t = {t}", found.t);
    }
}

// ---------------------------------------------------------------------------------------------
// 1g. Moment arms, the lag derivative, and the first-order model

proptest! {
    /// The common normal of a conjugate pair passes through the pitch point, at e·np from the
    /// input axis along the eccentric direction, i.e. at e·nc from the disc centre. The roller
    /// centre seen from the pitch point is Rp·(cos φi − K1, sin φi) in the eccentric frame, of
    /// length Rp·S, so the distance of the normal from the disc centre is e·nc·sin φi/S. Sign:
    /// at φi = 90° the roller pushes the disc clockwise, which is the +arm of the module doc
    /// (the disc turns clockwise at −φ/nc: the arm drives it). The first-order arm is the same.
    #[test]
    fn unmodified_arm_is_the_pitch_point_closed_form(c in unmodified_cases(), phi in 0.0..TAU) {
        let d = &c.design;
        let mesh = Mesh::new(d, &c.m);
        let scale = d.eccentricity_mm * nc(d);
        for i in 0..d.rollers {
            let g = mesh.roller_gap(i, &Pose::ideal(phi), None).unwrap();
            let expected = arm_closed(d, i, phi);
            // Round-off in the foot's normal (~1e-15) times |p| ≤ Rp + e.
            prop_assert!((g.arm_mm - expected).abs() <= 1e-10 * scale,
                "roller {i}: arm {} mm, closed form {expected} mm", g.arm_mm);
            let fo = first_order::roller(d, &c.m, i, phi);
            prop_assert!((fo.arm_mm - expected).abs() <= 1e-12 * scale);
        }
    }

    /// ∂gap/∂β = −arm, by central differences in the lag, for any modification and lag.
    /// Tolerance: the central difference D(h) has error c·h², estimated from two steps as
    /// (D(h) − D(h/2))/3 (Richardson) and allowed twice over; that covers rollers nearly
    /// conforming to a concave flank (centre close to the centre of curvature), where the foot
    /// runs fast and ∂³gap/∂β³ is large. Floor: gap round-off ~1e-13 mm / (h/2) ≈ 2e-7 mm/rad,
    /// allowed as 1e-6·e·nc (≥ 1.5e-6 mm/rad here).
    ///
    /// The differences follow the foot found at β (warm-started there, no scan for another
    /// flank): the identity is the derivative of the distance to that foot's flank. The gap
    /// itself, the distance to the nearest flank, has a kink where a roller centre is as near to
    /// two flanks, and a stencil across it mixes two slopes. The committed regression case (30
    /// teeth, equidistant −85 µm, roller 27 in 73 µm of interference) has one: between two lags
    /// 1e-7 rad apart the nearest foot jumps by 1.8e-3 in t and its arm from −3.66 to +3.68 mm,
    /// and a dense scan of the whole profile finds the same nearest point on each side.
    #[test]
    fn gap_derivative_in_lag_is_minus_the_arm(c in rotated_cases(), phi in 0.0..TAU, lag_frac in -1.0..1.0f64) {
        let d = &c.design;
        let mesh = Mesh::new(d, &c.m);
        let lag = lag_frac * 0.1 * d.roller_radius_mm / d.roller_circle_radius_mm;
        let h = 1e-6;
        for i in 0..d.rollers {
            let g = mesh.roller_gap(i, &Pose::lagging(phi, lag), None).unwrap();
            let on_flank = |l: f64| mesh.roller_gap(i, &Pose::lagging(phi, l), Some(g.t)).unwrap().gap_mm;
            let central = |h: f64| (on_flank(lag + h) - on_flank(lag - h)) / (2.0 * h);
            let (coarse, fine) = (central(h), central(0.5 * h));
            let tol = 2.0 * (coarse - fine).abs() / 3.0 + 1e-6 * d.eccentricity_mm * nc(d);
            prop_assert!((fine + g.arm_mm).abs() <= tol,
                "roller {i}: ∂gap/∂β {fine} mm/rad (at h: {coarse}), arm {} mm", g.arm_mm);
        }
    }

    /// A profile turned by Δδ counter-clockwise is the same disc lagging by β = Δδ: the disc
    /// sits at ψ = −φ/nc + β in the fixed frame, and the profile at ψ + Δδ. Exact identity.
    #[test]
    fn profile_rotation_is_a_lag(c in rotated_cases(), phi in 0.0..TAU) {
        let d = &c.design;
        let turned = Mesh::new(d, &c.m);
        let plain = Mesh::new(d, &modification(c.m.shift_mm, c.m.equidistant_mm, 0.0));
        for i in 0..d.rollers {
            let a = gap(&turned, i, phi, 0.0);
            let b = gap(&plain, i, phi, c.m.rotation_rad);
            // Two routes through the same geometry: round-off only.
            prop_assert!((a - b).abs() < 1e-11, "roller {i}: {a} vs {b}");
        }
    }
}

proptest! {
    /// Any rotation of the profile computes, and is the same disc as its rotation reduced to
    /// the tooth pitch: the locus has nc-fold symmetry, R(−2π/nc)·C(t) = C(t − 2π/nc) (expand
    /// both: the lobe term turns by np·2π/nc ≡ 2π/nc), so a profile turned by Δδ is the profile
    /// turned by Δδ' = Δδ mod 2π/nc, which in turn is the unturned disc lagging by Δδ'
    /// (`profile_rotation_is_a_lag`). Rotations up to three turns either way, including whole
    /// pitches and half pitches (rollers on the tooth tips). Δδ' is reduced here by its own
    /// remainder, independently of the code's reduction.
    #[test]
    fn any_rotation_is_the_same_disc_as_its_rotation_within_a_pitch(
        c in cases(),
        turns in -3.0f64..3.0,
        pitches in -4i32..4,
        half in proptest::bool::ANY,
        phi in 0.0..TAU,
    ) {
        let d = &c.design;
        let pitch = TAU / d.teeth as f64;
        let rotation = if half {
            (pitches as f64 + 0.5) * pitch
        } else {
            turns * TAU + pitches as f64 * pitch
        };
        let turned = Mesh::new(d, &modification(c.m.shift_mm, c.m.equidistant_mm, rotation));
        let plain = Mesh::new(d, &modification(c.m.shift_mm, c.m.equidistant_mm, 0.0));
        let mut reduced = rotation.rem_euclid(pitch);
        if reduced > 0.5 * pitch {
            reduced -= pitch;
        }
        for i in 0..d.rollers {
            let a = gap(&turned, i, phi, 0.0);
            let b = gap(&plain, i, phi, reduced);
            // The reduction of a rotation of up to 3 turns rounds to ~1e-15 rad, moving a gap
            // by at most that times the arm (≤ Rp + e): 1e-12 mm covers it and the round-off
            // of the two routes.
            let tol = 1e-12 * (1.0 + d.roller_circle_radius_mm);
            prop_assert!((a - b).abs() < tol, "roller {i}, rotation {rotation}: {a} vs {b}");
        }
    }

    /// Mesh::closing_lag_toward returns a lag at which the gap is zero (to round-off) each way,
    /// for any modification; and it does find one for every roller that the first-order model
    /// says closes nearby (the way its arm says): with a pure equidistant δ = 1e-3·e every
    /// roller with |arm| ≥ 0.2·e·nc closes at δ/arm up to the second-order term
    /// |∂²gap/∂β²|·δ/(2·arm²) (relative), with
    /// |∂²gap/∂β²| ≤ |p| + |p|²·max|κ_C| (a roller centre on a circle of radius |p| ≤ Rp + e
    /// crossing a curve of curvature ≤ max|κ_C|).
    #[test]
    fn closing_lag_closes_the_gap(c in rotated_cases(), phi in 0.0..TAU) {
        let d = &c.design;
        let mesh = Mesh::new(d, &c.m);
        for i in 0..d.rollers {
            for b in [1.0, -1.0].map(|sign| mesh.closing_lag_toward(i, phi, sign).unwrap()).into_iter().flatten() {
                let g = gap(&mesh, i, phi, b);
                // Converged to the gap's round-off, ~1e-14·Rp.
                prop_assert!(g.abs() <= 1e-12 * d.roller_circle_radius_mm,
                    "roller {i}: gap {g:e} mm at its closing lag {b}");
            }
        }
        let delta = 1e-3 * d.eccentricity_mm;
        let mesh = Mesh::new(d, &modification(0.0, delta, 0.0));
        let e_nc = d.eccentricity_mm * nc(d);
        let p_max = d.roller_circle_radius_mm + d.eccentricity_mm;
        let bound = (p_max + p_max * p_max * kappa_max(d)) * delta / (2.0 * (0.2 * e_nc).powi(2));
        for i in 0..d.rollers {
            let arm = arm_closed(d, i, phi);
            if arm.abs() >= 0.2 * e_nc {
                let b = mesh.closing_lag_toward(i, phi, arm.signum()).unwrap();
                prop_assert!(b.is_some(), "roller {i} (arm {arm} mm) does not close");
                let b = b.unwrap();
                prop_assert!((b * arm / delta - 1.0).abs() <= bound,
                    "roller {i}: closing lag {b}, first order {}", delta / arm);
            }
        }
    }
}

/// Largest |κ_C| of the unmodified locus: the sharper of the root (x = 1) and the convex maximum.
fn kappa_max(d: &Design) -> f64 {
    let (e, r) = (d.eccentricity_mm, d.roller_circle_radius_mm);
    locus_curvature_closed(d.rollers, e, r, 1.0)
        .abs()
        .max(1.0 / min_convex_radius_closed(d.rollers, e, r).0)
}

/// Largest |exact − first-order| gap over every roller and 12 crank angles of one mesh period
/// (which between them put a roller at every place on the tooth).
fn first_order_error(d: &Design, m: &Modification, phi0: f64) -> f64 {
    let mesh = Mesh::new(d, m);
    let mut worst: f64 = 0.0;
    for k in 0..12 {
        let phi = phi0 + k as f64 * d.mesh_period_rad() / 12.0;
        for i in 0..d.rollers {
            let exact = gap(&mesh, i, phi, 0.0);
            let fo = first_order::roller(d, m, i, phi).gap_mm;
            worst = worst.max((exact - fo).abs());
        }
    }
    worst
}

fn scaled(m: &Modification, f: f64) -> Modification {
    modification(m.shift_mm * f, m.equidistant_mm * f, m.rotation_rad * f)
}

proptest! {
    /// first_order::roller is the linearisation of the exact gap in (ΔRp, ΔRrp, Δδ): halving the
    /// modification divides its error by ~4. "Small" means small against the locus's radii of
    /// curvature: beyond a sharp concave root's radius the roller seats on both sides of the
    /// root and the error is no longer a power series in Δ. So the modification is scaled
    /// to at most 0.1·ρ (ρ = 1/max|κ_C|, closed form; Δδ counted as Rp·Δδ). The leading error is
    /// quadratic; the cubic term shifts the ratio 1/4 by O(|Δ|/ρ) ≤ ~0.0125, allowed as ±0.05.
    #[test]
    fn first_order_error_is_second_order(c in rotated_cases(), phi0 in 0.0..TAU) {
        let d = &c.design;
        let size = c.m.shift_mm.abs()
            .max(c.m.equidistant_mm.abs())
            .max(c.m.rotation_rad.abs() * d.roller_circle_radius_mm);
        let m = scaled(&c.m, (0.1 / kappa_max(d) / size).min(1.0));
        let full = first_order_error(d, &m, phi0);
        // A modification with (almost) no shift and rotation is exactly first-order: the ratio
        // is then round-off. Require an error well above round-off (1e-13 mm).
        prop_assume!(full > 1e-9);
        let half = first_order_error(d, &scaled(&m, 0.5), phi0);
        let ratio = half / full;
        prop_assert!((0.2..0.3).contains(&ratio),
            "error {full:e} mm at the full modification, {half:e} mm at half: ratio {ratio}");
    }

    /// The literature's closed form Δ(φi) is the first-order gap after the disc turned by
    /// β1 = (ΔRrp − ΔRp·sqrt(1 − K1²))/(e·nc) (the lag that closes the roller with the largest
    /// arm, at cos φi = K1): Δ = g0 − l·β1 with g0 = ΔRrp − ΔRp(1 − K1 cos φi)/S and
    /// l = e·nc·sin φi/S. Algebraic identity, so round-off only.
    #[test]
    fn literature_gap_is_the_first_order_gap_after_the_first_closure(c in cases(), phi in 0.0..TAU) {
        let d = &c.design;
        let (m, k1) = (&c.m, c.k1());
        let beta1 = (m.equidistant_mm - m.shift_mm * (1.0 - k1 * k1).sqrt()) / (d.eccentricity_mm * nc(d));
        for i in 0..d.rollers {
            let (phi_i, s) = phi_i_and_s(d, i, phi);
            let g0 = m.equidistant_mm - m.shift_mm * (1.0 - k1 * phi_i.cos()) / s;
            let expected = g0 - arm_closed(d, i, phi) * beta1;
            let got = first_order::literature_gap(d, m, i, phi);
            // Terms of size ≤ 0.3 mm·(1 + 1/S), S ≥ 1 − K1 ≥ 0.1: round-off ~1e-15 mm.
            prop_assert!((got - expected).abs() < 1e-12, "roller {i}: {got} vs {expected}");
            // And the first-order gap at zero lag is g0.
            let fo = first_order::roller(d, m, i, phi).gap_mm;
            prop_assert!((fo - g0).abs() < 1e-12);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 2. The paper's cases

fn paper_sweep(
    shift: f64,
    equidistant: f64,
) -> (cycloid::spec::Spec, cycloid::model::results::ClearanceSweep) {
    let spec = paper_spec(shift, equidistant);
    let scene = &spec.scenes[0];
    // One mesh period in 0.1° steps (reducer.yaml's scene).
    assert_eq!(scene.crank_rad.len(), 360);
    assert!((scene.crank_rad[1] - scene.crank_rad[0] - 0.1f64.to_radians()).abs() < 1e-15);
    assert!(scene.spans_whole(spec.design.mesh_period_rad()));
    let mesh = Mesh::new(&spec.design, &spec.modification);
    let sweep = clearance::sweep(
        &mesh,
        &scene.crank_rad,
        Scope::Gaps,
        &cycloid::progress::Silent,
    )
    .expect("sweep converges");
    (spec, sweep)
}

/// The smallest gap of one roller near a crank angle, refined continuously in φ by golden
/// section (to bound the error of sampling the crank at 0.1°).
fn refined_min_gap(mesh: &Mesh, i: usize, phi: f64, half_width: f64) -> f64 {
    let (mut a, mut b) = (phi - half_width, phi + half_width);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if gap(mesh, i, x1, 0.0) < gap(mesh, i, x2, 0.0) {
            b = x2;
        } else {
            a = x1;
        }
    }
    gap(mesh, i, 0.5 * (a + b), 0.0)
}

/// The paper's negative initial estimate (ΔRp, ΔRrp) = (−0.15, −0.135) mm satisfies its Eq. 8
/// (ΔRrp − ΔRp = 0.015 ≥ dt = 0.015), yet the whole-mesh sweep finds interference at mid-flank:
/// Eq. 8 is necessary, not sufficient. Reference: independent Python brute force (dense sampling
/// of Γ, refined; 0.1° crank steps): −23.414 µm.
#[test]
fn paper_negative_case_interferes_at_mid_flank() {
    let (spec, s) = paper_sweep(-0.15, -0.135);
    let m = &spec.modification;
    // Eq. 8 holds (to the decimal round-off of 0.015).
    assert!(m.tip_clearance_mm() >= 0.015 - 1e-12);
    let min_um = s.min.gap_mm * 1000.0;
    println!(
        "negative case: min clearance {min_um:.6} µm, roller {}, crank {:.2}°, tooth phase {:.4}",
        s.min.roller,
        s.min.crank_rad.to_degrees(),
        s.min.tooth_phase
    );
    // The reference is given to 1 nm (±0.5 nm rounding); the 0.1° crank sampling costs at most
    // ½·|∂²g/∂φ²|·(0.05°)², measured below to be ≪ 1 nm.
    assert!(
        (min_um - (-23.414)).abs() <= 0.001,
        "min clearance {min_um} µm, reference −23.414 µm"
    );
    let mesh = Mesh::new(&spec.design, m);
    let continuous = refined_min_gap(&mesh, s.min.roller, s.min.crank_rad, 0.1f64.to_radians());
    let sampling_um = (s.min.gap_mm - continuous) * 1000.0;
    println!(
        "negative case: continuous min {:.6} µm",
        continuous * 1000.0
    );
    // Golden section can only go down from the sample (up to round-off 1e-10 µm).
    assert!(
        (-1e-7..1e-4).contains(&sampling_um),
        "sampling error {sampling_um} µm"
    );
    // Mid-flank: well away from the root (0) and the tip (0.5).
    let phase = s.min.tooth_phase;
    assert!(
        (0.1..0.4).contains(&phase) || (0.6..0.9).contains(&phase),
        "tooth phase {phase}"
    );
    // Eq. 8's own place, the root (roller 0 at φ = 0), has the clearance it promises.
    let root = gap(&mesh, 0, 0.0, 0.0);
    assert!((root - 0.015).abs() < 1e-9);
}

/// The paper's optimum (0.125, 0.1593) mm: the first-order gap
/// ΔRrp − ΔRp(1 − K1 cos φi)/S is smallest where (1 − K1 cos φi)/S is largest, which is 1 at
/// cos φi = ±1 (root and tip: (1 − K1c)² ≤ 1 + K1² − 2K1c ⇔ c² ≤ 1). So the minimum clearance
/// is ΔRrp − ΔRp = 34.3 µm, at the root or the tip (equal; both are sampled exactly at φ = 0 for
/// np = 10: roller 0 at the root, roller 5 at the tip). Reference: Python brute force 34.300 µm.
#[test]
fn paper_optimum_has_its_min_clearance_at_root_and_tip() {
    let (_, s) = paper_sweep(0.125, 0.1593);
    let min_um = s.min.gap_mm * 1000.0;
    println!(
        "optimum: min clearance {min_um:.6} µm, roller {}, crank {:.2}°, tooth phase {:.6}",
        s.min.roller,
        s.min.crank_rad.to_degrees(),
        s.min.tooth_phase
    );
    // Exact value (closed form at the root/tip, sampled exactly): round-off only.
    assert!((min_um - 34.3).abs() < 1e-6, "min clearance {min_um} µm");
    let phase = s.min.tooth_phase;
    let to_root_or_tip = [0.0, 0.5, 1.0]
        .iter()
        .map(|x| (phase - x).abs())
        .fold(f64::INFINITY, f64::min);
    assert!(to_root_or_tip < 1e-9, "tooth phase {phase}");
    assert!(s.min.crank_rad.abs() < 1e-15);
}

// ---------------------------------------------------------------------------------------------
// 3. Smallest convex radius of curvature of the paper's locus

/// Independent reference: Python brute force, 9.5543 mm at t = 9.614° from the root (tip at
/// 20°). The closed form of common.rs gives the same. At the tip, K1 = e·np/Rp and
/// κ_C·Rp = (1 + K1·np)/(1 + K1)², so ρ_tip = Rp(1 + K1)²/(1 + K1·np) = 10.870 mm: larger than
/// the flank minimum, so a tip-only undercut check is unconservative.
#[test]
fn paper_min_convex_radius_is_inside_the_flank() {
    let d = paper_design();
    let p = Profile::new(&d, &Modification::default());
    let found = p.locus().min_convex_radius();
    println!(
        "paper locus: min convex radius {:.6} mm at t = {:.5}°",
        found.radius_mm,
        found.t.to_degrees()
    );
    // The Python value is rounded to 0.1 µm and 0.001°.
    assert!((found.radius_mm - 9.5543).abs() <= 0.5e-4);
    assert!((found.t.to_degrees() - 9.614).abs() <= 0.5e-3);
    let (rho, t) = min_convex_radius_closed(10, 2.0, 30.0);
    assert!((found.radius_mm - rho).abs() < 1e-9);
    assert!((found.t - t).abs() < 1e-6);

    let k1 = 2.0 * 10.0 / 30.0;
    let rho_tip = 30.0 * (1.0 + k1) * (1.0 + k1) / (1.0 + k1 * 10.0);
    let tip = PI / 9.0;
    println!("paper locus: tip radius {rho_tip:.6} mm");
    assert!((1.0 / p.locus_curvature(tip) - rho_tip).abs() < 1e-9);
    assert!(rho_tip > found.radius_mm + 1.0);
    // Well inside the flank: more than a quarter tooth (5°) from the tip.
    assert!((found.t - tip).abs() > 5f64.to_radians());

    // A roller radius between the two passes a tip-only check but undercuts the flank: Γ' turns
    // back against C' (a cusp) at the flank minimum, not at the tip.
    let between = 0.5 * (found.radius_mm + rho_tip);
    let undercut = Profile::from_parts(10, 2.0, 30.0, between, 0.0);
    let along = |t: f64| undercut.tangent(t).dot(&undercut.locus_jet(t).d1);
    assert!(along(tip) > 0.0);
    assert!(along(found.t) < 0.0);
    // And the design rules reject it as an undercut.
    let err = validity::check(&design(10, 2.0, 30.0, between), &Modification::default())
        .expect_err("undercut design must be rejected");
    assert!(err.message.contains("undercut"), "{}", err.message);
    assert_eq!(err.key_path.as_deref(), Some("reducer.roller_radius_mm"));
}

// ---------------------------------------------------------------------------------------------
// 4. Closing lag, backlash and lost motion

/// First-order closing lag of a pure equidistant modification δ: every gap is δ − l_i·β, so the
/// forward backlash is δ / max_i l_i over the rollers with l_i > 0 and the reverse one
/// δ / max_i (−l_i). The arm e·nc·sin φi/S is largest, = e·nc, at cos φi = K1.
fn first_order_backlash(d: &Design, delta: f64, phi: f64) -> (f64, f64) {
    let arms: Vec<f64> = (0..d.rollers).map(|i| arm_closed(d, i, phi)).collect();
    let fwd = arms.iter().cloned().fold(0.0, f64::max);
    let rev = arms.iter().map(|l| -l).fold(0.0, f64::max);
    (delta / fwd, delta / rev)
}

/// Relative error of the exact backlash against first order over one mesh period (24 angles
/// plus the angle where a roller has the largest possible arm e·nc), forward and reverse.
fn backlash_errors(d: &Design, delta: f64) -> (f64, f64, Vec<f64>) {
    let period = d.mesh_period_rad();
    let k1 = d.k1();
    // Roller 1 at cos φ1 = K1, sin φ1 > 0: φ = 2π/np − acos K1 (mod P).
    let best = (period - k1.acos()).rem_euclid(period);
    let mut crank: Vec<f64> = (0..24).map(|k| k as f64 * period / 24.0).collect();
    crank.push(best);
    let mesh = Mesh::new(d, &modification(0.0, delta, 0.0));
    let s = clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent)
        .unwrap_or_else(|f| panic!("{f}"));
    let b = s.backlash.as_ref().expect("backlash");
    let (mut fwd_err, mut rev_err): (f64, f64) = (0.0, 0.0);
    for (k, &phi) in crank.iter().enumerate() {
        let (fwd, rev) = first_order_backlash(d, delta, phi);
        fwd_err = fwd_err.max((b.forward_rad[k] / fwd - 1.0).abs());
        rev_err = rev_err.max((b.reverse_rad[k] / rev - 1.0).abs());
        assert!((b.lost_motion_rad[k] - b.forward_rad[k] - b.reverse_rad[k]).abs() < 1e-15);
    }
    (fwd_err, rev_err, b.forward_rad.clone())
}

/// Backlash of the paper's design with a pure equidistant modification δ: first order is
/// δ/max l (δ/(e·nc) where a roller has cos φi = K1); the exact closing lag differs by the
/// curvature of gap(β), ½·∂²gap/∂β²·β², a relative error ∝ δ. Checked at δ = 4, 2, 1 µm:
/// the relative error must halve with δ (second-order absolute error) and stay below
/// |∂²gap/∂β²|·δ/(2·l²) with |∂²gap/∂β²| ≤ |p| + |p|²·max|κ_C| (a roller centre on a circle of
/// radius |p| ≤ Rp + e crossing a curve of curvature ≤ max|κ_C|, the sharp concave root).
#[test]
fn paper_backlash_of_a_pure_equidistant_modification_is_first_order() {
    let d = paper_design();
    let (e_nc, k1) = (d.eccentricity_mm * nc(&d), d.k1());
    let p_max = d.roller_circle_radius_mm + d.eccentricity_mm;
    let kappa_root = (1.0 - k1 * 10.0) / (30.0 * (1.0 - k1) * (1.0 - k1));
    let curvature_bound = p_max + p_max * p_max * kappa_root.abs();
    // Smallest forward arm the backlash can use: the largest arm among the rollers, at worst.
    let l_min = (0..200)
        .map(|k| {
            let phi = k as f64 * d.mesh_period_rad() / 200.0;
            (0..10).map(|i| arm_closed(&d, i, phi)).fold(0.0, f64::max)
        })
        .fold(f64::INFINITY, f64::min);
    let mut previous: Option<(f64, f64)> = None;
    for delta in [0.004, 0.002, 0.001] {
        let (fwd_err, rev_err, backlash) = backlash_errors(&d, delta);
        let bound = curvature_bound * delta / (2.0 * l_min * l_min);
        println!(
            "δ = {delta} mm: relative backlash error forward {fwd_err:.3e}, reverse {rev_err:.3e}, bound {bound:.3e}"
        );
        assert!(fwd_err <= bound && rev_err <= bound);
        // At the angle of the largest arm, the backlash is δ/(e·nc).
        let at_best = *backlash.last().unwrap();
        assert!((at_best * e_nc / delta - 1.0).abs() <= bound);
        // Nowhere smaller than δ/(e·nc) (beyond the second-order term).
        assert!(backlash.iter().all(|&b| b * e_nc / delta >= 1.0 - bound));
        if let Some((f, r)) = previous {
            // Halving δ halves the relative error (±20 %: the next term is another O(δ)).
            assert!(
                (0.4..0.6).contains(&(fwd_err / f)),
                "forward ratio {}",
                fwd_err / f
            );
            assert!(
                (0.4..0.6).contains(&(rev_err / r)),
                "reverse ratio {}",
                rev_err / r
            );
        }
        previous = Some((fwd_err, rev_err));
    }
}

/// Lost motion of a pure equidistant modification δ: forward + reverse backlash, the two being
/// mirror images (reverse(φ) = forward(−φ)), so over a mesh period both have the same range and
/// mean, and the lost motion is ≈ 2δ/(e·nc): between 2δ/(e·nc) and 2δ/(e·nc)/f, f the smallest
/// fraction of e·nc that the best-placed roller reaches (first order, closed form).
#[test]
fn paper_lost_motion_of_a_pure_equidistant_modification_is_twice_the_backlash() {
    let d = paper_design();
    let delta = 0.002;
    let e_nc = d.eccentricity_mm * nc(&d);
    let steps = 36;
    let period = d.mesh_period_rad();
    let crank: Vec<f64> = (0..steps)
        .map(|k| k as f64 * period / steps as f64)
        .collect();
    let mesh = Mesh::new(&d, &modification(0.0, delta, 0.0));
    let s = clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent).unwrap();
    let lags = s.backlash.as_ref().expect("backlash");
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let range = |v: &[f64]| {
        let max = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let min = v.iter().cloned().fold(f64::INFINITY, f64::min);
        (min, max)
    };
    // Closing-lag convergence (relative 1e-12), summed over 36 angles.
    assert!(relative_eq!(
        mean(&lags.forward_rad),
        mean(&lags.reverse_rad),
        epsilon = 0.0,
        max_relative = 1e-9
    ));
    let (a, b) = (range(&lags.forward_rad), range(&lags.reverse_rad));
    assert!(
        relative_eq!(a.0, b.0, epsilon = 0.0, max_relative = 1e-9)
            && relative_eq!(a.1, b.1, epsilon = 0.0, max_relative = 1e-9)
    );
    let f = crank
        .iter()
        .map(|&phi| {
            let (fwd, _) = first_order_backlash(&d, 1.0, phi);
            1.0 / (fwd * e_nc)
        })
        .fold(f64::INFINITY, f64::min);
    println!(
        "lost motion: mean {:.4e} rad, 2δ/(e·nc) = {:.4e} rad, best-roller arm fraction ≥ {f:.4}",
        mean(&lags.lost_motion_rad),
        2.0 * delta / e_nc
    );
    // Second-order term of the closing lag: relative ≲ 1e-3 at δ = 2 µm (see the backlash test).
    for &lm in &lags.lost_motion_rad {
        let ratio = lm * e_nc / (2.0 * delta);
        assert!(
            ratio >= 1.0 - 1e-3 && ratio <= 1.0 / f + 1e-3,
            "lost motion ratio {ratio}"
        );
    }
}

proptest! {
    /// Random designs: with a pure equidistant modification of 0.1 % of e the exact backlash is
    /// δ/max l to within the same second-order bound as the paper test, forward and reverse.
    #[test]
    fn backlash_of_a_pure_equidistant_modification_is_first_order(c in unmodified_cases()) {
        let d = &c.design;
        let delta = 1e-3 * d.eccentricity_mm;
        let (fwd_err, rev_err, _) = backlash_errors(d, delta);
        let k1 = d.k1();
        let n = np(d);
        let p_max = d.roller_circle_radius_mm + d.eccentricity_mm;
        // Smallest best arm over the period: rollers are 2π/np apart, so the best one is within
        // π/np of the optimum φi = acos K1; bound it by the arm there (closed form).
        let phi_opt = k1.acos();
        let arm_at = |x: f64| d.eccentricity_mm * nc(d) * x.sin() / (1.0 + k1 * k1 - 2.0 * k1 * x.cos()).sqrt();
        let l_min = arm_at(phi_opt - PI / n).min(arm_at(phi_opt + PI / n));
        let bound = (p_max + p_max * p_max * kappa_max(d)) * delta / (2.0 * l_min * l_min);
        prop_assert!(fwd_err <= bound && rev_err <= bound,
            "relative errors {fwd_err:e} / {rev_err:e}, bound {bound:e}");
    }
}

/// A random form error: orders 2..=150, each present with its cosine and sine within ±2 µm.
fn form_errors() -> impl Strategy<Value = Vec<cycloid::model::FormTerm>> {
    proptest::collection::btree_map(2usize..=150, (-2e-3..2e-3f64, -2e-3..2e-3f64), 1..80).prop_map(
        |terms| {
            terms
                .into_iter()
                .map(|(order, (cos_mm, sin_mm))| cycloid::model::FormTerm {
                    order,
                    cos_mm,
                    sin_mm,
                })
                .collect()
        },
    )
}

proptest! {
    /// The profile's table of the form error against the series summed directly, at random
    /// parameters. For w: within the table's stated bound (the Hermite remainder
    /// max|w⁽⁶⁾|·h⁶/46080, which does not depend on the code under test: Σk⁶|c_k| and h) and
    /// within a picometre. For w′ and w″: where w⁽⁶⁾ is constant the remainder is exactly
    /// w⁽⁶⁾h⁶s³(1−s)³/720, whose derivatives peak at 0.0481/720·h⁵ and 0.375/720·h⁴ times
    /// max|w⁽⁶⁾|; twice those cover the variation of w⁽⁶⁾ over an interval. Each adds the
    /// series' own rounding, k·ε per order times k^j.
    #[test]
    fn the_form_table_is_the_series(form in form_errors(), u in proptest::collection::vec(0.0..1.0f64, 200)) {
        use cycloid::geometry::form_error::FormError;
        let f = FormError::new(&form);
        let h = TAU / f.table_intervals() as f64;
        let m6: f64 = form.iter().map(|t| (t.order as f64).powi(6) * t.amplitude_mm()).sum();
        let top = form.iter().map(|t| t.order).max().unwrap() as f64;
        let sum: f64 = form.iter().map(|t| t.amplitude_mm()).sum();
        let rounding = |j: i32| 4.0 * top * f64::EPSILON * sum * top.powi(j);
        prop_assert!(f.table_error_bound_mm() <= 1e-12);
        for &x in &u {
            // Anywhere on the period and past it (the table wraps t).
            let t = (x - 0.25) * 3.0 * TAU;
            let (a, b) = (f.jet(t), f.series_jet(t));
            prop_assert!((a.0 - b.0).abs() <= f.table_error_bound_mm() + rounding(0), "w at {t}");
            let d1 = 2.0 * 0.0481 / 720.0 * m6 * h.powi(5) + rounding(1);
            prop_assert!((a.1 - b.1).abs() <= d1, "w' at {t}: {} vs {}", a.1, b.1);
            let d2 = 2.0 * 0.375 / 720.0 * m6 * h.powi(4) + rounding(2);
            prop_assert!((a.2 - b.2).abs() <= d2, "w'' at {t}: {} vs {}", a.2, b.2);
        }
    }
}
