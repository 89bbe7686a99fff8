//! Per-angle output quantities, named and scaled exactly as in the results JSON.
//!
//! One table serves the golden curves (`golden`), the report plots and their units. A quantity
//! is either one curve over crank angle (`te_arcsec`) or one curve per roller or pin
//! (`roller_force_n`); values are in the unit named by the key (arcsec, N, mm, MPa, deg).

use crate::model::results::SceneResult;
use crate::model::Effect;
use crate::units;

/// Rows [column][angle] in output units.
type Rows = Vec<Vec<f64>>;

/// One per-angle output quantity.
pub struct QuantityDef {
    /// Key in the results JSON and in `golden[].quantity`.
    pub key: &'static str,
    /// Unit for axis labels and messages ("" when dimensionless).
    pub unit: &'static str,
    /// What a person calls it.
    pub label: &'static str,
    /// The effect that computes it.
    pub effect: Effect,
    /// `Some("roller")`/`Some("pin")` when there is one curve per roller or pin.
    pub per: Option<&'static str>,
    /// For an angle that wraps (±180°), its period: deviations are taken modulo it.
    pub period: Option<f64>,
    get: fn(&SceneResult) -> Option<Rows>,
}

/// Named curves of one quantity over the crank angles of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Curves {
    /// Column names: the quantity key, or `roller_0`, `roller_1`, ... / `pin_0`, ...
    pub columns: Vec<String>,
    /// [column][angle], output units.
    pub values: Vec<Vec<f64>>,
}

fn arcsec(v: &[f64]) -> Rows {
    vec![v.iter().map(|&x| units::arcsec(x)).collect()]
}

fn one(v: &[f64]) -> Rows {
    vec![v.to_vec()]
}

/// Every per-angle output. The equilibrium `residual` is left out on purpose: it is solver
/// noise, not a property of the design, and a golden of noise can only flake.
pub const QUANTITIES: &[QuantityDef] = &[
    QuantityDef {
        key: "clearance_mm",
        unit: "mm",
        label: "clearance",
        effect: Effect::Clearance,
        per: Some("roller"),
        period: None,
        get: |r| r.clearance.as_ref().map(|c| c.gap_mm.clone()),
    },
    QuantityDef {
        key: "backlash_arcsec",
        unit: "arcsec",
        label: "backlash (unloaded TE)",
        effect: Effect::Clearance,
        per: None,
        period: None,
        get: |r| r.clearance.as_ref().map(|c| arcsec(&c.backlash_rad)),
    },
    QuantityDef {
        key: "backlash_reverse_arcsec",
        unit: "arcsec",
        label: "reverse backlash",
        effect: Effect::Clearance,
        per: None,
        period: None,
        get: |r| {
            r.clearance
                .as_ref()
                .map(|c| arcsec(&c.backlash_reverse_rad))
        },
    },
    QuantityDef {
        key: "lost_motion_arcsec",
        unit: "arcsec",
        label: "lost motion",
        effect: Effect::Clearance,
        per: None,
        period: None,
        get: |r| r.clearance.as_ref().map(|c| arcsec(&c.lost_motion_rad)),
    },
    QuantityDef {
        key: "lag_arcsec",
        unit: "arcsec",
        label: "disc lag β",
        effect: Effect::RollerContact,
        per: None,
        period: None,
        get: |r| r.loaded.rollers.as_ref().map(|c| arcsec(&c.lag_rad)),
    },
    QuantityDef {
        key: "te_arcsec",
        unit: "arcsec",
        label: "loaded transmission error",
        effect: Effect::RollerContact,
        per: None,
        period: None,
        get: |r| r.loaded.transmission.as_ref().map(|t| arcsec(&t.te_rad)),
    },
    QuantityDef {
        key: "ratio",
        unit: "",
        label: "transmission ratio κ",
        effect: Effect::RollerContact,
        per: None,
        period: None,
        get: |r| {
            r.loaded
                .transmission
                .as_ref()
                .and_then(|t| t.ratio.as_deref().map(one))
        },
    },
    QuantityDef {
        key: "roller_force_n",
        unit: "N",
        label: "roller force",
        effect: Effect::RollerContact,
        per: Some("roller"),
        period: None,
        get: |r| r.loaded.rollers.as_ref().map(|c| c.force_n.clone()),
    },
    QuantityDef {
        key: "contact_pressure_mpa",
        unit: "MPa",
        label: "Hertz peak pressure",
        effect: Effect::RollerContact,
        per: Some("roller"),
        period: None,
        get: |r| r.loaded.rollers.as_ref().map(|c| c.pressure_mpa.clone()),
    },
    QuantityDef {
        key: "contact_half_width_mm",
        unit: "mm",
        label: "contact half-width",
        effect: Effect::RollerContact,
        per: Some("roller"),
        period: None,
        get: |r| r.loaded.rollers.as_ref().map(|c| c.half_width_mm.clone()),
    },
    QuantityDef {
        key: "contacts",
        unit: "",
        label: "rollers in contact",
        effect: Effect::RollerContact,
        per: None,
        period: None,
        get: |r| {
            r.loaded
                .rollers
                .as_ref()
                .map(|c| vec![c.contacts.iter().map(|&n| n as f64).collect()])
        },
    },
    QuantityDef {
        key: "output_lag_arcsec",
        unit: "arcsec",
        label: "output lag βo",
        effect: Effect::OutputPins,
        per: None,
        period: None,
        get: |r| r.loaded.pins.as_ref().map(|p| arcsec(&p.output_lag_rad)),
    },
    QuantityDef {
        key: "pin_force_n",
        unit: "N",
        label: "output-pin force",
        effect: Effect::OutputPins,
        per: Some("pin"),
        period: None,
        get: |r| r.loaded.pins.as_ref().map(|p| p.force_n.clone()),
    },
    QuantityDef {
        key: "bearing_force_n",
        unit: "N",
        label: "crank-bearing force",
        effect: Effect::Bearing,
        per: None,
        period: None,
        get: |r| r.loaded.bearing.as_ref().map(|b| one(&b.force_n)),
    },
    QuantityDef {
        key: "bearing_angle_deg",
        unit: "deg",
        label: "crank-bearing force angle ε",
        effect: Effect::Bearing,
        per: None,
        period: Some(360.0),
        get: |r| {
            r.loaded
                .bearing
                .as_ref()
                .map(|b| vec![b.angle_rad.iter().map(|&a| units::deg(a)).collect()])
        },
    },
    QuantityDef {
        key: "bearing_deflection_mm",
        unit: "mm",
        label: "crank-bearing deflection",
        effect: Effect::Bearing,
        per: None,
        period: None,
        get: |r| r.loaded.bearing.as_ref().map(|b| one(&b.deflection_mm)),
    },
];

/// The quantity with this key.
pub fn find(key: &str) -> Option<&'static QuantityDef> {
    QUANTITIES.iter().find(|q| q.key == key)
}

/// Every key, comma-separated, for error messages.
pub fn known_keys() -> String {
    QUANTITIES
        .iter()
        .map(|q| q.key)
        .collect::<Vec<_>>()
        .join(", ")
}

impl QuantityDef {
    /// The quantity's curves in a scene's results; `None` when the scene did not compute it.
    pub fn curves(&self, r: &SceneResult) -> Option<Curves> {
        let values = (self.get)(r)?;
        let columns = match self.per {
            Some(what) => (0..values.len()).map(|i| format!("{what}_{i}")).collect(),
            None => vec![self.key.to_string()],
        };
        Some(Curves { columns, values })
    }

    /// "label (unit)" for an axis.
    pub fn axis_label(&self) -> String {
        if self.unit.is_empty() {
            self.label.to_string()
        } else {
            format!("{} ({})", self.label, self.unit)
        }
    }
}
