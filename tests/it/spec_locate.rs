//! `spec::locate`: the 1-based line and column of a key path in YAML text, used to place value
//! and design-rule errors (which serde cannot locate) at the key the user has to change.

use cycloid::spec::{locate, parse};

/// A spec mixing block and flow styles, comments that mention keys, a key that is a suffix of
/// another (`material` / `roller_material`) and two scenes with lists in both styles.
const TEXT: &str = "\
# teeth: 99 in a comment is not a key
name: mixed
reducer:
  teeth: 9
  rollers: 10   # rollers: 11 in a trailing comment
  roller_material: { youngs_modulus_gpa: 206.0, poisson_ratio: 0.3 }
  material:
    youngs_modulus_gpa: 206.0
    poisson_ratio: 0.3
  output_pins:
    count: 6
scenes:
  - name: first
    crank: { from_deg: 0.0, to_deg: 36.0, steps: 360 }
    effects: [clearance, \"a, b\", bearing]

  # a comment between items
  - name: second
    crank:
      from_deg: 0.0
      steps: 4
    effects:
      - clearance
      - output_pins
limits:
  min_clearance_mm: 0.015
";

#[track_caller]
fn at(path: &str) -> Option<(usize, usize)> {
    locate(TEXT, path)
}

#[test]
fn top_level_and_nested_keys() {
    assert_eq!(at("name"), Some((2, 1)));
    assert_eq!(at("reducer"), Some((3, 1)));
    assert_eq!(at("reducer.teeth"), Some((4, 3)));
    assert_eq!(at("reducer.output_pins.count"), Some((11, 5)));
    assert_eq!(at("limits.min_clearance_mm"), Some((26, 3)));
}

#[test]
fn keys_in_comments_are_not_keys() {
    // Line 1 mentions `teeth:` and line 5 `rollers:` inside comments.
    assert_eq!(at("reducer.teeth"), Some((4, 3)));
    assert_eq!(at("reducer.rollers"), Some((5, 3)));
}

#[test]
fn a_key_is_not_matched_as_the_suffix_of_another() {
    // `roller_material` comes first and ends in `material`.
    assert_eq!(at("reducer.material"), Some((7, 3)));
    assert_eq!(at("reducer.material.poisson_ratio"), Some((9, 5)));
    assert_eq!(at("reducer.roller_material.poisson_ratio"), Some((6, 49)));
}

#[test]
fn block_list_items() {
    // An item's location is its content, after `- `.
    assert_eq!(at("scenes[0]"), Some((13, 5)));
    assert_eq!(at("scenes[0].name"), Some((13, 5)));
    // Blank lines and comments between items do not count as items.
    assert_eq!(at("scenes[1]"), Some((18, 5)));
    assert_eq!(at("scenes[1].crank.steps"), Some((21, 7)));
    assert_eq!(at("scenes[1].effects[0]"), Some((23, 9)));
    assert_eq!(at("scenes[1].effects[1]"), Some((24, 9)));
}

#[test]
fn flow_mappings_and_lists_inside_list_items() {
    assert_eq!(at("scenes[0].crank.steps"), Some((14, 43)));
    assert_eq!(at("scenes[0].effects[0]"), Some((15, 15)));
    // A quoted comma does not split an item.
    assert_eq!(at("scenes[0].effects[1]"), Some((15, 26)));
    assert_eq!(at("scenes[0].effects[2]"), Some((15, 34)));
}

#[test]
fn an_index_past_the_end_is_not_found() {
    // Not the next scene's effects, nor the items of a later list.
    assert_eq!(at("scenes[0].effects[3]"), None);
    assert_eq!(at("scenes[1].effects[2]"), None);
    assert_eq!(at("scenes[2]"), None);
}

#[test]
fn missing_keys_are_not_found() {
    assert_eq!(at("modification.shift_mm"), None);
    assert_eq!(at("reducer.eccentricity_mm"), None);
    // A scalar is not a list.
    assert_eq!(at("name[0]"), None);
}

#[test]
fn lists_at_the_indentation_of_their_key() {
    let text =
        "scenes:\n- name: a\n  effects:\n  - clearance\n  - bearing\n- name: b\nlimits:\n  x: 1\n";
    assert_eq!(locate(text, "scenes[1].name"), Some((6, 3)));
    assert_eq!(locate(text, "scenes[0].effects[1]"), Some((5, 5)));
    // The first scene's list ends where the second scene begins.
    assert_eq!(locate(text, "scenes[0].effects[2]"), None);
    assert_eq!(locate(text, "scenes[2]"), None);
}

#[test]
fn a_flow_list_of_flow_mappings_over_several_lines() {
    let text = "scenes: [\n  {name: a, effects: [clearance]},\n  {name: b, effects: [x, y]}\n]\n";
    assert_eq!(locate(text, "scenes[0]"), Some((2, 3)));
    assert_eq!(locate(text, "scenes[1]"), Some((3, 3)));
    assert_eq!(locate(text, "scenes[1].effects[1]"), Some((3, 26)));
    assert_eq!(locate(text, "scenes[2]"), None);
}

/// `parse` places errors that serde cannot locate (values, design rules) with `locate`.
#[test]
fn parse_places_value_errors_at_their_key() {
    let spec = include_str!("../../specs/reducer.yaml");
    let bad = spec.replace(
        "effects: [clearance]",
        "effects: [clearance]\n  - name: second\n    crank: { from_deg: 0, to_deg: 36, steps: 2 }\n    effects:\n      - clearance\n      - stress",
    );
    let err = parse("s.yaml", &bad).unwrap_err();
    assert_eq!(err.key_path.as_deref(), Some("scenes[1].effects[1]"));
    let loc = err.location.unwrap();
    assert_eq!((loc.file.as_str(), loc.line, loc.column), ("s.yaml", 31, 9));

    let bad = spec.replace("steps: 360", "steps: 0");
    let err = parse("s.yaml", &bad).unwrap_err();
    assert_eq!(err.key_path.as_deref(), Some("scenes[0].crank.steps"));
    let loc = err.location.unwrap();
    assert_eq!((loc.line, loc.column), (25, 43));
}

/// A quoted key is the same key to YAML (`"teeth": 8` is `teeth: 8`): its error is located at
/// it, not at the start of the file, and a spec written back with it (`--write-sample`) finds
/// it. Column 3 is the opening quote, where the key starts.
#[test]
fn quoted_keys_are_located_and_written_back() {
    use crate::common::{cycloid, Scratch, PAPER};
    let dir = Scratch::new("quoted-keys");
    let quoted = PAPER
        .replacen("  teeth: 9 ", "  \"teeth\": 8 ", 1)
        .replacen("  rollers: 10 ", "  'rollers': 10 ", 1);
    dir.write("q.yaml", &quoted);
    let line = quoted
        .lines()
        .position(|l| l.contains("'rollers'"))
        .unwrap()
        + 1;
    let run = cycloid(&dir.path, &["check", "q.yaml"]);
    assert_eq!(run.code(), 2, "{run:?}");
    assert!(
        run.stderr.starts_with(&format!(
            "q.yaml:{line}:3: impossible design: reducer.rollers"
        )),
        "{}",
        run.stderr
    );
    let sample = PAPER.replacen("  teeth: 9 ", "  \"teeth\": 9 ", 1)
        + "tolerances:\n  scene: rated\n  roller_radial_mm: 0.003\n  samples: 8\n  \
           max_failure_rate: 0.5\n";
    dir.write("s.yaml", &sample);
    let run = cycloid(
        &dir.path,
        &["tolerance", "s.yaml", "--write-sample", "1", "w.yaml"],
    );
    assert_eq!(run.code(), 0, "{run:?}");
    assert!(
        dir.read("w.yaml").contains("  deviations:\n"),
        "{}",
        dir.read("w.yaml")
    );
    assert!(matches!(
        cycloid(&dir.path, &["check", "w.yaml"]).code(),
        0 | 1
    ));
}
