//! The physical effects a scene can ask for (`Effect`), and the costly details within them
//! that only some quantities need (`Detail`).

/// A physical effect a scene can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Effect {
    /// Unloaded gaps, backlash, unloaded TE, lost motion, minimum clearance.
    Clearance,
    /// Loaded lag, roller forces, contacts, Hertz pressure.
    RollerContact,
    /// Output-pin forces and pin deflection.
    OutputPins,
    /// Crank-bearing force from the force balance, equilibrium residuals.
    Bearing,
    /// Torsion under a locked input (a scene's `torque_sweep`): the torsion curve and the
    /// catalogue figures at each crank angle, solved with the loaded effects the scene asks for
    /// in place of their curves over the crank angle.
    Torsion,
    /// Friction losses path by path, efficiency, input torque and the steady temperature
    /// (`reducer.friction`, MODEL.md "Friction, efficiency and heat"), from the loaded
    /// sweep's contact forces.
    Efficiency,
    /// The output pins' bending and shear stresses, the disc's and the rollers' contact
    /// fatigue lives and the crank bearing's static safety (issue 41,
    /// `docs/effects/strength.md`), from the loaded sweep's forces and pressures.
    Strength,
    /// The discs' centripetal force at speed, m·(e + de)·ω² along the eccentric, in each
    /// disc's force balance, so that the crank-bearing force is the one at speed (issue 42,
    /// `docs/effects/inertia.md`); with several discs the unbalance they leave (force and
    /// couple).
    Inertia,
}

named!(Effect "effect" {
    Clearance => "clearance",
    RollerContact => "roller_contact",
    OutputPins => "output_pins",
    Bearing => "bearing",
    Torsion => "torsion",
    Efficiency => "efficiency",
    Strength => "strength",
    Inertia => "inertia",
});

impl Effect {
    /// Effects this one cannot be computed without.
    pub fn needs(self) -> &'static [Effect] {
        match self {
            Effect::Bearing => &[Effect::RollerContact, Effect::OutputPins],
            Effect::Torsion => &[Effect::RollerContact],
            Effect::Efficiency | Effect::Strength | Effect::Inertia => {
                &[Effect::RollerContact, Effect::OutputPins, Effect::Bearing]
            }
            _ => &[],
        }
    }

    /// Whether it is read off the loaded curves over the crank angle as the crank turns (a
    /// sweep's forces, lags and speeds), which a torsion scene, its input locked, does not
    /// compute; roller contact, output pins and the bearing are parts of its loaded model.
    pub fn reads_the_sweep(self) -> bool {
        matches!(
            self,
            Effect::Efficiency | Effect::Strength | Effect::Inertia
        )
    }

    /// The effects a scene's `effects` list names (`torsion` is asked for by `torque_sweep`).
    pub fn listed() -> impl Iterator<Item = Effect> {
        Effect::ALL.into_iter().filter(|&e| e != Effect::Torsion)
    }

    /// Whether it is solved under the scene's load at each crank angle (its curves are over
    /// the crank angle, which a torsion scene does not produce).
    pub fn is_loaded(self) -> bool {
        matches!(
            self,
            Effect::RollerContact
                | Effect::OutputPins
                | Effect::Bearing
                | Effect::Efficiency
                | Effect::Strength
                | Effect::Inertia
        )
    }
}

/// Work within an effect that only some of its quantities need, done only when one of them is
/// read (by a limit, a golden, an objective or an output file).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Detail {
    /// The closing lag of every roller at every crank angle, within `clearance`: backlash both
    /// ways and lost motion. The gaps and the smallest gap need none of it.
    Backlash,
}

named!(Detail "detail" {
    Backlash => "backlash",
});

impl Detail {
    /// The effect it is part of.
    pub fn effect(self) -> Effect {
        match self {
            Detail::Backlash => Effect::Clearance,
        }
    }
}
