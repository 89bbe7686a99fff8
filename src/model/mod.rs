//! The data model: what a spec describes (design, modification, scenes and their plans,
//! limits, studies, goldens, accuracy settings), what the engine computes for a scene
//! (`results`), and the one registry of the quantities both are named by (`quantity`).
//! Plain data in engine units (mm, N, N·mm, rad, MPa); no computation beyond closed forms of
//! the design itself.

/// An enum whose variants each have one name, as the spec writes it: `ALL`, `name`,
/// `from_name`, `names` (for messages), `Display` and `FromStr`, from one table.
macro_rules! named {
    ($ty:ident $what:literal { $($variant:ident => $name:literal),+ $(,)? }) => {
        impl $ty {
            pub const ALL: [$ty; [$($name),+].len()] = [$($ty::$variant),+];

            /// The name the spec and the outputs use.
            pub fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }

            pub fn from_name(name: &str) -> Option<$ty> {
                Self::ALL.into_iter().find(|v| v.name() == name)
            }

            /// Every name, comma-separated, for messages.
            pub fn names() -> String {
                Self::ALL.map(|v| v.name()).join(", ")
            }
        }

        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $ty {
            type Err = String;

            fn from_str(s: &str) -> Result<Self, String> {
                Self::from_name(s)
                    .ok_or_else(|| format!("unknown {} `{s}`; known: {}", $what, Self::names()))
            }
        }
    };
}

pub mod accuracy;
pub mod design;
pub mod deviations;
pub mod golden;
pub mod limits;
pub mod measured;
pub mod quantity;
pub mod results;
pub mod scene;
pub mod study;
pub mod tolerances;

pub use design::{
    ConvexRadius, CrankBearing, Design, Locus, Material, Modification, OutputPins, MAX_DISCS,
};
pub use deviations::{CentreDeviation, Deviations, FormTerm, RollerDeviation};
pub use golden::{Golden, GoldenTolerance};
pub use limits::{Limit, Limits};
pub use scene::{
    ContactLaw, Detail, Effect, GeometryMode, Plan, PlannedDetail, PlannedEffect, Scene,
    TorqueSweep,
};
pub use study::{Objective, Study, Variable, VariableKind};

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
