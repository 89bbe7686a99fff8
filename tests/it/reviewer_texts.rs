//! What a reviewer reads on the terminal (issue 27): `check --explain` lists everything the run
//! computes, failure rates in one unit, the worst samples with their values, a lost motion that
//! never reads negative, each scene's sampling where two scenes give one quantity, a plain
//! PASS/FAIL last line, and a progress count that ends full.

use crate::common::{cycloid, cycloid_here, Scratch, PAPER};
use cycloid::progress::{Phase, Progress};
use std::sync::Mutex;

/// `check SPEC --explain ARGS` in the repository's root: its stdout, exit 0 asserted.
fn explain(spec: &str, args: &[&str]) -> String {
    let run = cycloid_here(&[&["check", spec, "--explain"], args].concat());
    assert_eq!(run.code, Some(0), "{run:?}");
    run.stdout
}

/// `reducer.discs: 2` is in the plan, with the discs' crank phases 2πk/discs (MODEL.md
/// "Several discs": 0° and 180° for two).
#[test]
fn explain_lists_the_discs() {
    let out = explain("specs/reducer-two-discs.yaml", &[]);
    assert!(
        out.lines()
            .any(|l| l.starts_with("reducer: 2 identical discs at crank phases 0°, 180° ")),
        "{out}"
    );
}

/// Every study and every golden of `specs/paper.yaml` is in the plan, by name (the spec's own
/// lists), and each study with the most evaluations it may take.
#[test]
fn explain_lists_the_studies_and_goldens() {
    let out = explain("specs/paper.yaml", &[]);
    let spec = cycloid::spec::load("specs/paper.yaml").unwrap();
    assert_eq!(spec.studies.len(), 4, "the paper's four studies");
    for s in &spec.studies {
        let most = cycloid::engine::optimise::most_evaluations(s);
        let head = format!(
            "  study `{}` on scene `{}`",
            s.name, spec.scenes[s.scene].name
        );
        assert!(
            out.lines()
                .any(|l| l.starts_with(&head) && l.contains(&format!("at most {most} evaluations"))),
            "{head} …at most {most} evaluations\n{out}"
        );
    }
    assert!(!spec.golden.is_empty());
    for g in &spec.golden {
        let line = format!(
            "  golden {} of scene `{}` against `{}`",
            g.quantity.key, g.scene, g.file
        );
        assert!(out.contains(&line), "{line}\n{out}");
    }
}

/// The accuracy ladder is in the plan: only the rungs that judge the resolution with `check`
/// alone, every rung with `--report` (which is what `engine::commands::check` runs).
#[test]
fn explain_lists_the_accuracy_ladder() {
    let head = "accuracy ladder (accuracy:) on scene `rated`: ";
    let alone = explain("specs/reducer-loaded.yaml", &[]);
    assert!(
        alone.contains(&format!("{head}only the rungs that judge")),
        "{alone}"
    );
    let dir = Scratch::new("explain-ladder");
    let review = dir.path.join("review");
    let with_report = explain(
        "specs/reducer-loaded.yaml",
        &["--report", review.to_str().unwrap()],
    );
    assert!(
        with_report.contains(&format!("{head}every rung")),
        "{with_report}"
    );
    assert!(!review.exists(), "--explain writes nothing");
}

/// The tolerance study is in the plan, skipped without `--tolerance` and run with it, with its
/// samples, seed and allowed rate as the spec gives them (2000, 1, 0.0027 = 0.27 %).
#[test]
fn explain_lists_the_tolerance_study() {
    let head = "tolerance study (tolerances:) on scene `rated`: 2000 samples, seed 1, allowed \
                failure rate 0.2700 %: ";
    let out = explain("specs/reducer-tolerance.yaml", &[]);
    assert!(out.contains(&format!("{head}skipped")), "{out}");
    let out = explain("specs/reducer-tolerance.yaml", &["--tolerance"]);
    assert!(out.contains(&format!("{head}runs (--tolerance)")), "{out}");
}

/// One unit for failure rates: `check --tolerance`'s row reads the allowed rate in percent,
/// as `cycloid tolerance` does (the spec's 0.0027 is 0.27 %), and its interval too; so does
/// its JUnit message.
#[test]
fn failure_rates_read_in_percent_in_check_and_tolerance() {
    let dir = Scratch::new("rate-percent");
    let junit = dir.path.join("j.xml");
    let check = cycloid_here(&[
        "check",
        "specs/reducer-tolerance.yaml",
        "--tolerance",
        "--junit",
        junit.to_str().unwrap(),
    ]);
    assert_eq!(check.code, Some(0), "{check:?}");
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(xml.contains("limit ≤ 0.2700 %: 0.2700 % inside"), "{xml}");
    let row = check
        .stdout
        .lines()
        .find(|l| l.starts_with("rated/tolerance_failure_rate"))
        .expect("the failure-rate row");
    let cells: Vec<&str> = row.split("  ").filter(|c| !c.is_empty()).collect();
    assert_eq!(cells[1].trim(), "0 %", "{row}");
    assert_eq!(cells[2].trim(), "≤ 0.2700 %", "{row}");
    assert!(row.contains("interval [0 %, "), "{row}");
    let study = cycloid_here(&["tolerance", "specs/reducer-tolerance.yaml"]);
    assert!(study.stdout.contains("allowed 0.2700 %"), "{study:?}");
}

/// Each worst sample of `cycloid tolerance` shows its value of the limit it is worst on, with
/// the unit and the limit: the value the JSON records for it, to the 4 significant digits
/// printed (relative 5e-4 covers the rounding).
#[test]
fn worst_samples_show_their_values() {
    let dir = Scratch::new("worst-values");
    let json = dir.path.join("t.json");
    let run = cycloid_here(&[
        "tolerance",
        "specs/reducer-tolerance.yaml",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert_eq!(run.code, Some(0), "{run:?}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let worst = doc["worst"].as_array().unwrap();
    assert!(!worst.is_empty());
    for w in worst {
        let k = w["sample"].as_u64().unwrap();
        let recorded = w["values"]["min_clearance_mm"].as_f64().unwrap();
        let line = run
            .stdout
            .lines()
            .find(|l| l.starts_with(&format!("  sample {k}: ")))
            .unwrap_or_else(|| panic!("sample {k} in\n{}", run.stdout));
        let shown = line
            .split("min_clearance_mm ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or_else(|| panic!("no value with unit and limit in {line}"));
        assert!(
            line.contains(" mm (≥ 0.01500 mm); largest draws "),
            "{line}"
        );
        assert!(
            (shown - recorded).abs() <= 5e-4 * recorded.abs(),
            "{line}: {recorded}"
        );
    }
}

/// The headline of a lost motion never reads negative: the preloaded hard case (every roller
/// overlaps the profile by 20 µm, so no lag is free) reads 0 with the overlap, which is the
/// signed sum the results JSON keeps (printed to 4 significant digits: relative 5e-4).
#[test]
fn a_preloaded_lost_motion_reads_zero_with_its_overlap() {
    let dir = Scratch::new("preload-lost-motion");
    let json = dir.path.join("r.json");
    let run = cycloid_here(&[
        "check",
        "specs/hard/preload-zero-torque.yaml",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert_eq!(run.code, Some(0), "{run:?}");
    let line = run
        .stdout
        .lines()
        .find(|l| l.contains("max lost motion (unloaded)"))
        .expect("the lost-motion headline");
    let after = line
        .split("max lost motion (unloaded)")
        .nth(1)
        .unwrap()
        .trim_start();
    assert!(
        after.starts_with("0 arcsec  preloaded: no free play"),
        "{line}"
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let signed = doc["summary"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|s| s["headlines"].as_array().unwrap())
        .find(|h| h["key"] == "max_lost_motion_arcsec")
        .and_then(|h| h["value"].as_f64())
        .expect("the signed lost motion in the JSON");
    assert!(signed < 0.0, "the hard case interferes: {signed}");
    let overlap: f64 = line
        .split("overlap by ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no overlap in {line}"));
    assert!(
        (overlap + signed).abs() <= 5e-4 * signed.abs(),
        "{line}: {signed}"
    );
}

/// Two scenes of `specs/paper.yaml` give the ratio fluctuation at two samplings (1080 angles
/// every 0.1°, 540 every 0.2°): each line says its own; the min clearance, given by one scene
/// alone, says nothing more.
#[test]
fn two_values_of_one_quantity_state_their_sampling() {
    let paper = std::fs::read_to_string("specs/paper.yaml").unwrap();
    let dir = Scratch::new("two-samplings");
    dir.write("p.yaml", &paper[..paper.find("optimise:").unwrap()]);
    let run = cycloid(&dir.path, &["check", "p.yaml"]);
    assert_eq!(run.code, Some(0), "{run:?}");
    let ratio: Vec<&str> = (run.stdout.lines())
        .filter(|l| l.contains("ratio fluctuation κmax − κmin"))
        .collect();
    assert_eq!(ratio.len(), 2, "{}", run.stdout);
    assert!(
        ratio[0].ends_with("; sampled at 1080 crank angles, every 0.1000°"),
        "{}",
        ratio[0]
    );
    assert!(
        ratio[1].ends_with("; sampled at 540 crank angles, every 0.2000°"),
        "{}",
        ratio[1]
    );
    let clearance = (run.stdout.lines())
        .find(|l| l.starts_with("  min clearance over the mesh"))
        .unwrap();
    assert!(!clearance.contains("sampled at"), "{clearance}");
}

/// `check` ends with one plain word and the counts of its table: PASS when every check passes
/// (exit 0), FAIL with how many did not (exit 1: a 1 mm clearance limit the paper's 34 µm
/// cannot meet).
#[test]
fn check_ends_with_pass_or_fail_and_the_counts() {
    let dir = Scratch::new("verdict-line");
    dir.write("pass.yaml", PAPER);
    let run = cycloid(&dir.path, &["check", "pass.yaml"]);
    assert_eq!(run.code, Some(0), "{run:?}");
    assert_eq!(run.stdout.lines().last(), Some("PASS: 1 of 1 check passed"));
    let failing = PAPER.replace("min_clearance_mm: 0.015", "min_clearance_mm: 1.0");
    assert_ne!(failing, PAPER);
    dir.write("fail.yaml", &failing);
    let run = cycloid(&dir.path, &["check", "fail.yaml"]);
    assert_eq!(run.code, Some(1), "{run:?}");
    assert_eq!(run.stdout.lines().last(), Some("FAIL: 1 of 1 check failed"));
}

/// What each phase heard: (what, total, units advanced).
#[derive(Default)]
struct Phases(Mutex<Vec<(String, u64, u64)>>);

/// One phase's count, handed back to `Phases` when the phase ends.
struct Heard<'a> {
    phases: &'a Phases,
    what: String,
    total: u64,
    done: std::sync::atomic::AtomicU64,
}

impl Progress for Heard<'_> {
    fn advance(&self, n: u64) {
        self.done.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    }
}

impl Drop for Heard<'_> {
    fn drop(&mut self) {
        let done = *self.done.get_mut();
        let entry = (self.what.clone(), self.total, done);
        self.phases.0.lock().unwrap().push(entry);
    }
}

impl Progress for Phases {
    fn phase(&self, p: &Phase) -> Box<dyn Progress + '_> {
        Box::new(Heard {
            phases: self,
            what: p.what.clone(),
            total: p.total,
            done: Default::default(),
        })
    }
}

/// The optimiser's phase counts "evaluations at most": local runs stop before their budget, and
/// the count must still end at 100 % of the total the phase announced (it stopped at ~63 %).
#[test]
fn the_optimise_count_ends_at_its_total() {
    let paper = std::fs::read_to_string("specs/paper.yaml").unwrap();
    let head = &paper[..paper.find("  - name: positive-te").unwrap()];
    let text = head.replace("steps: 540", "steps: 72").replace(
        "    scene: study\n",
        "    scene: study\n    global_samples: 12\n    boundary_samples: 8\n    verify_grid: 0\n",
    );
    let spec = cycloid::spec::parse("small.yaml", &text).unwrap();
    assert_eq!(spec.studies.len(), 1);
    let phases = Phases::default();
    let run = cycloid::check(&spec, &cycloid::CheckOptions::default(), &phases).unwrap();
    assert!(run.studies[0].evaluations > 0);
    let heard = phases.0.into_inner().unwrap();
    let optimise = heard
        .iter()
        .find(|(what, ..)| what.starts_with("optimising"))
        .expect("the optimise phase");
    assert_eq!(optimise.2, optimise.1, "{optimise:?}");
}

/// The review's headline text of `specs/reducer-two-discs.yaml` (its `--report`), tags
/// stripped: what a reviewer reads in the headline table.
fn two_disc_review(tag: &str) -> (String, String) {
    let dir = Scratch::new(tag);
    let review = dir.path.join("review");
    let run = cycloid_here(&[
        "check",
        "specs/reducer-two-discs.yaml",
        "--report",
        review.to_str().unwrap(),
    ]);
    assert_eq!(run.code, Some(0), "{run:?}");
    let html = std::fs::read_to_string(review.join("index.html")).unwrap();
    let start = html
        .find("<section id=\"summary\">")
        .expect("the headline section");
    let end = start + html[start..].find("</section>").unwrap();
    (run.stdout, untagged(&html[start..end]))
}

/// One meaning per line (issue 27): with two discs the unloaded lost motion is one disc's
/// (each disc's closing lags at its own phase) and the torsion figure the reducer's at ±3 % of
/// rated torque; each line says which, and the unloaded one says why the two differ. The
/// unloaded figure reads in arcmin, as the torsion figures beside it, the arcsec one / 60
/// (1511.2 arcsec at crank 18° on this design, README "Torsion": 1505.7–1511.2 arcsec over the
/// locked angles; 25.19 arcmin).
#[test]
fn two_disc_lost_motions_say_per_disc_or_reducer_and_why_they_differ() {
    let (_, text) = two_disc_review("two-disc-labels");
    assert!(
        text.contains("max lost motion per disc (unloaded)"),
        "{text}"
    );
    assert!(
        text.contains("max lost motion of the reducer (±3 % of rated torque)"),
        "{text}"
    );
    assert!(!text.contains("max lost motion (unloaded)"), "{text}");
    let why = text
        .split("max lost motion per disc (unloaded)")
        .nth(1)
        .unwrap();
    assert!(
        why.contains("; against the reducer's 25.20 arcmin at ±3 % of rated torque: this is one disc's free play with no load"),
        "{why}"
    );
    assert!(why.trim_start().starts_with("25.19 arcmin "), "{why}");
}

/// Each disc's torque share is in the terminal's headline results and in the review: with 10
/// rollers (even) the second disc meshes in the first one's phase and the two share equally
/// (MODEL.md "Several discs"), so each carries T/2 = 10 N·m of the scene's 20 N·m, 50 %, at
/// every crank angle (range of one value).
#[test]
fn disc_torque_shares_are_headlines() {
    let (stdout, text) = two_disc_review("two-disc-shares");
    for disc in 0..2 {
        let line = format!(
            "  torque share, disc {disc}  10.00 N·m  50.00 % of the scene's 20.00 N·m, mean over \
             its 1080 crank angles; range 10.00–10.00 N·m (50.00 %–50.00 %)"
        );
        // Columns are padded to the scene's widest cell: compare words.
        let words = |l: &str| l.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(
            stdout
                .lines()
                .any(|l| l.starts_with("  ") && words(l) == words(&line)),
            "{line}\n{stdout}"
        );
        assert!(
            text.contains(&format!("torque share, disc {disc}")),
            "{text}"
        );
    }
    assert!(
        text.contains("50.00 % of the scene's 20.00 N·m, mean over its 1080 crank angles"),
        "{text}"
    );
}

/// The paper's negative start without limits (−0.15/−0.135 mm at 10 N·m): a preload makes
/// 17.6 kN on a roller and 5.7 GPa of Hertz pressure. Steel (E 206 GPa) is marked beyond ISO
/// 76's 4,000 MPa, the roller force beyond 5 × T/(e·nc) = 5 × 10 N·m / 18 mm = 2,778 N, and
/// so is the crank bearing (5,429 N); the pins are not (370 N < 5 × T/rw = 2,778 N). A mark
/// is not a failed check: with no limits the run passes, exit 0. A limit on a quantity takes
/// over its judgement: no mark.
#[test]
fn implausible_headlines_are_marked_without_failing() {
    let dir = Scratch::new("plausible");
    let start = crate::common::PaperSpec::new()
        .modification(-0.15, -0.135)
        .scenes(&crate::common::scene_item(
            "rated",
            10.0,
            "{ from_deg: 0.0, to_deg: 108.0, steps: 1080 }",
            "bearing",
        ));
    dir.write("start.yaml", start.text());
    let run = cycloid(&dir.path, &["check", "start.yaml", "--json", "out.json"]);
    assert_eq!(run.code, Some(0), "{run:?}");
    // The results JSON carries the band of a marked headline, and only of a marked one.
    let json: serde_json::Value = serde_json::from_str(&dir.read("out.json")).unwrap();
    let headlines = json["summary"][0]["headlines"].as_array().unwrap();
    let band = |key: &str| {
        let h = headlines.iter().find(|h| h["key"] == key).unwrap();
        h.get("beyond_plausible").and_then(|b| b.as_f64())
    };
    assert_eq!(band("max_contact_pressure_mpa"), Some(4000.0));
    assert_eq!(band("max_pin_force_n"), None);
    let marked: Vec<&str> = run.stdout.lines().filter(|l| l.starts_with("! ")).collect();
    let starts = |l: &&str, what: &str| l.starts_with(&format!("! {what} "));
    assert!(
        marked.iter().any(|l| starts(l, "max Hertz pressure")
            && l.contains("4000 MPa (ISO 76's static limit")
            && l.contains("set limits.max_contact_pressure_mpa to judge it")),
        "{marked:?}"
    );
    assert!(
        marked.iter().any(|l| starts(l, "max roller force")
            && l.contains(
                "the 555.6 N the torque needs at the largest arm (T/(e·nc) = 10.00 N·m / 18.00 mm)"
            )),
        "{marked:?}"
    );
    assert!(
        marked.iter().any(|l| starts(l, "max crank-bearing force")),
        "{marked:?}"
    );
    assert!(!run.stdout.contains("! max pin force"), "{}", run.stdout);
    assert_eq!(marked.len(), 3, "{marked:?}");
    // A limit judges the pressure instead of the band.
    dir.write(
        "limited.yaml",
        start
            .with("limits:\n  max_contact_pressure_mpa: 6000\n")
            .text(),
    );
    let run = cycloid(&dir.path, &["check", "limited.yaml"]);
    assert_eq!(run.code, Some(0), "{run:?}");
    assert!(
        !run.stdout.contains("! max Hertz pressure"),
        "{}",
        run.stdout
    );
    assert!(
        run.stdout.contains("rated/max_contact_pressure_mpa"),
        "{}",
        run.stdout
    );
}

/// The shipped specs' ordinary designs carry no mark: every headline of theirs lies within its
/// band (the largest force at most 1.8 × its scale). `specs/paper-negative-start.yaml` is the
/// preloaded design above (marked on purpose); `specs/paper.yaml` runs four studies (slow) on
/// the design and scenes of `specs/reducer-loaded.yaml`, covered here; `requirements-*.yaml`
/// are `cycloid design`'s inputs.
#[test]
fn shipped_specs_have_no_implausible_headline() {
    let mut names: Vec<String> = std::fs::read_dir("specs")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".yaml"))
        .filter(|n| n != "paper-negative-start.yaml" && n != "paper.yaml")
        // A requirements file of `cycloid design`, not a spec.
        .filter(|n| !n.starts_with("requirements-"))
        .collect();
    names.sort();
    assert!(names.len() >= 8, "{names:?}");
    for name in names {
        let run = cycloid_here(&["check", &format!("specs/{name}")]);
        assert!(
            run.code == Some(0) || run.code == Some(1),
            "{name}: {run:?}"
        );
        assert!(
            !run.stdout.lines().any(|l| l.starts_with("! ")),
            "{name}:\n{}",
            run.stdout
        );
    }
    let start = cycloid_here(&["check", "specs/paper-negative-start.yaml"]);
    assert!(
        start.stdout.contains("! max Hertz pressure"),
        "{}",
        start.stdout
    );
}

/// The bands themselves (`engine::plausibility`): steel (E 206 GPa, the paper's) gets ISO 76's
/// 4,000 MPa; a disc of E 70 GPa (aluminium) is no steel, so the conservative 1,500 MPa; the
/// roller force's band is 5 × T/(e·nc) = 5 × 10,000 N·mm / (2 mm × 9) = 2,777.8 N and the pins'
/// 5 × T/rw = 5 × 10,000 / 18 = 2,777.8 N too on this design (rw = e·nc = 18 mm); a scene
/// without torque has no force band; a limit on the quantity leaves no band.
#[test]
fn plausibility_bands_follow_the_material_and_the_torque() {
    use cycloid::engine::plausibility::{band, Basis};
    use cycloid::model::quantity::{MAX_CONTACT_PRESSURE, MAX_PIN_FORCE, MAX_ROLLER_FORCE};
    let spec = crate::common::PaperSpec::new().parse("paper.yaml");
    let pressure = band(&spec.design, &spec.limits, &MAX_CONTACT_PRESSURE, 1e4).unwrap();
    assert_eq!(pressure.band, 4000.0);
    assert!(matches!(pressure.basis, Basis::Steel { .. }));
    let mut aluminium = spec.design.clone();
    aluminium.disc_material.youngs_modulus_mpa = 70e3;
    let soft = band(&aluminium, &spec.limits, &MAX_CONTACT_PRESSURE, 1e4).unwrap();
    assert_eq!(soft.band, 1500.0);
    assert!(matches!(soft.basis, Basis::UnknownMaterial { .. }));
    // 5 × 10,000/18 N; the division's round-off only.
    for q in [&MAX_ROLLER_FORCE, &MAX_PIN_FORCE] {
        let f = band(&spec.design, &spec.limits, q, 1e4).unwrap();
        assert!((f.band - 5.0 * 1e4 / 18.0).abs() < 1e-9, "{q:?}: {f:?}");
        assert!(band(&spec.design, &spec.limits, q, 0.0).is_none());
    }
    let limited = crate::common::PaperSpec::new()
        .rated_period(36)
        .with("limits:\n  max_contact_pressure_mpa: 2000.0\n")
        .parse("limited.yaml");
    assert!(band(&limited.design, &limited.limits, &MAX_CONTACT_PRESSURE, 1e4).is_none());
}

/// The review's design table states the disc's crowning as the spec writes it
/// (`specs/reducer-misaligned.yaml`: `{ kind: circular, radius_mm: 1000.0, start_mm: 2.0 }`):
/// a reviewer reading the line-load plot must see which crown made it. A straight disc's
/// table (`specs/paper.yaml`) has no crowning row.
#[test]
fn the_design_table_states_the_crowning() {
    let design_section = |spec: &str, tag: &str| {
        let dir = Scratch::new(tag);
        let review = dir.path.join("review");
        let run = cycloid_here(&["check", spec, "--report", review.to_str().unwrap()]);
        assert_eq!(run.code, Some(0), "{run:?}");
        let html = std::fs::read_to_string(review.join("index.html")).unwrap();
        let start = html
            .find("<section id=\"design\">")
            .expect("the design section");
        let end = start + html[start..].find("</section>").unwrap();
        html[start..end].to_string()
    };
    let crowned = design_section("specs/reducer-misaligned.yaml", "crowning-row");
    assert!(
        crowned.contains("circular, Rc 1000 mm, flat over |z| ≤ 2.000 mm"),
        "{crowned}"
    );
    let straight = design_section("specs/paper.yaml", "no-crowning-row");
    assert!(!straight.contains("crowning"), "{straight}");
}

/// Words of a text, one space apart: the terminal pads its columns.
fn words(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// `html` with its tags dropped, each tag read as a space.
fn untagged(html: &str) -> String {
    let mut text = String::new();
    let mut inside = false;
    for c in html.chars() {
        match c {
            '<' => inside = true,
            '>' => {
                inside = false;
                text.push(' ');
            }
            _ if !inside => text.push(c),
            _ => {}
        }
    }
    text
}

/// The text of a review's section (tags stripped, words one space apart).
fn section_text(html: &str, id: &str) -> String {
    let start = html
        .find(&format!("<section id=\"{id}\">"))
        .unwrap_or_else(|| panic!("no section {id}"));
    let end = start + html[start..].find("</section>").unwrap();
    words(
        &untagged(&html[start..end])
            .replace("&#39;", "'")
            .replace("&amp;", "&"),
    )
}

/// One unit per line (review of the outputs, item 1): on `specs/reducer-torsion.yaml` the
/// unloaded lost motion's line compares it with the reducer's ±3 % figure in arcmin, so it
/// reads in arcmin too, in the terminal and in the review alike, and no figure of that line is
/// in arcsec. 25.19 arcmin is README "Torsion"'s 1511.2 arcsec at crank 18° over 60; 25.22
/// arcmin the largest of the ±3 % figures README gives (25.13–25.22 arcmin).
#[test]
fn a_torsion_scenes_unloaded_lost_motion_reads_in_arcmin() {
    let dir = Scratch::new("torsion-lost-motion-unit");
    let review = dir.path.join("review");
    let run = cycloid_here(&[
        "check",
        "specs/reducer-torsion.yaml",
        "--report",
        review.to_str().unwrap(),
    ]);
    assert_eq!(run.code, Some(0), "{run:?}");
    let want = "max lost motion (unloaded) 25.19 arcmin crank 18.00°, over the scene's 4 crank \
                angles; against the reducer's 25.22 arcmin at ±3 % of rated torque: this is the \
                disc's free play with no load (the closing lags at the ideal pose), the other \
                the catalogue's figure, the torsion angle of the reducer between ±3 % of rated \
                torque: that free play plus the elastic twist of the contacts at 3 % of rated";
    let line = run
        .stdout
        .lines()
        .find(|l| l.contains("max lost motion (unloaded)"))
        .expect("the unloaded lost motion's line");
    assert_eq!(words(line), want);
    let html = std::fs::read_to_string(review.join("index.html")).unwrap();
    let text = section_text(&html, "summary");
    assert!(text.contains(want), "{text}");
    let row = text.split("max lost motion (unloaded)").nth(1).unwrap();
    let row = &row[..row.find("max lost motion of the reducer").unwrap()];
    assert!(!row.contains("arcsec"), "{row}");
}

/// A preloaded lost motion beside the reducer's torsion figures reads 0 arcmin with its
/// overlap in arcmin too (`report::table::summary_rows`): −494.8 arcsec is 8.247 arcmin (÷ 60).
/// Without the torsion figure the same headline stays in arcsec, the unit of the TE.
#[test]
fn a_preloaded_lost_motion_beside_torsion_figures_reads_in_arcmin() {
    use cycloid::engine::summary::{Headline, SceneSummary};
    use cycloid::model::place::{Crank, Place, Site};
    use cycloid::model::quantity::{MAX_LOST_MOTION, MAX_TORSION_LOST_MOTION};
    let headline = |quantity, value: f64| Headline {
        quantity,
        value,
        at: Place::of(Site::Crank(Crank { index: 0, rad: 0.0 })),
        beyond: None,
        resolution: 0.0,
    };
    let scene = |headlines| SceneSummary {
        scene: "torsion".into(),
        headlines,
        scalars: Vec::new(),
        angles: 1,
        step_rad: 0.0,
        first_rad: 0.0,
        discs: 1,
        shares: Vec::new(),
    };
    let with_torsion = scene(vec![
        headline(&MAX_LOST_MOTION, -494.8),
        headline(&MAX_TORSION_LOST_MOTION, 2.5),
    ]);
    let rows = cycloid::report::table::summary_rows(&with_torsion, &[]);
    assert_eq!(rows[0].value, "0 arcmin");
    assert!(
        rows[0].at.starts_with(
            "preloaded: no free play, the closing lags overlap by 8.247 arcmin (interference), \
             crank 0.00°; against the reducer's 2.500 arcmin at ±3 % of rated torque"
        ),
        "{}",
        rows[0].at
    );
    let alone = scene(vec![headline(&MAX_LOST_MOTION, -494.8)]);
    let rows = cycloid::report::table::summary_rows(&alone, &[]);
    assert_eq!(rows[0].value, "0 arcsec");
    assert_eq!(
        rows[0].at,
        "preloaded: no free play, the closing lags overlap by 494.8 arcsec (interference), \
         crank 0.00°"
    );
}

/// A rigid part is a compliance not modelled (review of the outputs, item 2; issue 29 item
/// 5): `specs/reducer-torsion.yaml` gives no crank-bearing stiffness and no pin support, so
/// its bearing and pins are rigid and listed as not modelled; `specs/reducer-pin-beams.yaml`
/// bends its cantilever pins, so only its bearing is rigid (and gives the structure's 2
/// arcmin per kN·m). The review and the JSON say the same.
#[test]
fn torsion_compliances_list_rigid_parts_as_not_modelled() {
    let cases = [
        (
            "specs/reducer-torsion.yaml",
            vec![
                "roller contacts (paper_linear law, exact geometry)",
                "output-pin contacts (paper_linear law)",
            ],
            vec!["pin bending (pins rigid)", "crank bearing (rigid)"],
            "none (carrier, housing and shafts rigid)",
        ),
        (
            "specs/reducer-pin-beams.yaml",
            vec![
                "roller contacts (paper_linear law, exact geometry)",
                "output-pin contacts (paper_linear law)",
                "pin bending (cantilever clamped in the flange, 14.00 mm long, disc mid-planes \
                 at 10.00 mm from the flange)",
            ],
            vec!["crank bearing (rigid)"],
            "structure (carrier, housing, shafts) 2.000 arcmin per kN·m, added as c·T",
        ),
    ];
    for (k, (spec, modelled, not_modelled, given)) in cases.iter().enumerate() {
        let dir = Scratch::new(&format!("torsion-compliances-{k}"));
        let (review, json) = (dir.path.join("review"), dir.path.join("r.json"));
        let run = cycloid_here(&[
            "check",
            spec,
            "--report",
            review.to_str().unwrap(),
            "--json",
            json.to_str().unwrap(),
        ]);
        assert_eq!(run.code, Some(0), "{run:?}");
        let html = std::fs::read_to_string(review.join("index.html")).unwrap();
        let text = section_text(&html, "scene-1-torsion-torsion");
        let want = format!(
            "Compliances modelled: {}. Not modelled: {}. Given: {given}.",
            modelled.join("; "),
            not_modelled.join("; ")
        );
        assert!(text.contains(&want), "{spec}: {want}\nnot in {text}");
        let doc: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let c = &doc["scenes"][0]["compliances"];
        assert_eq!(c["modelled"], serde_json::json!(modelled), "{spec}");
        assert_eq!(c["not_modelled"], serde_json::json!(not_modelled), "{spec}");
    }
}

/// The review's design table states the friction and heat inputs as the spec writes them,
/// with units (review of the outputs, item 5): `specs/reducer-efficiency.yaml` gives the loss
/// model, rotating rollers on 1.5 mm pins at μ 0.06, sleeves on 2 mm pins at μ 0.06, the
/// bearing at μ 0.0025 on a 20 mm bore, 30 N·mm of drag and a housing of 0.06 m² at 20
/// W/(m²·K) in 20 °C air. A spec without friction (`specs/paper.yaml`) has none of these rows.
#[test]
fn the_design_table_states_the_friction_inputs() {
    let design = |spec: &str, tag: &str| {
        let dir = Scratch::new(tag);
        let review = dir.path.join("review");
        let run = cycloid_here(&["check", spec, "--report", review.to_str().unwrap()]);
        assert_eq!(run.code, Some(0), "{run:?}");
        section_text(
            &std::fs::read_to_string(review.join("index.html")).unwrap(),
            "design",
        )
    };
    let text = design("specs/reducer-efficiency.yaml", "friction-rows");
    let want = "friction model loss (the frictionless balance's forces, each path's loss \
                μ·F·sliding speed) friction, rollers rotating on pins of radius r_b 1.5 mm, μ \
                0.06 (at the roller's pin) friction, output pins free sleeves on pins of radius \
                r_bore 2 mm, μ 0.06 (between sleeve and pin) friction, crank bearing μ 0.0025 at \
                its bore d 20 mm no-load torque at the input 30 N·mm housing's heat path area A \
                0.06 m², heat transfer h 20 W/(m²·K), ambient 20 °C";
    assert!(text.contains(want), "{want}\nnot in {text}");
    let plain = design("specs/paper.yaml", "no-friction-rows");
    assert!(!plain.contains("friction"), "{plain}");
    assert!(!plain.contains("heat"), "{plain}");
}

/// Every figure caption of a review ends with a full stop, as the page's other prose does: the
/// reviews of the specs with the torsion curve, the efficiency plots and two discs' scene plots
/// (three captions there once stopped without one).
#[test]
fn every_figure_caption_ends_with_a_full_stop() {
    let dir = Scratch::new("captions");
    for (k, spec) in ["reducer-torsion", "reducer-efficiency", "reducer-two-discs"]
        .iter()
        .enumerate()
    {
        let out = dir.join(&format!("review-{k}"));
        let run = cycloid_here(&[
            "check",
            &format!("specs/{spec}.yaml"),
            "--report",
            out.to_str().unwrap(),
        ]);
        assert!(matches!(run.code, Some(0 | 1)), "{run:?}");
        let html = std::fs::read_to_string(out.join("index.html")).unwrap();
        let captions: Vec<&str> = (html.split("<figcaption>").skip(1))
            .map(|c| &c[..c.find("</figcaption>").unwrap()])
            .collect();
        assert!(!captions.is_empty(), "{spec}: no figure");
        for c in captions {
            assert!(
                c.ends_with('.'),
                "{spec}: a caption without its full stop: {c}"
            );
        }
    }
}
