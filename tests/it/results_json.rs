//! The results JSON's scene documents are the registry's (issue 40 §4): every quantity of
//! `model::quantity::QUANTITIES` that a scene computes is in the scene's object under its key,
//! with the values `Quantity::curves` / `Quantity::scalar` give, in a disc's object
//! (`discs[k]`) for a disc's results and in a duty bin's (`duty_cycle.bins[j].results`) for
//! the bin's run. Read back from the JSON text, not from the document's own types.

use cycloid::model::quantity::{Curves, Extreme, Quantity, QUANTITIES};
use cycloid::model::results::SceneResult;
use serde_json::Value;

/// serde_json's default float parser (without its `float_roundtrip` feature) may miss the
/// correctly rounded double by one unit in the last place; the text itself is the shortest
/// round-trip form of the value, so one ulp is the whole error allowed.
fn same(json: f64, registry: f64) -> bool {
    json == registry || (json - registry).abs() <= f64::EPSILON * registry.abs()
}

fn numbers(v: &Value, what: &str) -> Vec<f64> {
    (v.as_array()
        .unwrap_or_else(|| panic!("{what}: not an array: {v}"))
        .iter())
    .map(|x| {
        x.as_f64()
            .unwrap_or_else(|| panic!("{what}: {x} is no number"))
    })
    .collect()
}

/// Checks the registry's quantities of `r` against its object `json`, and its discs' (with
/// several) and duty bins' against theirs; returns the keys of the curves found.
fn registry_in_json(json: &Value, r: &SceneResult, what: &str) -> Vec<&'static str> {
    let mut seen = quantities_in_json(json, (&|q| q.scalar(r), &|q| q.curves(r)), what);
    for (k, disc) in r.discs.iter().enumerate().filter(|_| r.names_discs()) {
        let scalar = |q: &Quantity| q.disc_scalar(disc, &r.crank_rad);
        seen.extend(quantities_in_json(
            &json["discs"][k],
            (&scalar, &|q| q.disc_curves(disc)),
            &format!("{what} disc {k}"),
        ));
    }
    for (j, bin) in r.duty.iter().flat_map(|d| &d.bins).enumerate() {
        let results = &json["duty_cycle"]["bins"][j]["results"];
        seen.extend(registry_in_json(
            results,
            &bin.result,
            &format!("{what} bin {j}"),
        ));
    }
    seen
}

/// A scalar's or a curves' reader of the registry's quantities.
type Reader<'a, T> = &'a dyn Fn(&Quantity) -> Option<T>;

/// Checks the quantities `scalar` and `curves` read against the object `json`; returns the
/// keys of the curves found.
fn quantities_in_json(
    json: &Value,
    (scalar, curves): (Reader<'_, Extreme>, Reader<'_, Curves>),
    what: &str,
) -> Vec<&'static str> {
    let mut seen = Vec::new();
    for q in QUANTITIES {
        let at = format!("{what}: {}", q.key);
        if let Some(e) = scalar(q) {
            let value = json[q.key]
                .as_f64()
                .unwrap_or_else(|| panic!("{at} missing"));
            assert!(same(value, e.value), "{at}: {value} against {}", e.value);
        }
        let Some(c) = curves(q) else { continue };
        seen.push(q.key);
        let rows = match q.shape.per() {
            Some(_) => (json[q.key]
                .as_array()
                .unwrap_or_else(|| panic!("{at} missing")))
            .iter()
            .map(|row| numbers(row, &at))
            .collect(),
            None => vec![numbers(&json[q.key], &at)],
        };
        assert_eq!(rows.len(), c.values.len(), "{at}: rows");
        for (row, expected) in rows.iter().zip(&c.values) {
            assert_eq!(row.len(), expected.len(), "{at}: crank angles");
            for (&x, &y) in row.iter().zip(expected) {
                assert!(same(x, y), "{at}: {x} against {y}");
            }
        }
    }
    seen
}

/// The results file (`Document::write_to`, `report::json_text`'s numbers) is, byte for byte,
/// the document's `Serialize` through serde_json (what the Python bindings read), for every
/// shape of result: one disc, two discs (each disc's document inside), a duty cycle's bins,
/// a torsion loop, efficiency, strength.
fn the_written_document_is_its_serialisation(
    spec: &cycloid::spec::Spec,
    results: &[SceneResult],
    summaries: &[cycloid::engine::summary::SceneSummary],
    path: &str,
) {
    let doc = cycloid::report::json::scenes_document(spec, results, summaries);
    let mut written = Vec::new();
    doc.write_to(&mut written).unwrap();
    let serialised = serde_json::to_string(&doc).unwrap();
    assert!(
        String::from_utf8(written).unwrap() == serialised,
        "{path}: the written JSON differs from serde_json's"
    );
}

/// A long scene's document is written on two threads (`report::json::LONG_SCENE` crank angles
/// and more: fields from both ends of the document, the back ones copied after the front's),
/// and is still, byte for byte, its serialisation: one disc with a resolved face (line
/// loads), and two discs (each disc's document inside).
#[test]
fn a_long_scene_written_on_two_threads_is_its_serialisation() {
    for (path, name) in [
        ("specs/reducer-misaligned.yaml", "designed"),
        ("specs/reducer-two-discs.yaml", "rated"),
    ] {
        let text = std::fs::read_to_string(path).unwrap();
        let spec = cycloid::spec::parse(path, &text).unwrap_or_else(|e| panic!("{path}: {e}"));
        let mut scene = (spec.scenes.iter().find(|s| s.name == name).unwrap()).clone();
        // Angles 1 mrad apart from the scene's first: a sweep like any other, longer.
        let first = scene.crank_rad[0];
        scene.crank_rad = (0..cycloid::report::json::LONG_SCENE + 37)
            .map(|k| first + 1e-3 * k as f64)
            .collect();
        let writes = cycloid::engine::scene::Writes {
            json: true,
            report: false,
        };
        let plan = cycloid::engine::scene::plan(&spec, &scene, writes);
        let result = cycloid::engine::scene::run(&spec, &scene, &plan, &Default::default())
            .unwrap_or_else(|e| panic!("{path} {}: {e:?}", scene.name));
        let results = [result];
        let summaries = cycloid::engine::summary::summarise(&results);
        // Two threads at least: with one the document is written on one (`SceneDoc::is_long`).
        crate::common::on_threads(2, || {
            the_written_document_is_its_serialisation(&spec, &results, &summaries, path)
        });
    }
}

/// Every scene of the shipped specs that together compute every curve of the registry (two
/// discs for a disc's torque share, a resolved face, friction, strength, a duty cycle, a
/// torsion loop with friction for its hysteresis), on a few crank angles, every effect its
/// scene lists and every quantity read (the plan of a run that writes the JSON): each curve
/// and scalar computed is in the scene's JSON, and every curve of the registry is computed by
/// one of them.
#[test]
fn every_registry_quantity_a_scene_computes_is_in_its_document() {
    let torsion = std::fs::read_to_string("specs/reducer-torsion.yaml").unwrap();
    let friction_torsion = torsion.replacen(
        "\nmodification:",
        "\n  friction: { rollers: { mode: fixed, mu: 0.05 } }\nmodification:",
        1,
    );
    let mut specs: Vec<(String, String)> = [
        "specs/reducer-loaded.yaml",
        "specs/reducer-two-discs.yaml",
        "specs/reducer-misaligned.yaml",
        "specs/reducer-efficiency.yaml",
        "specs/reducer-strength.yaml",
        "specs/reducer-duty-cycle.yaml",
    ]
    .iter()
    .map(|p| (p.to_string(), std::fs::read_to_string(p).unwrap()))
    .collect();
    specs.push(("specs/reducer-torsion.yaml".into(), friction_torsion));
    let mut seen = Vec::new();
    for (path, text) in &specs {
        let spec = cycloid::spec::parse(path, text).unwrap_or_else(|e| panic!("{path}: {e}"));
        let mut results = Vec::new();
        for scene in &spec.scenes {
            let mut scene = scene.clone();
            scene.crank_rad.truncate(6);
            let writes = cycloid::engine::scene::Writes {
                json: true,
                report: false,
            };
            let plan = cycloid::engine::scene::plan(&spec, &scene, writes);
            results.push(
                cycloid::engine::scene::run(&spec, &scene, &plan, &Default::default())
                    .unwrap_or_else(|e| panic!("{path} {}: {e:?}", scene.name)),
            );
        }
        let summaries = cycloid::engine::summary::marked(&spec, &results);
        the_written_document_is_its_serialisation(&spec, &results, &summaries, path);
        let doc = cycloid::report::json::scenes_value(&spec, &results, &summaries).unwrap();
        for (i, r) in results.iter().enumerate() {
            let what = format!("{path} scene {}", r.name);
            assert_eq!(doc["scenes"][i]["name"], r.name.as_str(), "{what}");
            seen.extend(registry_in_json(&doc["scenes"][i], r, &what));
        }
    }
    seen.sort_unstable();
    seen.dedup();
    let mut curves: Vec<_> = (QUANTITIES.iter().filter(|q| !q.is_scalar()))
        .map(|q| q.key)
        .collect();
    curves.sort_unstable();
    assert_eq!(
        seen, curves,
        "the specs compute every curve of the registry"
    );
}
