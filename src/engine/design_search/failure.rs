//! A requirement of a design search, and a design's miss of it: a typed value (which
//! requirement, and the design's value against its limit, or what the engine said).

use crate::engine::limit::excess;
use crate::model::quantity::{find_limit, Bound, LimitDef};

/// A requirement a design of the search must meet.
#[derive(Debug, Clone, PartialEq)]
pub enum Requirement {
    /// `envelope.max_outer_diameter_mm`: 2·(Rp + Rrp + housing wall) at most, mm.
    OuterDiameter,
    /// `envelope.max_axial_length_mm`: discs·B + allowance at most, mm.
    AxialLength,
    /// `rules.max_k1`: K1 = e·np/Rp at most (and below 1, the spec's own rule).
    MaxK1,
    /// `rules.min_roller_gap_mm`: 2·Rp·sin(π/np) − 2·Rrp at least, mm.
    MinRollerGap,
    /// `rules.min_ligament_mm`: the smallest pin-hole ligament at least, mm.
    MinLigament,
    /// `crowning.start_mm`: a circular crown's flat half-length z0 below B/2, mm (recorded
    /// as z0 against B/2).
    CrownStart,
    /// A rule of the spec itself (`spec::rules`: undercut, rollers overlapping, holes, …),
    /// by the key where the candidate's spec is refused.
    SpecRule(String),
    /// The contact model holds the scenes' torques (a scene that cannot be computed).
    Torque,
    /// A limit of `limits:`, checked on every scene that computes its quantity.
    Limit(&'static LimitDef),
}

impl Requirement {
    /// The requirements file's key of the requirement (`rules` for a rule of the spec,
    /// `torque` for the contact model's reach): its name in reports and shards.
    pub fn key(&self) -> String {
        match self {
            Requirement::OuterDiameter => "envelope.max_outer_diameter_mm".into(),
            Requirement::AxialLength => "envelope.max_axial_length_mm".into(),
            Requirement::MaxK1 => "rules.max_k1".into(),
            Requirement::MinRollerGap => "rules.min_roller_gap_mm".into(),
            Requirement::MinLigament => "rules.min_ligament_mm".into(),
            Requirement::CrownStart => "crowning.start_mm".into(),
            Requirement::SpecRule(at) => format!("rules ({at})"),
            Requirement::Torque => "torque".into(),
            Requirement::Limit(def) => format!("limits.{}", def.key),
        }
    }

    /// The limit of `limits:` with this key.
    pub fn limit(key: &str) -> Option<Requirement> {
        find_limit(key).map(Requirement::Limit)
    }

    /// The unit of its value and limit ("" for K1, a count or a ratio).
    pub fn unit(&self) -> &'static str {
        match self {
            Requirement::MaxK1 | Requirement::SpecRule(_) | Requirement::Torque => "",
            Requirement::Limit(def) => def.quantity.unit,
            _ => "mm",
        }
    }

    /// Which side of its limit passes.
    pub fn bound(&self) -> Bound {
        match self {
            Requirement::MinRollerGap | Requirement::MinLigament => Bound::Min,
            Requirement::Limit(def) => def.bound,
            _ => Bound::Max,
        }
    }
}

/// How a design misses a requirement.
#[derive(Debug, Clone, PartialEq)]
pub enum Miss {
    /// The design's value beyond the requirement's limit, both in the requirement's unit.
    Bound { value: f64, limit: f64 },
    /// What the engine said: a rule of the spec refused, a torque the contacts cannot hold.
    Said(String),
}

/// A requirement a design does not meet.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    pub requirement: Requirement,
    pub miss: Miss,
}

impl Failure {
    /// A bound missed: the design's `value` beyond `limit`.
    pub fn bound(requirement: Requirement, value: f64, limit: f64) -> Failure {
        Failure {
            requirement,
            miss: Miss::Bound { value, limit },
        }
    }

    /// How far beyond its limit, relative (`engine::limit::excess`); a failure without a
    /// number ranks beyond every bound.
    pub fn excess(&self) -> f64 {
        match self.miss {
            Miss::Bound { value, limit } => excess(value, limit, self.requirement.bound()),
            Miss::Said(_) => f64::MAX,
        }
    }
}
