//! The data model: what a spec describes (design, modification, scenes and their plans,
//! limits, studies, goldens, accuracy settings), what the engine computes for a scene
//! (`results`), and the one registry of the quantities both are named by (`quantity`).
//! Plain data in engine units (mm, N, N·mm, rad, MPa); no computation beyond closed forms of
//! the design itself.

#[macro_use]
mod named;

pub mod accuracy;
pub mod design;
pub mod deviations;
pub mod effect;
pub mod face;
pub mod friction;
pub mod golden;
pub mod limits;
pub mod measured;
pub mod modification;
pub mod period;
pub mod place;
pub mod power_flow;
pub mod quantity;
pub mod requirements;
pub mod results;
pub mod scene;
pub mod strength;
pub mod study;
pub mod tolerances;

pub use design::{
    ConvexRadius, CrankBearing, Design, Locus, Material, OutputPins, PinSupport, PinSupportKind,
    MAX_DISCS,
};
pub use deviations::{CentreDeviation, Deviations, FormTerm, RollerDeviation, MAX_FORM_ORDER};
pub use effect::{Detail, Effect};
pub use face::{Crowning, Face, Misalignment};
pub use friction::{
    BearingFriction, Friction, FrictionModel, NoLoadTorque, PinFriction, PinMode, RollerFriction,
    RollerMode, Thermal, MAX_NO_LOAD_POINTS,
};
pub use golden::{Golden, GoldenTolerance};
pub use limits::{Limit, Limits};
pub use modification::Modification;
pub use scene::{
    ContactLaw, DutyBin, GeometryMode, Plan, PlannedDetail, PlannedEffect, Scene, TorqueSweep,
};
pub use study::{Objective, Point, Study, Variable, VariableKind};

#[cfg(test)]
mod tests {
    use super::{ContactLaw, Effect, GeometryMode};

    /// Every name reads back as its variant, and an unknown one names the known ones.
    #[test]
    fn names_round_trip() {
        for e in Effect::ALL {
            assert_eq!(e.to_string().parse::<Effect>(), Ok(e));
        }
        for g in GeometryMode::ALL {
            assert_eq!(g.name().parse::<GeometryMode>(), Ok(g));
        }
        assert_eq!("first_order".parse(), Ok(GeometryMode::FirstOrder));
        assert_eq!(ContactLaw::ALL.len(), 2);
        assert_eq!(
            "bogus".parse::<ContactLaw>(),
            Err("unknown contact law `bogus`; known: paper_linear, hertz_nonlinear".to_string())
        );
    }
}
