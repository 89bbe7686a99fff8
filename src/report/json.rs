//! The results JSON (schema 1). Arrays are [roller][angle] or [angle]; engine values are
//! converted to the units named in the keys here. A quantity not computed is absent.

use crate::check::Check;
use crate::scene::SceneResult;
use crate::spec::Spec;
use serde_json::{json, Map, Value};

/// Radians to arcseconds.
pub const ARCSEC_PER_RAD: f64 = 180.0 * 3600.0 / std::f64::consts::PI;

/// A finite number as JSON; a non-finite one becomes null (never NaN in the file).
fn num(x: f64) -> Value {
    serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)
}

fn list(xs: impl IntoIterator<Item = f64>) -> Value {
    Value::Array(xs.into_iter().map(num).collect())
}

fn scene(r: &SceneResult) -> Value {
    let mut s = Map::new();
    s.insert("name".into(), json!(r.name));
    s.insert(
        "crank_deg".into(),
        list(r.crank_rad.iter().map(|a| a.to_degrees())),
    );
    if let Some(c) = &r.clearance {
        s.insert(
            "clearance_mm".into(),
            Value::Array(c.gap_mm.iter().map(|g| list(g.iter().copied())).collect()),
        );
        s.insert("min_clearance_mm".into(), num(c.min.gap_mm));
        s.insert(
            "min_clearance_at".into(),
            json!({
                "roller": c.min.roller,
                "crank_deg": num(c.min.crank_rad.to_degrees()),
                "tooth_phase": num(c.min.tooth_phase),
            }),
        );
        let arcsec = |v: &[f64]| list(v.iter().map(|b| b * ARCSEC_PER_RAD));
        s.insert("backlash_arcsec".into(), arcsec(&c.backlash_rad));
        s.insert(
            "backlash_reverse_arcsec".into(),
            arcsec(&c.backlash_reverse_rad),
        );
        s.insert("lost_motion_arcsec".into(), arcsec(&c.lost_motion_rad));
    }
    Value::Object(s)
}

/// The whole results document.
pub fn document(spec: &Spec, checks: &[Check], results: &[SceneResult]) -> Value {
    json!({
        "schema": 1,
        "name": spec.name,
        "passed": checks.iter().all(|c| c.passed),
        "checks": checks.iter().map(|c| json!({
            "id": c.id,
            "value": num(c.value),
            "limit": num(c.limit),
            "passed": c.passed,
            "at": c.at,
        })).collect::<Vec<_>>(),
        "scenes": results.iter().map(scene).collect::<Vec<_>>(),
    })
}
