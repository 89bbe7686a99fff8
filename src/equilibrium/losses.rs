//! What a sweep records of the friction at each angle it solves, for the effect `efficiency`
//! (MODEL.md "Friction, efficiency and heat"): the disc's contact losses
//! (`friction::loss::disc_losses`) and, with the coupled model, its share of the input torque
//! (`Coupling::input_torque`), each measured where the angle's solution is at hand.

use super::coupling::Coupling;
use crate::model::{Design, Friction, FrictionModel};

/// What a sweep records of the friction at each solved angle, for the effect `efficiency`
/// (`loaded::Model::losses`): the disc's contact losses (`disc_losses`) and, with the coupled
/// model, its share of the input torque (`Coupling::input_torque`), each from the solution at
/// hand.
#[derive(Debug, Clone)]
pub struct LossModel {
    pub friction: Friction,
    pub design: Design,
    /// The coupled model's friction coefficients, for the input torque; none for the loss
    /// model (whose input torque is the reducer's energy balance, `engine::efficiency`).
    pub input: Option<Coupling>,
}

impl LossModel {
    /// The losses of `friction` on `design`.
    pub fn new(friction: Friction, design: &Design) -> Self {
        let coupled = friction.model == FrictionModel::Coupled;
        LossModel {
            friction,
            design: design.clone(),
            input: coupled.then(|| Coupling::new(&friction, design)),
        }
    }
}
