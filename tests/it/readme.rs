//! The guide: the README (the landing page) and the pages of `docs/`. The spec-key table
//! (`docs/spec.md`) is one table (a blank line once cut it, and 26 keys rendered as raw text)
//! and documents every key and limit; the shipped specs are all listed; every file the pages
//! name exists and every link between them lands on a heading.

/// The spec reference, which holds the key table.
const SPEC_PAGE: &str = "docs/spec.md";

/// The Markdown files of the guide: the README and every page under `docs/`, sorted.
fn guide_files() -> Vec<std::path::PathBuf> {
    fn walk(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    let mut files = vec![std::path::PathBuf::from("README.md")];
    walk(std::path::Path::new("docs"), &mut files);
    files.sort();
    files
}

/// The whole guide's text, its files one after the other.
fn guide() -> String {
    (guide_files().iter())
        .map(|f| std::fs::read_to_string(f).unwrap())
        .collect::<Vec<_>>()
        .join("\n\n")
}

#[test]
fn the_spec_key_table_is_whole_and_lists_every_limit() {
    let readme = std::fs::read_to_string(SPEC_PAGE).unwrap();
    let start = readme
        .find("| key | unit | default | meaning |")
        .expect("the spec-key table");
    let section_end = readme[start..]
        .find("\n#")
        .map_or(readme.len(), |i| start + i);
    let lines: Vec<&str> = readme[start..section_end].lines().collect();
    let rows = lines.iter().take_while(|l| l.starts_with('|')).count();
    let stray: Vec<&&str> = lines[rows..]
        .iter()
        .filter(|l| l.starts_with("| `"))
        .collect();
    assert!(
        stray.is_empty(),
        "rows cut off the table by a blank line: {stray:?}"
    );
    let table = lines[..rows].join("\n");
    for l in cycloid::model::quantity::LIMITS {
        let key = format!("| `limits.{}` |", l.key);
        assert!(table.contains(&key), "{key} is not documented");
    }
}

/// The rows of the README's spec-key table, each split into its cells.
fn key_table() -> Vec<Vec<String>> {
    let readme = std::fs::read_to_string(SPEC_PAGE).unwrap();
    let start = readme
        .find("| key | unit | default | meaning |")
        .expect("the spec-key table");
    readme[start..]
        .lines()
        .take_while(|l| l.starts_with('|'))
        .skip(2)
        .map(|l| l.split(" | ").map(str::to_string).collect())
        .collect()
}

/// The keys `src/spec/raw.rs` accepts, with their place in a spec, read from its serde structs
/// (every one `deny_unknown_fields`): a struct's `pub` fields are its keys; a field whose type
/// is another spec struct is the place of that struct's keys, not a key of its own. A struct
/// this test does not place fails it, so a new section cannot slip past the table.
fn accepted_keys() -> Vec<String> {
    const PLACES: &[(&str, &str)] = &[
        ("RawSpecOf", ""),
        ("RawTolerances", "tolerances."),
        ("RawMeasuredProfile", "measured_profile."),
        ("RawStudy", "optimise."),
        ("RawVariables", "optimise.variables."),
        ("RawPoint", "optimise.start."),
        ("RawConstraints", "optimise.constraints."),
        ("RawReference", "optimise.references."),
        ("RawReducer", "reducer."),
        ("RawDeviations", "reducer.deviations."),
        ("RawFormTerm", "reducer.deviations.form."),
        ("RawRollerDeviation", "reducer.deviations.rollers."),
        ("RawCentreDeviation", "reducer.deviations.holes."),
        ("RawCrankBearing", "reducer.crank_bearing."),
        ("RawFriction", "reducer.friction."),
        ("RawRollerFriction", "reducer.friction.rollers."),
        ("RawPinFriction", "reducer.friction.output_pins."),
        ("RawBearingFriction", "reducer.friction.crank_bearing."),
        ("RawThermal", "reducer.thermal."),
        ("RawOutputPins", "reducer.output_pins."),
        ("RawPinSupport", "reducer.output_pins.support."),
        ("RawMaterial", "reducer.material."),
        ("RawContactFatigue", "reducer.material.contact_fatigue."),
        ("RawModification", "modification."),
        ("RawCrowning", "modification.crowning."),
        ("RawMisalignment", "scenes[].misalignment."),
        ("RawMisalignment", "reducer.deviations.misalignment."),
        ("RawScene", "scenes[]."),
        ("RawTorqueSweep", "scenes[].torque_sweep."),
        ("RawCrank", "scenes[].crank."),
        ("RawDutyBin", "scenes[].duty_cycle."),
        ("RawGolden", "golden[]."),
        ("RawTolerance", "golden[].tolerance."),
        ("RawAccuracy", "accuracy."),
        ("RawAccuracyTolerance", "accuracy.tolerance."),
    ];
    let raw = std::fs::read_to_string("src/spec/raw.rs").unwrap();
    let mut keys = Vec::new();
    // A struct used at several places (`RawMisalignment`) has its keys at each.
    let mut places: Vec<&str> = Vec::new();
    for line in raw.lines() {
        if let Some(rest) = line.strip_prefix("pub(crate) struct ") {
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric()).collect();
            places = PLACES
                .iter()
                .filter(|(n, _)| *n == name)
                .map(|(_, p)| *p)
                .collect();
            assert!(!places.is_empty(), "struct {name} of raw.rs has no place");
        } else if line.starts_with('}') {
            places.clear();
        } else if let (false, Some(field)) = (places.is_empty(), line.trim().strip_prefix("pub ")) {
            let (name, ty) = field.split_once(": ").unwrap();
            // Nested sections have their own struct; `limits` are the registry's (tested above).
            let nested = ty.contains("Raw") && !ty.contains("RawObjective");
            if !nested {
                keys.extend(places.iter().map(|p| format!("{p}{name}")));
            }
        }
    }
    assert!(
        keys.len() > 50,
        "raw.rs read as {} keys: {keys:?}",
        keys.len()
    );
    keys
}

/// Whether the table documents `key`: a row of its own (`` `scenes[].crank.from_deg` ``), a row
/// of its section listing it (`` `scenes[].crank.from_deg`, `to_deg` ``, `` `.rel` ``), or the
/// row of a section that spells its keys out inline (`reducer.deviations`: `form: [{order,
/// cos_mm, sin_mm}]`).
fn documented(key: &str, table: &[Vec<String>]) -> bool {
    let (parent, leaf) = key.rsplit_once('.').unwrap_or(("", key));
    let word = |text: &str| {
        text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .any(|w| w == leaf)
    };
    let ancestors: Vec<&str> = key.match_indices('.').map(|(i, _)| &key[..i]).collect();
    table.iter().any(|row| {
        let first = row[0].trim_start_matches('|').trim();
        first.contains(&format!("`{key}`"))
            || (first.contains(&format!("`{parent}."))
                && (first.contains(&format!("`{leaf}`")) || first.contains(&format!("`.{leaf}`"))))
            || (ancestors.iter().any(|a| first == format!("`{a}`"))
                && row[1..].iter().any(|cell| word(cell)))
    })
}

/// Every key the parser accepts has a row in the README's table ("keys not listed here are
/// errors" must be true both ways): read from the serde structs, not a list kept by hand.
#[test]
fn every_key_the_parser_accepts_is_in_the_table() {
    let table = key_table();
    let missing: Vec<String> = accepted_keys()
        .into_iter()
        .filter(|k| !documented(k, &table))
        .collect();
    assert!(
        missing.is_empty(),
        "keys the README's table omits: {missing:?}"
    );
}

/// Every quantity a golden may name (`quantity::curve_keys`, what the parser accepts) is in
/// the `golden[].quantity` row.
#[test]
fn every_golden_quantity_is_in_the_table() {
    let table = key_table();
    let row = table
        .iter()
        .find(|r| r[0].contains("`golden[].quantity`"))
        .expect("the golden[].quantity row")
        .join(" | ");
    let keys = cycloid::model::quantity::curve_keys();
    let missing: Vec<&str> = keys
        .split(", ")
        .filter(|k| !row.contains(&format!("`{k}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "golden quantities the README omits: {missing:?}"
    );
}

/// The guide's list of shipped specs names every file of `specs/*.yaml`.
#[test]
fn the_shipped_specs_list_names_every_spec() {
    let readme = guide();
    let start = readme
        .find("Shipped specs:")
        .expect("the shipped-specs list");
    let list = &readme[start..start + readme[start..].find("\n\n").unwrap()];
    let mut missing = Vec::new();
    for entry in std::fs::read_dir("specs").unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name.ends_with(".yaml") && !list.contains(&format!("`specs/{name}`")) {
            missing.push(name);
        }
    }
    assert!(
        missing.is_empty(),
        "shipped specs the README's list omits: {missing:?}"
    );
}

/// Every file the guide names under `specs/`, `golden/`, `tools/` or `docs/` exists: its
/// examples point at shipped files (a reader can run each as written from the repository's
/// root).
#[test]
fn every_path_the_readme_names_exists() {
    let readme = guide();
    let mut missing = Vec::new();
    let mut named = 0;
    for root in ["specs/", "golden/", "tools/", "docs/"] {
        for (at, _) in readme.match_indices(root) {
            // A path starts the word: not `tests/bad-specs/` or `cmm/specs/`.
            let before = readme[..at].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || "-_/.".contains(c)) {
                continue;
            }
            let path: String = readme[at..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || "._-/".contains(*c))
                .collect();
            let path = path.trim_end_matches(['.', '/']);
            // A pattern (`specs/*.yaml`) or a folder named as such is no file to run.
            if readme[at + path.len()..].starts_with('*') || path == root.trim_end_matches('/') {
                continue;
            }
            named += 1;
            if !std::path::Path::new(path).exists() {
                missing.push(path.to_string());
            }
        }
    }
    missing.sort();
    missing.dedup();
    assert!(
        named > 20,
        "the README names the shipped files ({named} found)"
    );
    assert!(
        missing.is_empty(),
        "the README names files that do not exist: {missing:?}"
    );
}

/// GitHub's anchor of a heading: lower case, punctuation but `-` and `_` dropped, spaces as `-`.
fn anchor(heading: &str) -> String {
    (heading.trim().to_lowercase().chars())
        .filter(|c| c.is_alphanumeric() || "-_ ".contains(*c))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a Markdown file's headings (outside code blocks).
fn anchors(text: &str) -> Vec<String> {
    let mut code = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            code = !code;
        } else if !code && line.starts_with('#') {
            out.push(anchor(line.trim_start_matches('#')));
        }
    }
    out
}

/// Every relative link of the guide (`[text](page.md#heading)`, `[text](#heading)`,
/// `[text](../specs/x.yaml)`) reaches a file that exists and, with an anchor, a heading of it:
/// the README's split into pages left no link pointing into the old single page.
#[test]
fn every_link_between_the_pages_lands() {
    let mut broken = Vec::new();
    let mut links = 0;
    for file in guide_files() {
        let text = std::fs::read_to_string(&file).unwrap();
        let dir = file.parent().unwrap();
        for (at, _) in text.match_indices("](") {
            let target: String = text[at + 2..].chars().take_while(|&c| c != ')').collect();
            if target.contains("://") || target.contains(' ') {
                continue;
            }
            links += 1;
            let (path, heading) = target.split_once('#').unwrap_or((&target, ""));
            let page = if path.is_empty() {
                file.clone()
            } else {
                dir.join(path)
            };
            if !page.exists() {
                broken.push(format!("{}: {target} (no such file)", file.display()));
                continue;
            }
            if !heading.is_empty() {
                let page_text = std::fs::read_to_string(&page).unwrap_or_default();
                if !anchors(&page_text).iter().any(|a| a == heading) {
                    broken.push(format!("{}: {target} (no such heading)", file.display()));
                }
            }
        }
    }
    assert!(
        links > 50,
        "the guide's links were not read ({links} found)"
    );
    assert!(broken.is_empty(), "links that land nowhere: {broken:#?}");
}

/// The README is the landing page (at most 400 lines); the guide lives in `docs/`.
#[test]
fn the_readme_is_a_landing_page() {
    let readme = std::fs::read_to_string("README.md").unwrap();
    let lines = readme.lines().count();
    assert!(lines <= 400, "README.md has {lines} lines");
    for command in [
        "check",
        "optimise",
        "accuracy",
        "bless",
        "profile",
        "tolerance",
        "fit",
        "design",
    ] {
        assert!(
            readme.contains(&format!("`cycloid {command} ")),
            "the README shows no example of `cycloid {command}`"
        );
    }
}
