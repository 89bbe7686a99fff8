//! The results JSON (schema 1). Arrays are [roller][angle] or [angle]; engine values are
//! converted to the units named in the keys here. A quantity not computed is absent.

use crate::engine::check::{Check, CheckKind};
use crate::engine::golden::{sha256_hex, GoldenResult, Point};
use crate::model::results::SceneResult;
use crate::numeric::{extremes, max_entry};
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
        if let Some(b) = &c.backlash {
            let arcsec = |v: &[f64]| list(v.iter().map(|b| b * ARCSEC_PER_RAD));
            s.insert("backlash_arcsec".into(), arcsec(&b.forward_rad));
            s.insert("backlash_reverse_arcsec".into(), arcsec(&b.reverse_rad));
            s.insert("lost_motion_arcsec".into(), arcsec(&b.lost_motion_rad));
        }
    }
    loaded(&mut s, r);
    Value::Object(s)
}

fn grid(rows: &[Vec<f64>]) -> Value {
    Value::Array(rows.iter().map(|row| list(row.iter().copied())).collect())
}

/// Curves and scalar summaries of the loaded solve (absent when not computed).
fn loaded(s: &mut Map<String, Value>, r: &SceneResult) {
    let l = &r.loaded;
    let arcsec = |v: &[f64]| list(v.iter().map(|b| b * ARCSEC_PER_RAD));
    if let Some(c) = &l.rollers {
        s.insert("lag_arcsec".into(), arcsec(&c.lag_rad));
        s.insert("roller_force_n".into(), grid(&c.force_n));
        s.insert("contact_pressure_mpa".into(), grid(&c.pressure_mpa));
        s.insert("contact_half_width_mm".into(), grid(&c.half_width_mm));
        s.insert("contacts".into(), json!(c.contacts));
        s.insert("max_roller_force_n".into(), num(max_entry(&c.force_n).0));
        s.insert(
            "max_contact_pressure_mpa".into(),
            num(max_entry(&c.pressure_mpa).0),
        );
        let counts: Vec<f64> = c.contacts.iter().map(|&n| n as f64).collect();
        s.insert("min_rollers_in_contact".into(), num(extremes(&counts).0 .0));
    }
    if let Some(p) = &l.pins {
        s.insert("output_lag_arcsec".into(), arcsec(&p.output_lag_rad));
        s.insert("pin_force_n".into(), grid(&p.force_n));
        s.insert("max_pin_force_n".into(), num(max_entry(&p.force_n).0));
    }
    if let Some(b) = &l.bearing {
        s.insert("bearing_force_n".into(), list(b.force_n.iter().copied()));
        s.insert(
            "bearing_angle_deg".into(),
            list(b.angle_rad.iter().map(|a| a.to_degrees())),
        );
        s.insert(
            "bearing_deflection_mm".into(),
            list(b.deflection_mm.iter().copied()),
        );
        s.insert("residual".into(), list(b.residual.iter().copied()));
        s.insert("max_residual".into(), num(extremes(&b.residual).1 .0));
        s.insert("max_bearing_force_n".into(), num(extremes(&b.force_n).1 .0));
    }
    if let Some(t) = &l.transmission {
        let ((lo, _), (hi, _)) = extremes(&t.te_rad);
        s.insert("te_arcsec".into(), arcsec(&t.te_rad));
        s.insert("te_max_arcsec".into(), num(hi * ARCSEC_PER_RAD));
        s.insert("te_min_arcsec".into(), num(lo * ARCSEC_PER_RAD));
        s.insert(
            "te_fluctuation_arcsec".into(),
            num((hi - lo) * ARCSEC_PER_RAD),
        );
        if let Some(ratio) = &t.ratio {
            let ((lo, _), (hi, _)) = extremes(ratio);
            s.insert("ratio".into(), list(ratio.iter().copied()));
            s.insert("ratio_max".into(), num(hi));
            s.insert("ratio_min".into(), num(lo));
            s.insert("ratio_fluctuation".into(), num(hi - lo));
        }
    }
}

fn point(p: &Point) -> Value {
    json!({
        "column": p.column,
        "crank_deg": num(p.crank_deg),
        "golden": num(p.golden),
        "value": num(p.value),
        "deviation": num(p.deviation),
        "band": num(p.band),
    })
}

fn golden(g: &GoldenResult) -> Value {
    let c = &g.comparison;
    json!({
        "scene": g.golden.scene,
        "quantity": g.golden.quantity.key,
        "unit": g.unit,
        "file": g.golden.path.display().to_string(),
        "tolerance": {"abs": num(g.golden.tolerance.abs), "rel": num(g.golden.tolerance.rel)},
        "passed": c.passed,
        "points_compared": c.points,
        "worst": point(&c.worst),
        "largest": point(&c.largest),
    })
}

/// The whole results document, without golden curves.
pub fn document(spec: &Spec, checks: &[Check], results: &[SceneResult]) -> Value {
    document_with_golden(spec, checks, results, &[])
}

/// The whole results document. `checks` holds the golden checks too; `goldens` their detail.
pub fn document_with_golden(
    spec: &Spec,
    checks: &[Check],
    results: &[SceneResult],
    goldens: &[GoldenResult],
) -> Value {
    json!({
        "schema": 1,
        "name": spec.name,
        "tool_version": env!("CARGO_PKG_VERSION"),
        "spec_path": spec.path,
        "spec_sha256": sha256_hex(&spec.source),
        "passed": checks.iter().all(|c| c.passed),
        "checks": checks.iter().map(|c| json!({
            "id": c.id,
            "kind": match c.kind { CheckKind::Limit => "limit", CheckKind::Golden => "golden" },
            "value": num(c.value),
            "limit": num(c.limit),
            "unit": c.unit,
            "passed": c.passed,
            "at": c.at,
        })).collect::<Vec<_>>(),
        "golden": goldens.iter().map(golden).collect::<Vec<_>>(),
        "scenes": results.iter().map(scene).collect::<Vec<_>>(),
    })
}
