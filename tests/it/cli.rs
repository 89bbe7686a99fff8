//! End-to-end tests of the `cycloid` binary: the exact text a user sees on stdout and stderr,
//! the exit code (0 pass, 1 a check failed, 2 invalid spec or computation) and the files
//! written. Specs are the shipped `specs/reducer.yaml` (the paper's design) with small edits,
//! written into a scratch directory under the system temp dir; the binary runs inside that
//! directory so messages name the spec as `spec.yaml`.

use crate::common;

use crate::common::{cycloid, Run as Output, Scratch, PAPER};
use serde_json::Value;
use std::path::Path;

/// Assert the exit code and the exact stdout and stderr.
#[track_caller]
fn assert_output(out: &Output, code: i32, stdout: &str, stderr: &str) {
    assert_eq!(
        (out.code, out.stdout.as_str(), out.stderr.as_str()),
        (Some(code), stdout, stderr),
        "\n--- stdout\n{}--- stderr\n{}",
        out.stdout,
        out.stderr
    );
}

/// `out` with its mass lines taken out (the terminal's `mass: …` after the headline results,
/// `--explain`'s `mass (…` and `  inertia at the input …`), each of which must be there once:
/// their numbers are held against the annulus's closed form in `mass_properties.rs`; the tests
/// here hold the rest of the text.
fn without_mass(mut out: Output) -> Output {
    let heads = ["mass: ", "mass (", "  inertia at the input"];
    let lines: Vec<&str> = out.stdout.lines().collect();
    let found = lines.iter().filter(|l| l.starts_with("mass")).count();
    assert_eq!(found, 1, "one mass line:\n{}", out.stdout);
    out.stdout = (lines.into_iter())
        .filter(|l| !heads.iter().any(|h| l.starts_with(h)))
        .map(|l| format!("{l}\n"))
        .collect();
    out
}

/// The paper's spec with each `(from, to)` replaced; `from` must occur exactly once, so an
/// edit can never silently do nothing.
fn paper_with(edits: &[(&str, &str)]) -> String {
    let mut text = PAPER.to_string();
    for (from, to) in edits {
        assert_eq!(
            text.matches(from).count(),
            1,
            "`{from}` must occur exactly once in the spec"
        );
        text = text.replacen(from, to, 1);
    }
    text
}

/// Write `spec` as `spec.yaml` in a scratch dir and run `cycloid check spec.yaml`.
fn check(spec: &str) -> Output {
    let dir = Scratch::new("check");
    dir.write("spec.yaml", spec);
    cycloid(&dir.path, &["check", "spec.yaml"])
}

/// `check` of a spec that must be rejected: exit 2, nothing on stdout, exactly this on stderr.
#[track_caller]
fn assert_rejected(spec: &str, stderr: &str) {
    assert_output(&check(spec), 2, "", &format!("{stderr}\n"));
}

// ---------------------------------------------------------------------------------------------
// check: verdicts

#[test]
fn shipped_spec_passes_with_the_table() {
    let out = cycloid(
        Path::new(env!("CARGO_MANIFEST_DIR")),
        &["check", "specs/reducer.yaml"],
    );
    assert_output(
        &without_mass(out),
        0,
        "cycloid check `paper-table-1`
check                   value       limit         verdict  where
rated/min_clearance_mm  0.03430 mm  ≥ 0.01500 mm  pass     roller 0 at crank 0.00°, tooth phase 0.000 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.1000° (error ≤ 1.538e-4 µm)
1 check: 1 passed, 0 failed
headline results:
scene `rated`:
  min clearance over the mesh  0.03430 mm  roller 0 at crank 0.00°, tooth phase 0.000 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.1000° (error ≤ 1.538e-4 µm)
PASS: 1 of 1 check passed
",
        "",
    );
}

/// A limit on the lost motion makes the clearance scene compute the backlash (nothing else in
/// the shipped spec reads it): the check and the summary show it. It cross-checks with the
/// first-order closed form (MODEL.md): the backlash is (ΔRrp − ΔRp·sqrt(1 − K1²))/(e·nc) =
/// (0.1593 − 0.125·0.7454)/18 rad = 757.8″ each way, 1516″ of lost motion; the exact 1511″
/// differs at second order of the modification.
#[test]
fn a_lost_motion_limit_computes_the_backlash() {
    let spec = paper_with(&[("limits:\n", "limits:\n  max_lost_motion_arcsec: 1500\n")]);
    assert_output(
        &without_mass(check(&spec)),
        1,
        "cycloid check `paper-table-1`
check                         value        limit          verdict  where
rated/max_lost_motion_arcsec  1511 arcsec  ≤ 1500 arcsec  FAIL     crank 18.00°, over the scene's 360 crank angles
rated/min_clearance_mm        0.03430 mm   ≥ 0.01500 mm   pass     roller 0 at crank 0.00°, tooth phase 0.000 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.1000° (error ≤ 1.538e-4 µm)
2 checks: 1 passed, 1 failed
headline results:
scene `rated`:
  min clearance over the mesh   0.03430 mm  roller 0 at crank 0.00°, tooth phase 0.000 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.1000° (error ≤ 1.538e-4 µm)
  max lost motion (unloaded)   1511 arcsec  crank 18.00°, over the scene's 360 crank angles
FAIL: 1 of 2 checks failed
",
        "",
    );
}

/// The paper's negative modification meets its own tip condition ΔRrp − ΔRp = 15 µm ≥ dt but
/// interferes by 23 µm at mid-flank (README): the whole-mesh check must catch it.
#[test]
fn paper_negative_modification_fails_with_exit_1() {
    let spec = paper_with(&[
        ("shift_mm: 0.125 ", "shift_mm: -0.15 "),
        ("equidistant_mm: 0.1593", "equidistant_mm: -0.135"),
    ]);
    assert_output(
        &without_mass(check(&spec)),
        1,
        "cycloid check `paper-table-1`
check                   value        limit         verdict  where
rated/min_clearance_mm  -0.02341 mm  ≥ 0.01500 mm  FAIL     roller 9 at crank 10.90°, tooth phase 0.137 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.1000° (error ≤ 7.415e-5 µm)
1 check: 0 passed, 1 failed
headline results:
scene `rated`:
  min clearance over the mesh  -0.02341 mm  roller 9 at crank 10.90°, tooth phase 0.137 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.1000° (error ≤ 7.415e-5 µm)
FAIL: 1 of 1 check failed
",
        "",
    );
}

/// Failures come first in the table, whatever the order of the scenes, the furthest outside
/// its limit first. With the negative modification, a scene of crank 0° alone (listed first)
/// and one of the whole mesh period: both report the smallest gap over the whole mesh,
/// −23.41 µm (crank 0° alone has −21.55 µm, which a limit of −22 µm passed before the minimum
/// was sought over the whole period); the lost motion is the scene's own (−502.2 arcsec at
/// crank 0°, passing ≤ −500, and −494.8 over the period, failing). The checks compare the
/// signed sum with the limit, but no line reads a negative lost motion: a negative sum is a
/// free play of 0 with an overlap, and the limit −500 an overlap of at least 500; the
/// headlines say each scene's sampling, since both scenes give the lost motion, the one-angle
/// scene naming its angle once.
#[test]
fn failed_rows_come_first() {
    let spec = paper_with(&[
        ("shift_mm: 0.125 ", "shift_mm: -0.15 "),
        ("equidistant_mm: 0.1593", "equidistant_mm: -0.135"),
        (
            "scenes:\n",
            "scenes:\n  - name: start\n    crank: { from_deg: 0.0, to_deg: 36.0, steps: 1 }\n    effects: [clearance]\n",
        ),
        (
            "min_clearance_mm: 0.015",
            "min_clearance_mm: -0.022\n  max_lost_motion_arcsec: -500.0",
        ),
    ]);
    assert_output(
        &without_mass(check(&spec)),
        1,
        "cycloid check `paper-table-1`
check                         value                                       limit                   verdict  where
rated/min_clearance_mm        -0.02341 mm                                 ≥ -0.02200 mm           FAIL     roller 9 at crank 10.90°, tooth phase 0.137 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.1000° (error ≤ 7.415e-5 µm)
start/min_clearance_mm        -0.02341 mm                                 ≥ -0.02200 mm           FAIL     roller 9 at crank 10.88°, tooth phase 0.137 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.3750° (error ≤ 0.001043 µm)
rated/max_lost_motion_arcsec  0 arcsec (preloaded: overlap 494.8 arcsec)  overlap ≥ 500.0 arcsec  FAIL     crank 31.60°, over the scene's 360 crank angles
start/max_lost_motion_arcsec  0 arcsec (preloaded: overlap 502.2 arcsec)  overlap ≥ 500.0 arcsec  pass     crank 0.00°, the scene's only crank angle
4 checks: 1 passed, 3 failed
headline results:
scene `start`:
  min clearance over the mesh  -0.02341 mm  roller 9 at crank 10.88°, tooth phase 0.137 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.3750° (error ≤ 0.001043 µm)
  max lost motion (unloaded)      0 arcsec  preloaded: no free play, the closing lags overlap by 502.2 arcsec (interference), crank 0.00°, the scene's only crank angle
scene `rated`:
  min clearance over the mesh  -0.02341 mm  roller 9 at crank 10.90°, tooth phase 0.137 (0 root, 0.5 tip), over the whole period of 36.00° sampled every 0.1000° (error ≤ 7.415e-5 µm)
  max lost motion (unloaded)      0 arcsec  preloaded: no free play, the closing lags overlap by 494.8 arcsec (interference), crank 31.60°, over the scene's 360 crank angles, every 0.1000°
FAIL: 3 of 4 checks failed
",
        "",
    );
}

// ---------------------------------------------------------------------------------------------
// check: spec errors, exact text (file:line:column: kind: key.path: message)

#[test]
fn misspelt_key_names_the_key_its_place_and_the_right_spelling() {
    assert_rejected(
        &paper_with(&[("roller_radius_mm: 3.0 ", "roller_radus_mm: 3.0 ")]),
        "spec.yaml:8:3: spec error: reducer.roller_radus_mm: unknown key; did you mean `roller_radius_mm`?",
    );
}

#[test]
fn misspelt_key_inside_a_flow_mapping_of_a_list_item() {
    assert_rejected(
        &paper_with(&[("steps: 360", "stepz: 360")]),
        "spec.yaml:25:43: spec error: scenes[0].crank.stepz: unknown key; did you mean `steps`?",
    );
}

#[test]
fn unknown_key_with_no_close_match_lists_the_keys() {
    assert_rejected(
        &paper_with(&[("steps: 360", "steps: 360, speed: 1")]),
        "spec.yaml:25:55: spec error: scenes[0].crank.speed: unknown key; the keys here are from_deg, to_deg, steps",
    );
}

#[test]
fn missing_key_names_the_mapping_and_the_key() {
    assert_rejected(
        &paper_with(&[(
            "  teeth: 9                       # nc, disc teeth; must equal rollers - 1\n",
            "",
        )]),
        "spec.yaml:4:3: spec error: reducer: missing required key `teeth`",
    );
}

#[test]
fn duplicate_key_points_at_the_second_one() {
    assert_rejected(
        &paper_with(&[("  rollers: 10 ", "  teeth: 9\n  rollers: 10 ")]),
        "spec.yaml:5:3: spec error: reducer.teeth: key appears twice",
    );
}

#[test]
fn wrong_type_says_what_was_expected_in_spec_terms() {
    assert_rejected(
        &paper_with(&[("teeth: 9 ", "teeth: nine ")]),
        "spec.yaml:4:10: spec error: reducer.teeth: invalid type: string \"nine\", expected an integer",
    );
    assert_rejected(
        &paper_with(&[("face_width_mm: 8.0", "face_width_mm: wide")]),
        "spec.yaml:9:18: spec error: reducer.face_width_mm: invalid type: string \"wide\", expected a number",
    );
}

/// A limit on a count is a whole number: the fewest rollers in contact cannot be 2.5, so such
/// a limit is refused at its key (line 28, the line added above `min_clearance_mm`) rather than
/// read as 3 or as 2.
#[test]
fn a_limit_on_a_count_must_be_a_whole_number() {
    assert_rejected(
        &paper_with(&[(
            "  min_clearance_mm: 0.015 ",
            "  min_rollers_in_contact: 2.5\n  min_clearance_mm: 0.015 ",
        )]),
        "spec.yaml:28:3: invalid value: limits.min_rollers_in_contact: must be a whole number of \
         at least 0, got 2.5",
    );
}

/// The undercut rule with its numbers, at the key to change. Rrp + ΔRrp = 10 + 0.1593.
#[test]
fn undercut_names_the_rule_and_the_numbers() {
    assert_rejected(
        &paper_with(&[("roller_radius_mm: 3.0 ", "roller_radius_mm: 10 ")]),
        "spec.yaml:8:3: impossible design: reducer.roller_radius_mm: undercut: the generating \
         roller radius Rrp + ΔRrp = 10.1593 mm is not smaller than the smallest convex radius of \
         curvature of the roller-centre locus, 9.6258 mm (at t = 9.673° from the tooth root); \
         the profile would have cusps",
    );
}

/// Without modification the smallest convex radius is the README's 9.554 mm at t ≈ 9.6°.
#[test]
fn undercut_of_the_unmodified_design_matches_the_readme() {
    let spec = paper_with(&[
        ("roller_radius_mm: 3.0 ", "roller_radius_mm: 10 "),
        ("shift_mm: 0.125 ", "shift_mm: 0 "),
        ("equidistant_mm: 0.1593", "equidistant_mm: 0"),
    ]);
    assert_rejected(
        &spec,
        "spec.yaml:8:3: impossible design: reducer.roller_radius_mm: undercut: the generating \
         roller radius Rrp + ΔRrp = 10.0000 mm is not smaller than the smallest convex radius of \
         curvature of the roller-centre locus, 9.5543 mm (at t = 9.614° from the tooth root); \
         the profile would have cusps",
    );
}

/// A crank bearing too soft for the torque, refused before any solve with the rule's numbers
/// (`spec::bearing_push`): the rated scene made loaded, 10 N·m on one disc of nc = 9 teeth at
/// e = 2 mm, loads the bearing tangentially by 10,000/(9·2) = 555.6 N on average, which moves
/// the centre of a 250 N/mm bearing by 2.222 mm > e; it needs more than 10,000/(9·4) =
/// 277.8 N/mm. The key is the line added under the scene's effects (line 27).
#[test]
fn a_crank_bearing_too_soft_for_the_torque_names_the_rule_and_the_numbers() {
    assert_rejected(
        &on_a_crank_bearing_of("250", &[]),
        "spec.yaml:27:5: impossible design: scenes[0].bearing_stiffness_n_per_mm: scene `rated`: \
         a crank bearing of 250 N/mm cannot hold the disc at 10 N·m: over a period the input \
         torque loads the disc's bearing tangentially by at least T/(N·nc·e) = 555.6 N on \
         average (N = 1, nc = 9, e = 2 mm), which moves its centre by at least 2.222 mm on \
         average, more than e: the disc would leave its mesh; the bearing needs more than \
         T/(N·nc·e²) = 277.8 N/mm",
    );
}

/// The paper's spec with `edits`, its scene computing the bearing on a compliant crank bearing
/// of `kb` N/mm (a line added under the scene's effects: line 27 without other edits).
fn on_a_crank_bearing_of(kb: &str, edits: &[(&str, &str)]) -> String {
    let bearing = format!("    effects: [bearing]\n    bearing_stiffness_n_per_mm: {kb}");
    let mut edits = edits.to_vec();
    edits.push(("    effects: [clearance]", &bearing));
    paper_with(&edits)
}

/// The rule's other wordings, numbers by hand: two discs on a duty cycle are judged at the
/// largest positive bin (30 N·m, bin 1; the −40 N·m bin is larger in size but not judged):
/// 30,000/(2·9·2) = 833.3 N, /250 = 3.333 mm, 30,000/(2·9·4) = 416.7 N/mm. A torque so small
/// that the numbers need their significant digits: 3/(9·2) = 0.1667 N, /0.05 = 3.333 mm, and
/// 3/36 = 0.083333… N/mm written rounded up, 0.08334 (rounded to nearest it would read
/// 0.08333, a stiffness that is not enough).
#[test]
fn a_crank_bearing_too_soft_names_the_most_loaded_disc_the_bin_and_rounds_the_need_up() {
    assert_rejected(
        &on_a_crank_bearing_of(
            "250",
            &[
                (
                    "  eccentricity_mm: 2.0 ",
                    "  discs: 2\n  eccentricity_mm: 2.0 ",
                ),
                (
                    "    output_torque_nm: 10.0 ",
                    "    duty_cycle:\n\
                 \x20     - { output_torque_nm: 5.0, input_speed_rpm: 1000.0, time_share: 0.3 }\n\
                 \x20     - { output_torque_nm: 30.0, input_speed_rpm: 1000.0, time_share: 0.3 }\n\
                 \x20     - { output_torque_nm: -40.0, input_speed_rpm: 1000.0, time_share: 0.4 }\n\
                 \x20   # ",
                ),
            ],
        ),
        "spec.yaml:32:5: impossible design: scenes[0].bearing_stiffness_n_per_mm: scene `rated`: \
         a crank bearing of 250 N/mm cannot hold the discs at 30 N·m (duty-cycle bin 1): over a \
         period the input torque loads the most loaded disc's bearing tangentially by at least \
         T/(N·nc·e) = 833.3 N on average (N = 2, nc = 9, e = 2 mm), which moves its centre by \
         at least 3.333 mm on average, more than e: that disc would leave its mesh; the bearing \
         needs more than T/(N·nc·e²) = 416.7 N/mm",
    );
    assert_rejected(
        &on_a_crank_bearing_of(
            "0.05",
            &[("output_torque_nm: 10.0 ", "output_torque_nm: 0.003 ")],
        ),
        "spec.yaml:27:5: impossible design: scenes[0].bearing_stiffness_n_per_mm: scene `rated`: \
         a crank bearing of 0.05 N/mm cannot hold the disc at 0.003 N·m: over a period the input \
         torque loads the disc's bearing tangentially by at least T/(N·nc·e) = 0.1667 N on \
         average (N = 1, nc = 9, e = 2 mm), which moves its centre by at least 3.333 mm on \
         average, more than e: the disc would leave its mesh; the bearing needs more than \
         T/(N·nc·e²) = 0.08334 N/mm",
    );
}

#[test]
fn rollers_must_be_teeth_plus_one() {
    assert_rejected(
        &paper_with(&[("rollers: 10 ", "rollers: 11 ")]),
        "spec.yaml:5:3: impossible design: reducer.rollers: rollers must equal teeth + 1 \
         (one-tooth-difference reducer): rollers = 11, teeth = 9",
    );
}

#[test]
fn sizes_must_be_positive() {
    assert_rejected(
        &paper_with(&[("face_width_mm: 8.0", "face_width_mm: 0")]),
        "spec.yaml:9:3: invalid value: reducer.face_width_mm: must be a positive number, got 0",
    );
    assert_rejected(
        &paper_with(&[("pin_radius_mm: 3.0", "pin_radius_mm: -3.0")]),
        "spec.yaml:13:5: invalid value: reducer.output_pins.pin_radius_mm: must be a positive number, got -3",
    );
}

#[test]
fn k1_must_be_below_one() {
    assert_rejected(
        &paper_with(&[("eccentricity_mm: 2.0 ", "eccentricity_mm: 3.0 ")]),
        "spec.yaml:6:3: impossible design: reducer.eccentricity_mm: short-amplitude coefficient \
         K1 = e·np/Rp = 3·10/30 = 1.0000 must be below 1 (the locus would loop)",
    );
}

/// K1 also with the shifted locus radius: Rp + ΔRp = 19 mm gives 2·10/19 > 1 although
/// e·np/Rp = 20/30 is fine.
#[test]
fn k1_of_the_shifted_locus_must_be_below_one() {
    assert_rejected(
        &paper_with(&[("shift_mm: 0.125 ", "shift_mm: -11 ")]),
        "spec.yaml:19:3: impossible design: modification.shift_mm: the shifted locus radius \
         Rp + ΔRp = 19.0000 mm gives K1 = 1.0526; it must stay below 1",
    );
}

#[test]
fn crank_needs_a_step() {
    assert_rejected(
        &paper_with(&[("steps: 360", "steps: 0")]),
        "spec.yaml:25:43: invalid value: scenes[0].crank.steps: a crank range needs at least 1 step, got 0",
    );
}

#[test]
fn crank_range_must_not_be_empty_or_reversed() {
    assert_rejected(
        &paper_with(&[("to_deg: 36.0", "to_deg: 0.0")]),
        "spec.yaml:25:29: invalid value: scenes[0].crank.to_deg: the crank range is empty: \
         to_deg = 0 must exceed from_deg = 0",
    );
    assert_rejected(
        &paper_with(&[("to_deg: 36.0", "to_deg: -10")]),
        "spec.yaml:25:29: invalid value: scenes[0].crank.to_deg: the crank range is empty: \
         to_deg = -10 must exceed from_deg = 0",
    );
}

/// Too many crank angles used to abort with a failed allocation; now it is a spec error.
#[test]
fn crank_steps_are_bounded_by_memory() {
    assert_rejected(
        &paper_with(&[("steps: 360", "steps: 100000000000")]),
        "spec.yaml:25:43: invalid value: scenes[0].crank.steps: at most 1000000 steps with 10 \
         rollers (rollers × steps ≤ 10000000), got 100000000000",
    );
}

/// The location is the unknown entry itself, in a flow list and in a block list.
#[test]
fn unknown_effect_points_at_the_entry() {
    assert_rejected(
        &paper_with(&[("effects: [clearance]", "effects: [clearance, stress]")]),
        "spec.yaml:26:26: invalid value: scenes[0].effects[1]: unknown effect `stress`; known \
         effects: clearance, roller_contact, output_pins, bearing, efficiency, strength, inertia",
    );
    assert_rejected(
        &paper_with(&[(
            "effects: [clearance]",
            "effects:\n      - clearance\n      - clearence",
        )]),
        "spec.yaml:28:9: invalid value: scenes[0].effects[1]: unknown effect `clearence`; did \
         you mean `clearance`?",
    );
}

/// Rrp = 9.3 mm is below the undercut radius (9.3 + 0.1593 < 9.6258) but the rollers, 18.6 mm
/// across, do not fit 18.541 mm apart.
#[test]
fn rollers_must_not_overlap() {
    assert_rejected(
        &paper_with(&[("roller_radius_mm: 3.0 ", "roller_radius_mm: 9.3 ")]),
        "spec.yaml:8:3: impossible design: reducer.roller_radius_mm: rollers overlap: the distance \
         between neighbouring roller centres, 2·Rp·sin(π/np) = 18.5410 mm, must exceed the roller \
         diameter 18.6000 mm",
    );
}

/// Holes of radius 3 + 2 on a 22 mm circle reach 27 mm; the root circle is
/// 30.125 − 2 − 3.1593 = 24.9657 mm.
#[test]
fn pin_holes_must_not_cut_the_tooth_root() {
    assert_rejected(
        &paper_with(&[("circle_radius_mm: 18.0", "circle_radius_mm: 22.0")]),
        "spec.yaml:12:5: impossible design: reducer.output_pins.circle_radius_mm: output-pin holes \
         cut into the tooth root: pin circle radius + hole radius = 22 + 5.0000 = 27.0000 mm \
         reaches the root radius of the profile, Rp + ΔRp − e − (Rrp + ΔRrp) = 24.9657 mm \
         (hole radius = pin radius + e + hole clearance)",
    );
}

/// A YAML syntax error has the parser's location and no key path (the typed pass would name
/// the last key it reached, which is not where the error is).
#[test]
fn yaml_syntax_error_has_the_parser_location_and_no_key_path() {
    assert_rejected(
        &paper_with(&[("teeth: 9 ", "teeth: [9 ")]),
        "spec.yaml:5:3: spec error: did not find expected ',' or ']', while parsing a flow \
         sequence at line 4 column 10",
    );
    assert_rejected(
        &paper_with(&[(
            "name: paper-table-1\nreducer:",
            "name: paper-table-1\n\treducer:",
        )]),
        "spec.yaml:3:1: spec error: found a tab character that violates indentation, while \
         scanning a plain scalar at line 2 column 7",
    );
}

#[test]
fn missing_file_is_an_io_error() {
    let dir = Scratch::new("missing");
    let out = cycloid(&dir.path, &["check", "no-such-spec.yaml"]);
    assert_eq!(out.code, Some(2), "{out:?}");
    assert_eq!(out.stdout, "");
    assert!(
        out.stderr
            .starts_with("i/o error: no-such-spec.yaml: No such file or directory"),
        "{out:?}"
    );
    assert_eq!(out.stderr.lines().count(), 1, "{out:?}");
}

#[test]
fn usage_errors_exit_2() {
    let dir = Scratch::new("usage");
    for args in [&[][..], &["check"], &["frobnicate", "spec.yaml"]] {
        let out = cycloid(&dir.path, args);
        assert_eq!(out.code, Some(2), "{args:?}: {out:?}");
        assert!(out.stderr.contains("Usage: cycloid"), "{args:?}: {out:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// No input makes the binary panic, abort or hang.

/// Each of these specs must be rejected with exit 2 and one non-empty line on stderr that is
/// not a panic, with nothing on stdout.
#[test]
fn malformed_specs_are_errors_never_panics() {
    let edit = |from: &str, to: &str| paper_with(&[(from, to)]);
    let cases: Vec<(&str, String)> = vec![
        ("empty file", String::new()),
        ("only a comment", "# nothing here\n".into()),
        ("null document", "~\n".into()),
        ("list at top level", "- name: a\n- name: b\n".into()),
        ("scalar at top level", "just a sentence\n".into()),
        ("two documents", format!("{PAPER}---\n{PAPER}")),
        // Deeper than serde_yaml's recursion limit (128). Not 10⁵: libyaml's scanner is
        // quadratic in the flow depth (10⁴ levels take 0.3 s, 10⁵ take 80 s).
        ("deep nesting", format!("name: {}\n", "[".repeat(10_000))),
        ("alias loop", "name: x\nreducer: &a [*a]\n".into()),
        (
            "NaN size",
            edit("face_width_mm: 8.0", "face_width_mm: .nan"),
        ),
        (
            "NaN eccentricity",
            edit("eccentricity_mm: 2.0 ", "eccentricity_mm: .nan "),
        ),
        (
            "NaN Poisson",
            edit("poisson_ratio: 0.3 ", "poisson_ratio: .nan "),
        ),
        ("NaN shift", edit("shift_mm: 0.125 ", "shift_mm: .nan ")),
        (
            "NaN rotation",
            edit("rotation_deg: 0.0", "rotation_deg: .nan"),
        ),
        ("NaN crank", edit("from_deg: 0.0", "from_deg: .nan")),
        (
            "NaN torque",
            edit("output_torque_nm: 10.0", "output_torque_nm: .nan"),
        ),
        (
            "NaN limit",
            edit("min_clearance_mm: 0.015", "min_clearance_mm: .nan"),
        ),
        (
            "infinite size",
            edit(
                "roller_circle_radius_mm: 30.0",
                "roller_circle_radius_mm: .inf",
            ),
        ),
        (
            "-infinite equidistant",
            edit("equidistant_mm: 0.1593", "equidistant_mm: -.inf"),
        ),
        (
            "infinite hole clearance",
            edit("hole_clearance_mm: 0.0", "hole_clearance_mm: .inf"),
        ),
        (
            "overflowing float",
            edit("face_width_mm: 8.0", "face_width_mm: 1e400"),
        ),
        (
            "huge integer",
            edit("teeth: 9 ", "teeth: 99999999999999999999 "),
        ),
        (
            "integer just past i64",
            edit("teeth: 9 ", "teeth: 9223372036854775808 "),
        ),
        (
            "huge negative integer",
            edit("teeth: 9 ", "teeth: -99999999999999999999 "),
        ),
        (
            "huge steps",
            edit("steps: 360", "steps: 9223372036854775807"),
        ),
        (
            "huge Rp",
            edit(
                "roller_circle_radius_mm: 30.0",
                "roller_circle_radius_mm: 1e300",
            ),
        ),
        (
            "huge eccentricity",
            edit("eccentricity_mm: 2.0 ", "eccentricity_mm: 1e300 "),
        ),
        (
            "huge roller",
            edit("roller_radius_mm: 3.0 ", "roller_radius_mm: 1e300 "),
        ),
        (
            "huge pin count",
            edit("count: 6 ", "count: 9223372036854775807 "),
        ),
        (
            "huge teeth",
            edit("teeth: 9 ", "teeth: 9223372036854775807 "),
        ),
        ("huge crank range", edit("to_deg: 36.0", "to_deg: 1e300")),
        (
            "huge rotation",
            edit("rotation_deg: 0.0", "rotation_deg: 1e300"),
        ),
        ("negative teeth", edit("teeth: 9 ", "teeth: -9 ")),
        ("negative rollers", edit("rollers: 10 ", "rollers: -10 ")),
        ("negative pin count", edit("count: 6 ", "count: -6 ")),
        ("negative steps", edit("steps: 360", "steps: -360")),
        (
            "i64::MIN steps",
            edit("steps: 360", "steps: -9223372036854775808"),
        ),
        ("zero pins", edit("count: 6 ", "count: 0 ")),
        (
            "string for a number",
            edit("eccentricity_mm: 2.0 ", "eccentricity_mm: two "),
        ),
        ("string for a count", edit("steps: 360", "steps: many")),
        (
            "list for a number",
            edit("pin_radius_mm: 3.0", "pin_radius_mm: [3.0]"),
        ),
        (
            "mapping for a number",
            edit("pin_radius_mm: 3.0", "pin_radius_mm: {mm: 3}"),
        ),
        (
            "null for a number",
            edit("pin_radius_mm: 3.0", "pin_radius_mm: ~"),
        ),
        ("float for a count", edit("teeth: 9 ", "teeth: 9.5 ")),
        (
            "number for the effects list",
            edit("effects: [clearance]", "effects: 3"),
        ),
        ("empty effects", edit("effects: [clearance]", "effects: []")),
        ("number for scenes", edit("scenes:\n", "scenes: 3\nx:\n")),
        ("empty name", edit("name: paper-table-1", "name: ''")),
        ("empty scene name", edit("name: rated", "name: ' '")),
        (
            "Poisson 0.5",
            edit("poisson_ratio: 0.3 ", "poisson_ratio: 0.5 "),
        ),
        (
            "negative Young",
            edit("youngs_modulus_gpa: 206.0", "youngs_modulus_gpa: -206.0"),
        ),
        (
            "negative equidistant radius",
            edit("equidistant_mm: 0.1593", "equidistant_mm: -5"),
        ),
        (
            "unknown contact law",
            edit(
                "effects: [clearance]",
                "effects: [clearance]\n    contact_law: glue",
            ),
        ),
        (
            "zero bearing stiffness",
            edit(
                "effects: [clearance]",
                "effects: [clearance]\n    bearing_stiffness_n_per_mm: 0",
            ),
        ),
        (
            "negative rollers in contact",
            edit("min_clearance_mm: 0.015", "min_rollers_in_contact: -1"),
        ),
    ];
    let mut cases: Vec<(&str, Vec<u8>)> = cases
        .into_iter()
        .map(|(what, text)| (what, text.into_bytes()))
        .collect();
    cases.push(("not UTF-8", b"name: \xff\xfe\n".to_vec()));
    let dir = Scratch::new("malformed");
    let mut failures = Vec::new();
    for (i, (what, text)) in cases.iter().enumerate() {
        let name = format!("case{i}.yaml");
        dir.write(&name, text);
        let out = cycloid(&dir.path, &["check", &name]);
        let line = out.stderr.strip_suffix('\n').unwrap_or(&out.stderr);
        let ok = out.code == Some(2)
            && out.stdout.is_empty()
            && !line.trim().is_empty()
            && !line.contains('\n')
            && !line.contains("panicked");
        if !ok {
            failures.push(format!("{what}: {out:?}"));
        }
    }
    assert!(
        failures.is_empty(),
        "{} case(s) not rejected cleanly:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

// ---------------------------------------------------------------------------------------------
// check --json

fn json_of(dir: &Scratch, spec: &str) -> (Output, Value) {
    dir.write("spec.yaml", spec);
    let out = cycloid(&dir.path, &["check", "spec.yaml", "--json", "results.json"]);
    let text = dir.read("results.json");
    assert!(
        !text.contains("NaN") && !text.contains("Infinity"),
        "{text}"
    );
    let doc: Value = serde_json::from_str(&text).expect("results.json is JSON");
    (out, doc)
}

fn keys(v: &Value) -> Vec<&str> {
    let mut k: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    k.sort_unstable();
    k
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap_or_else(|| panic!("not a number: {x}")))
        .collect()
}

/// Schema 1 with the documented keys, [roller][angle] arrays sized rollers × steps per scene,
/// numbers only (no null, no NaN), and a minimum over the whole mesh: for the scene whose
/// angles cover the mesh period it is the minimum of its array and sits where
/// `min_clearance_at` says; the coarse scene (7 angles) reports the same minimum (within the
/// bound `min_clearance_over` states), below its own array's, at crank 0° (a tip, where the
/// paper's optimum has its 34.30 µm).
#[test]
fn json_has_schema_1_sized_arrays_and_consistent_minimum() {
    let dir = Scratch::new("json");
    let spec = paper_with(&[(
        "limits:",
        "  - name: coarse\n    crank: { from_deg: 5.0, to_deg: 41.0, steps: 7 }\n    effects: [clearance]\nlimits:",
    )]);
    let (out, doc) = json_of(&dir, &spec);
    assert_eq!(out.code, Some(0), "{out:?}");
    assert_eq!(
        keys(&doc),
        [
            "checks",
            "disc_centroid_offset_mm",
            "disc_inertia_kgm2",
            "disc_mass_kg",
            "golden",
            "input_inertia_kgm2",
            "name",
            "passed",
            "scenes",
            "schema",
            "spec_path",
            "spec_sha256",
            "studies",
            "summary",
            "tool_version"
        ]
    );
    assert_eq!(doc["schema"], 1);
    assert_eq!(doc["name"], "paper-table-1");
    assert_eq!(doc["passed"], true);
    let checks = doc["checks"].as_array().unwrap();
    assert_eq!(checks.len(), 2);
    for c in checks {
        assert_eq!(
            keys(c),
            ["at", "id", "kind", "limit", "passed", "unit", "value"]
        );
    }
    let scenes = doc["scenes"].as_array().unwrap();
    assert_eq!(scenes.len(), 2);
    for (scene, steps, from, step) in [
        (&scenes[0], 360, 0.0, 0.1),
        (&scenes[1], 7, 5.0, 36.0 / 7.0),
    ] {
        let name = scene["name"].as_str().unwrap();
        assert_eq!(
            keys(scene),
            [
                "backlash_arcsec",
                "backlash_reverse_arcsec",
                "clearance_mm",
                "crank_deg",
                "lost_motion_arcsec",
                "max_lost_motion_arcsec",
                "min_clearance_at",
                "min_clearance_mm",
                "min_clearance_over",
                "name"
            ],
            "{name}"
        );
        let crank = numbers(&scene["crank_deg"]);
        assert_eq!(crank.len(), steps, "{name}");
        for (k, a) in crank.iter().enumerate() {
            assert!(
                (a - (from + step * k as f64)).abs() < 1e-9,
                "{name}: crank {k} = {a}"
            );
        }
        for key in [
            "backlash_arcsec",
            "backlash_reverse_arcsec",
            "lost_motion_arcsec",
        ] {
            assert_eq!(numbers(&scene[key]).len(), steps, "{name}: {key}");
        }
        let gaps: Vec<Vec<f64>> = scene["clearance_mm"]
            .as_array()
            .unwrap()
            .iter()
            .map(numbers)
            .collect();
        assert_eq!(gaps.len(), 10, "{name}: one row per roller");
        assert!(gaps.iter().all(|row| row.len() == steps), "{name}");
        let min = scene["min_clearance_mm"].as_f64().unwrap();
        let smallest = gaps.iter().flatten().copied().fold(f64::INFINITY, f64::min);
        let at = &scene["min_clearance_at"];
        assert_eq!(keys(at), ["crank_deg", "roller", "tooth_phase"]);
        let over = &scene["min_clearance_over"];
        assert_eq!(keys(over), ["error_bound_mm", "period_deg", "step_deg"]);
        assert!((over["period_deg"].as_f64().unwrap() - 36.0).abs() < 1e-9);
        let bound = over["error_bound_mm"].as_f64().unwrap();
        // The accuracy ladder's default clearance tolerance, 0.1 µm.
        assert!((0.0..=1e-4).contains(&bound), "{name}: bound {bound}");
        if steps == 360 {
            assert_eq!(
                min, smallest,
                "{name}: min_clearance_mm is the smallest gap"
            );
            let roller = at["roller"].as_u64().unwrap() as usize;
            let k = crank
                .iter()
                .position(|a| (a - at["crank_deg"].as_f64().unwrap()).abs() < 1e-9)
                .expect("min_clearance_at.crank_deg is one of crank_deg");
            assert_eq!(
                gaps[roller][k], min,
                "{name}: min_clearance_at points at the minimum"
            );
        } else {
            let whole = scenes[0]["min_clearance_mm"].as_f64().unwrap();
            assert!(
                min < smallest && (min - whole).abs() <= bound,
                "{name}: {min}"
            );
            assert_eq!(at["crank_deg"], 0.0, "{name}");
        }
        let check = checks
            .iter()
            .find(|c| c["id"] == format!("{name}/min_clearance_mm"))
            .unwrap();
        assert_eq!(check["value"].as_f64().unwrap(), min);
        assert_eq!(check["limit"], 0.015);
        assert_eq!(check["passed"], true);
    }
}

/// `summary` holds, per scene, the registry's headline scalars (`quantity::SUMMARY`) the scene
/// computed, each equal to the scene's own value under the same key and described by the
/// registry's label and unit; `studies` holds each study's optimum as `cycloid optimise`
/// prints it (variables to 6 decimals, objective to 4 digits, evaluations exactly) with its
/// constraints, whose margins are value − bound or bound − value and satisfied when ≥ 0.
#[test]
fn json_has_the_summary_of_each_scene_and_the_result_of_each_study() {
    let dir = Scratch::new("json-summary");
    let out = cycloid(
        Path::new(env!("CARGO_MANIFEST_DIR")),
        &[
            "check",
            "specs/paper.yaml",
            "--json",
            &dir.join("r.json").display().to_string(),
        ],
    );
    assert_eq!(out.code, Some(0), "{out:?}");
    let doc: Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let scenes = doc["scenes"].as_array().unwrap();
    let summary = doc["summary"].as_array().unwrap();
    assert_eq!(summary.len(), scenes.len());
    let mut headlines = 0;
    for (s, scene) in summary.iter().zip(scenes) {
        assert_eq!(s["scene"], scene["name"]);
        for h in s["headlines"].as_array().unwrap() {
            assert_eq!(keys(h), ["at", "key", "label", "unit", "value"]);
            let key = h["key"].as_str().unwrap();
            let q = cycloid::model::quantity::find(key).unwrap();
            assert!(cycloid::model::quantity::SUMMARY.contains(&q), "{key}");
            assert_eq!(
                (h["label"].as_str(), h["unit"].as_str()),
                (Some(q.label), Some(q.unit))
            );
            assert_eq!(h["value"], scene[key], "{key}");
            headlines += 1;
        }
    }
    // mesh: clearance and lost motion; rated and study: the loaded ones.
    assert!(headlines >= 10, "{headlines}");
    let studies = doc["studies"].as_array().unwrap();
    let names: Vec<&str> = studies
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "positive-ratio",
            "positive-te",
            "negative-ratio",
            "negative-te"
        ]
    );
    let study = &studies[0];
    let printed = cycloid(
        Path::new(env!("CARGO_MANIFEST_DIR")),
        &["optimise", "specs/paper.yaml", "--study", "positive-ratio"],
    )
    .stdout;
    let line = printed
        .lines()
        .find(|l| l.trim_start().starts_with("optimum "))
        .unwrap();
    let variables = &study["variables"];
    assert_eq!(keys(variables), ["equidistant_mm", "shift_mm"]);
    for key in ["shift_mm", "equidistant_mm"] {
        let value = format!("{key} {:.6}", variables[key].as_f64().unwrap());
        assert!(line.contains(&value), "`{line}` lacks `{value}`");
    }
    let objective = study["objective_value"].as_f64().unwrap();
    assert!(
        line.contains(&format!("objective {objective:.5}")),
        "{line}: {objective}"
    );
    assert_eq!(study["objective"][0]["name"], "ratio_fluctuation");
    assert_eq!(
        study["objective"][0]["value"], study["objective_value"],
        "weight 1"
    );
    let evaluations = study["evaluations"].as_u64().unwrap();
    assert!(
        printed.contains(&format!("{evaluations} evaluations")),
        "{printed}"
    );
    assert_eq!(study["feasible"], true);
    let constraints = study["constraints"].as_array().unwrap();
    assert_eq!(constraints.len(), 3);
    for c in constraints {
        let (value, bound, margin) = (
            c["value"].as_f64().unwrap(),
            c["bound"].as_f64().unwrap(),
            c["margin"].as_f64().unwrap(),
        );
        // Exactly one of the two differences, as the optimiser computed it.
        assert!(margin == value - bound || margin == bound - value, "{c}");
        assert_eq!(c["satisfied"], margin >= 0.0, "{c}");
        let name = c["name"].as_str().unwrap();
        assert!(printed.contains(name), "{name}");
    }
    // What the objective hides and how good the answer is, as the optimiser prints them.
    let clearance_um = study["min_clearance_mm"].as_f64().unwrap() * 1e3;
    assert!(
        line.contains(&format!("min clearance {clearance_um:.2} µm")),
        "{line}"
    );
    let lost = study["lost_motion_arcsec"].as_f64().unwrap();
    assert!(
        line.contains(&format!("lost motion {lost:.1} arcsec")),
        "{line}: {lost}"
    );
    let v = &study["verification"];
    assert_eq!(
        (v["steps"].as_u64(), v["points"].as_u64()),
        (Some(41), Some(1681))
    );
    let margin = v["margin"].as_f64().unwrap();
    assert!(
        margin >= 0.0,
        "a grid point beats the optimum by {}",
        -margin
    );
    assert!(
        printed.contains(&format!("is higher by {margin:.6}")),
        "{printed}: {margin}"
    );
}

#[test]
fn json_passed_is_false_when_the_exit_code_is_1() {
    let dir = Scratch::new("json-fail");
    let spec = paper_with(&[
        ("shift_mm: 0.125 ", "shift_mm: -0.15 "),
        ("equidistant_mm: 0.1593", "equidistant_mm: -0.135"),
    ]);
    let (out, doc) = json_of(&dir, &spec);
    assert_eq!(out.code, Some(1), "{out:?}");
    assert_eq!(doc["passed"], false);
    assert_eq!(doc["checks"][0]["passed"], false);
    let value = doc["checks"][0]["value"].as_f64().unwrap();
    assert!((value - -0.02341).abs() < 5e-6, "{value}");
}

#[test]
fn json_is_not_written_for_an_invalid_spec() {
    let dir = Scratch::new("json-invalid");
    dir.write("spec.yaml", paper_with(&[("rollers: 10 ", "rollers: 11 ")]));
    let out = cycloid(&dir.path, &["check", "spec.yaml", "--json", "results.json"]);
    assert_eq!(out.code, Some(2), "{out:?}");
    assert!(!dir.exists("results.json"));
}

// ---------------------------------------------------------------------------------------------
// check --explain

/// The plan: what each scene computes and why, what it skips, which limits apply. A scene
/// asking for `bearing` pulls in what bearing needs, and `min_clearance_mm` applies only to the
/// scene that computes clearance, over the whole period of the gaps (one mesh period, 36°).
#[test]
fn explain_prints_the_plan() {
    let spec = paper_with(&[(
        "limits:",
        "  - name: loaded\n    output_torque_nm: 25\n    crank: { from_deg: 0.0, to_deg: 36.0, steps: 4 }\n    effects: [bearing]\nlimits:",
    )]);
    let dir = Scratch::new("explain");
    dir.write("spec.yaml", spec);
    let out = cycloid(&dir.path, &["check", "spec.yaml", "--explain"]);
    assert_output(
        &without_mass(out),
        0,
        "spec `paper-table-1`: 2 scene(s)
reducer: 1 disc

scene `rated`: output torque 10 N·m, 360 crank angles from 0.0000° in steps of 0.1000°, exact geometry
  note    min clearance over the whole period of the gaps (36.00° of crank), whatever crank angles the scene samples
  compute clearance       asked for by the scene
  skip    backlash (part of clearance; no limit, golden or output file reads it)
  skip    roller_contact, output_pins, bearing (not asked for)
  limits  min_clearance_mm

scene `loaded`: output torque 25 N·m, 4 crank angles from 0.0000° in steps of 9.0000°, exact geometry
  contact law paper_linear, crank bearing rigid
  compute roller_contact  needed by bearing
  compute output_pins     needed by bearing
  compute bearing         asked for by the scene
  skip    clearance (not asked for)
",
        "",
    );
}

/// A scene that computes `strength` lists, in its plan, each formula it will use with its
/// source and this design's numbers (the passes per crank turn np/nc = 10/9 of the paper's
/// nc = 9), and skips, saying why, each figure the spec gives no input for.
#[test]
fn explain_lists_the_strength_formulas() {
    let shipped = include_str!("../../specs/reducer-strength.yaml");
    let dir = Scratch::new("explain-strength");
    let plan = |text: &str| {
        dir.write("spec.yaml", text);
        let out = cycloid(&dir.path, &["check", "spec.yaml", "--explain"]);
        assert_eq!((out.code, out.stderr.as_str()), (Some(0), ""), "{out:?}");
        without_mass(out).stdout
    };
    let head = |crank: &str| {
        format!(
            "spec `paper-table-1-strength`: 1 scene(s)
reducer: 1 disc

scene `rated`: output torque 20 N·m, {crank}, exact geometry
  contact law paper_linear, crank bearing rigid
  compute roller_contact  needed by strength
  compute output_pins     needed by strength
  compute bearing         needed by strength
  compute strength        asked for by the scene
"
        )
    };
    assert_eq!(
        plan(shipped),
        head("1080 crank angles from 0.0000° in steps of 0.1000°")
            + "  formula pin bending σ_b = 32·M/(π·d³), d = 6 mm (the pin that bends), M = |Σ F_k·a_k| at the clamp (cantilever, Roark Table 8.1 case 1a); F_k disc k's pin force at a_k = 10 mm from the flange
  formula pin shear τ = 4·V/(3·A), A = π·d²/4, at the largest shear force V along the pin (the peak of the round section, Jourawski)
  formula pin bending safety = yield/σ_b, yield 1400 MPa (the rollers' material)
  formula contact fatigue of disc and rollers N(p) = 5e7·(1500 MPa/p)^13.2 cycles to failure at the Hertz pressure p (Basquin's form)
  formula passes per crank turn: each disc lobe np/nc = 10/9 = 1.111 (the load turns 1 + 1/nc times in the disc), each roller 1 per disc track
  formula life = N(p)/(passes·n·60) h at n = 1500 rpm, p the largest Hertz pressure over the scene's whole periods
  formula static safety of the crank bearing s0 = C0/max |Fb|, C0 = 14000 N, max |Fb| the largest crank-bearing force of the scene (ISO 76)
  skip    clearance, inertia (not asked for)
  limits  max_pin_bending_stress_mpa, min_pin_bending_safety, min_contact_fatigue_life_h, min_static_safety
"
    );
    // A propped pin, no yield strength, no C0, part of a period: no limits, so the spec is
    // valid, and the plan says what it cannot judge.
    let mut text = shipped.split("limits:").next().unwrap_or("").to_string();
    for (from, to) in [
        ("kind: cantilever", "kind: both_ends"),
        ("    yield_strength_mpa: 1400.0\n", ""),
        ("    static_load_rating_n: 14000.0", "    # no C0"),
        ("to_deg: 108.0, steps: 1080", "to_deg: 50.0, steps: 500"),
    ] {
        assert_eq!(text.matches(from).count(), 1, "{from}");
        text = text.replacen(from, to, 1);
    }
    assert_eq!(
        plan(&text),
        head("500 crank angles from 0.0000° in steps of 0.1000°")
            + "  formula pin bending σ_b = 32·M/(π·d³), d = 6 mm (the pin that bends), M the larger of the moment at the clamp, F·a·(L − a)·(2L − a)/(2L²) for one load, and the moment under each load, R·F·(L − a) with the prop's share R = a²·(3L − a)/(2L³), L = 14 mm (propped cantilever, Roark Table 8.1 case 1c); F_k disc k's pin force at a_k = 10 mm from the flange
  formula pin shear τ = 4·V/(3·A), A = π·d²/4, at the largest shear force V along the pin (the peak of the round section, Jourawski)
  skip    pin bending safety: yield_strength_mpa not given (reducer.roller_material, or reducer.material without it)
  skip    contact fatigue life: the crank range is not a whole number of periods of the reducer as run (108.0°): the largest pressure of part of a period is not the reducer's
  skip    static safety: reducer.crank_bearing.static_load_rating_n not given
  skip    clearance, inertia (not asked for)
"
    );
}

/// The backlash (the closing lags of every roller) is computed when something reads it, and
/// `--explain` says what: a limit, a golden of the scene, the results JSON or the design review
/// (which read every quantity). A golden of another scene does not ask for it here.
#[test]
fn explain_says_what_reads_the_backlash() {
    let dir = Scratch::new("explain-backlash");
    dir.write(
        "golden/backlash_arcsec.csv",
        "crank_deg,backlash_arcsec\n0,1\n",
    );
    let explain = |spec: &str, args: &[&str]| {
        dir.write("spec.yaml", spec);
        let out = cycloid(
            &dir.path,
            &[&["check", "spec.yaml", "--explain"], args].concat(),
        );
        assert_eq!(out.code, Some(0), "{out:?}");
        out.stdout
            .lines()
            .find(|l| l.contains("backlash"))
            .unwrap_or("")
            .to_string()
    };
    let skip = "  skip    backlash (part of clearance; no limit, golden or output file reads it)";
    let read_by =
        |what: &str| format!("  compute backlash        part of clearance, read by {what}");
    assert_eq!(explain(PAPER, &[]), skip);
    assert_eq!(explain(PAPER, &["--json", "r.json"]), read_by("--json"));
    assert_eq!(explain(PAPER, &["--report", "review"]), read_by("--report"));
    let limit = paper_with(&[("limits:\n", "limits:\n  max_lost_motion_arcsec: 2000\n")]);
    assert_eq!(
        explain(&limit, &["--json", "r.json"]),
        read_by("limit max_lost_motion_arcsec, --json")
    );
    let golden = |scene: &str| {
        format!(
            "{PAPER}golden:\n  - {{ scene: {scene}, quantity: lost_motion_arcsec, file: golden/backlash_arcsec.csv, tolerance: {{ abs: 1.0 }} }}\n"
        )
    };
    assert_eq!(
        explain(&golden("rated"), &[]),
        read_by("golden lost_motion_arcsec")
    );
    let two_scenes = golden("other").replace(
        "limits:",
        "  - name: other\n    crank: { from_deg: 0.0, to_deg: 36.0, steps: 4 }\n    effects: [clearance]\nlimits:",
    );
    assert_eq!(explain(&two_scenes, &[]), skip);
}

/// `--explain` of a spec with a measured disc ends by saying that every scene runs on the disc
/// identified from the file the spec names (`measured_profile.file`, relative to the spec's
/// folder, shown as found from where the tool runs), in exact geometry: the run identifies it
/// before any scene (`engine::as_built`).
#[test]
fn explain_says_the_scenes_run_on_the_measured_disc() {
    let out = cycloid(
        Path::new(env!("CARGO_MANIFEST_DIR")),
        &["check", "specs/reducer-measured.yaml", "--explain"],
    );
    assert_eq!(out.code, Some(0), "{out:?}");
    assert!(
        out.stdout.ends_with(
            "\n\nas built: every scene runs on the disc identified from \
             `specs/measured/reducer-disc.csv` (its modification and form error), exact geometry\n"
        ),
        "{}",
        out.stdout
    );
}

/// `--explain` computes nothing: a design whose check fails (exit 1) explains with exit 0, no
/// table, and no results file even with `--json`.
#[test]
fn explain_computes_nothing() {
    let spec = paper_with(&[
        ("shift_mm: 0.125 ", "shift_mm: -0.15 "),
        ("equidistant_mm: 0.1593", "equidistant_mm: -0.135"),
    ]);
    let dir = Scratch::new("explain-nothing");
    dir.write("spec.yaml", spec);
    let out = cycloid(
        &dir.path,
        &["check", "spec.yaml", "--explain", "--json", "results.json"],
    );
    assert_eq!(out.code, Some(0), "{out:?}");
    assert!(
        out.stdout.starts_with("spec `paper-table-1`: 1 scene(s)\n"),
        "{out:?}"
    );
    assert!(
        !out.stdout.contains("verdict") && !out.stdout.contains("FAIL"),
        "{out:?}"
    );
    assert_eq!(out.stderr, "");
    assert!(!dir.exists("results.json"));
}

/// An invalid spec is still an error under `--explain`.
#[test]
fn explain_still_validates_the_spec() {
    let dir = Scratch::new("explain-invalid");
    dir.write("spec.yaml", paper_with(&[("steps: 360", "steps: 0")]));
    let out = cycloid(&dir.path, &["check", "spec.yaml", "--explain"]);
    assert_output(
        &out,
        2,
        "",
        "spec.yaml:25:43: invalid value: scenes[0].crank.steps: a crank range needs at least 1 step, got 0\n",
    );
}

// ---------------------------------------------------------------------------------------------
// profile

fn rows(csv: &str) -> Vec<Vec<f64>> {
    csv.lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|x| {
                    x.parse::<f64>()
                        .unwrap_or_else(|_| panic!("bad CSV row {l}"))
                })
                .collect()
        })
        .collect()
}

/// Both files, with as many points as reported. The profile runs from the root (on +x, radius
/// Rp + ΔRp − e − (Rrp + ΔRrp) = 24.9657 mm) to the tips (Rp + ΔRp + e − (Rrp + ΔRrp) =
/// 28.9657 mm).
#[test]
fn profile_writes_csv_and_dxf() {
    let dir = Scratch::new("profile");
    dir.write("spec.yaml", PAPER);
    let out = cycloid(
        &dir.path,
        &[
            "profile",
            "spec.yaml",
            "--csv",
            "disc.csv",
            "--dxf",
            "disc.dxf",
            "--tolerance-um",
            "0.5",
        ],
    );
    assert_output(
        &out,
        0,
        "profile of `paper-table-1`: 1737 points, chordal error <= 0.5 um\n",
        "",
    );
    let csv = dir.read("disc.csv");
    assert_eq!(
        csv.lines().find(|l| !l.starts_with('#')),
        Some("x_mm,y_mm,normal_x,normal_y,curvature_per_mm")
    );
    let points = rows(&csv);
    assert_eq!(points.len(), 1737);
    assert!(points
        .iter()
        .all(|r| r.len() == 5 && r.iter().all(|x| x.is_finite())));
    assert_eq!(&points[0][..4], &[24.9657, 0.0, 1.0, 0.0]);
    let radii: Vec<f64> = points.iter().map(|r| r[0].hypot(r[1])).collect();
    let (lo, hi) = radii.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| {
        (lo.min(r), hi.max(r))
    });
    assert!((lo - 24.9657).abs() < 1e-6, "root radius {lo}");
    assert!((hi - 28.9657).abs() < 5e-4, "tip radius {hi}");
    for r in &points {
        let n = r[2].hypot(r[3]);
        assert!((n - 1.0).abs() < 1e-9, "normal of length {n}");
    }

    let dxf = dir.read("disc.dxf");
    let lines: Vec<&str> = dxf.lines().map(str::trim).collect();
    assert_eq!(lines.iter().filter(|l| **l == "VERTEX").count(), 1737);
    let polyline = lines
        .iter()
        .position(|l| *l == "POLYLINE")
        .expect("a POLYLINE");
    let flags = lines[polyline + 1..]
        .chunks(2)
        .take_while(|pair| pair[0] != "0")
        .find(|pair| pair[0] == "70")
        .expect("POLYLINE flags");
    assert_eq!(flags[1], "1", "the polyline is closed");
    assert_eq!(lines.last(), Some(&"EOF"));
}

#[test]
fn profile_tolerance_must_be_positive_and_not_absurdly_fine() {
    let dir = Scratch::new("profile-tol");
    dir.write("spec.yaml", PAPER);
    for (tol, message) in [
        (
            "0",
            "invalid value: --tolerance-um must be a positive number, got 0\n",
        ),
        (
            "-1",
            "invalid value: --tolerance-um must be a positive number, got -1\n",
        ),
        (
            "NaN",
            "invalid value: --tolerance-um must be a positive number, got NaN\n",
        ),
        (
            "1e-12",
            "invalid value: --tolerance-um must be at least 0.001 (1 nm), got 1e-12\n",
        ),
    ] {
        let out = cycloid(
            &dir.path,
            &[
                "profile",
                "spec.yaml",
                "--csv",
                "disc.csv",
                "--dxf",
                "disc.dxf",
                "--tolerance-um",
                tol,
            ],
        );
        assert_output(&out, 2, "", message);
        assert!(!dir.exists("disc.csv") && !dir.exists("disc.dxf"), "{tol}");
    }
}

#[test]
fn profile_of_an_invalid_spec_is_a_located_error() {
    let dir = Scratch::new("profile-invalid");
    dir.write(
        "spec.yaml",
        paper_with(&[("roller_radius_mm: 3.0 ", "roller_radus_mm: 3.0 ")]),
    );
    let out = cycloid(&dir.path, &["profile", "spec.yaml", "--csv", "disc.csv"]);
    assert_output(
        &out,
        2,
        "",
        "spec.yaml:8:3: spec error: reducer.roller_radus_mm: unknown key; did you mean `roller_radius_mm`?\n",
    );
    assert!(!dir.exists("disc.csv"));
}

/// A spec with nothing to check says so instead of an empty table, and still shows what it
/// computed (the headline results).
#[test]
fn a_spec_without_checks_says_so_and_shows_its_results() {
    let dir = Scratch::new("no-checks");
    let spec = common::PaperSpec::new().rated_period(36);
    dir.write("s.yaml", spec.text());
    let run = cycloid(&dir.path, &["check", "s.yaml"]);
    assert_eq!(run.code, Some(0), "{run:?}");
    let lines: Vec<&str> = run.stdout.lines().collect();
    assert_eq!(
        lines[1],
        "no checks: the spec sets no limits, golden curves or studies"
    );
    assert_eq!(lines[2], "headline results:");
    assert!(!run.stdout.contains("check  value"), "{}", run.stdout);
}

/// A spec that sets no limits, golden curves or studies judges nothing: the run ends saying so
/// (exit 0), not "PASS: 0 of 0 checks passed" (issue 44 item 4).
#[test]
fn a_spec_without_limits_says_nothing_was_judged() {
    let spec = common::PaperSpec::new().rated_period(4);
    let out = check(spec.text());
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    assert_eq!(
        out.stdout.lines().last(),
        Some("NOTHING JUDGED: 0 checks, so neither PASS nor FAIL"),
        "{}",
        out.stdout
    );
}

/// `cycloid check` given a requirements file says what it is and which command reads it, at
/// its first key a spec lacks (issue 44 item 3), instead of "ratio: unknown key".
#[test]
fn a_requirements_file_given_to_check_points_to_design() {
    let text = std::fs::read_to_string(format!(
        "{}/specs/requirements-robot-joint.yaml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    // The `ratio` key's line, counted here: the comment lines and `name` before it.
    let line = 1 + text[..text.find("\nratio:").unwrap() + 1]
        .matches('\n')
        .count();
    let dir = Scratch::new("check-requirements");
    dir.write("joint.yaml", &text);
    assert_output(
        &cycloid(&dir.path, &["check", "joint.yaml"]),
        2,
        "",
        &format!(
            "joint.yaml:{line}:1: spec error: this is a requirements file (top-level `ratio`, no \
             `reducer`), not a spec: `cycloid design joint.yaml` searches the designs that meet \
             it\n"
        ),
    );
}
