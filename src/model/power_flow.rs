//! The power that flows through the reducer (MODEL.md "Friction, efficiency and heat", issue 39
//! §3): which side drives, from the sign of the output torque against the direction of
//! rotation, and the efficiency of that flow. The one home of that decision: the scene's
//! efficiency (`engine::efficiency`), the duty cycle's energy-weighted efficiency
//! (`engine::duty_cycle`), the efficiency-against-torque curve and every report read it.
//!
//! Kinematics are the forward ones (input at ω ≥ 0, the output flange at −ω/nc; a negative
//! speed is refused by the spec), so the sign of the output torque T (the load on the disc,
//! positive against the motion) decides: T ≥ 0 resists the output's motion and the input
//! drives; T < 0 pushes the output along its motion (a load lowered, a joint braked) and the
//! output drives, the reducer back-driven. Powers per unit input speed, N·mm/rad (the power at
//! ω = 1 rad/s): P = |T|·ω_out = |T|/nc passes the output flange either way.
//! - input drives: P + loss enters at the input, P leaves at the output: η = P/(P + loss);
//! - output drives: P enters at the output, P − loss reaches the input: η = (P − loss)/P. Where
//!   the loss takes all of P (η ≤ 0) the reducer self-locks: the input must push as well to
//!   keep it turning, and nothing reaches it. η ≤ 0 is the back-driving efficiency of the
//!   self-locking drives of the literature (e.g. a worm pair's tan(γ − ρ)/tan γ < 0), not
//!   clamped: how far below 0 says how hard the input must push.

/// The side of the reducer whose power enters it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Driver {
    /// The input drives, the output torque resists the motion (T ≥ 0).
    Input,
    /// The output drives, its torque pushes along the motion (T < 0): back-driven.
    Output,
}

/// The flow of one run: its driving side and the power through the output flange.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerFlow {
    /// The side whose power enters the reducer.
    pub driver: Driver,
    /// P = |T|/nc, N·mm/rad: the power through the output flange per unit input speed.
    pub output_power_nmm: f64,
}

/// The energy of a run per unit input speed, N·mm/rad: what enters the reducer (at either
/// side) and what reaches the driven side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Energy {
    /// What enters the reducer, at either side.
    pub entering_nmm: f64,
    /// What reaches the driven side (0 where it self-locks).
    pub delivered_nmm: f64,
}

impl PowerFlow {
    /// The flow at output torque `output_torque_nmm` (N·mm, all discs; positive against the
    /// output's forward motion) of a reducer of `teeth` disc teeth (nc).
    pub fn new(output_torque_nmm: f64, teeth: usize) -> Self {
        PowerFlow {
            driver: match output_torque_nmm < 0.0 {
                true => Driver::Output,
                false => Driver::Input,
            },
            output_power_nmm: output_torque_nmm.abs() / teeth as f64,
        }
    }

    /// The efficiency at `loss_nmm` (N·mm/rad): P/(P + loss) with the input driving (1 when
    /// nothing is lost, 0 when only loss: no output torque), (P − loss)/P with the output
    /// driving (≤ 0 where it self-locks).
    pub fn efficiency(&self, loss_nmm: f64) -> f64 {
        let p = self.output_power_nmm;
        match self.driver {
            Driver::Input if p + loss_nmm > 0.0 => p / (p + loss_nmm),
            Driver::Input => 1.0,
            Driver::Output => (p - loss_nmm) / p,
        }
    }

    /// Whether the loss `loss_nmm` takes all the power the driving output brings: the reducer
    /// self-locks (never with the input driving).
    pub fn self_locks(&self, loss_nmm: f64) -> bool {
        self.driver == Driver::Output && loss_nmm >= self.output_power_nmm
    }

    /// What enters and what is delivered at `loss_nmm`: the input driving, P + loss in and P
    /// out; the output driving, P in and P − loss out; self-locked, P at the output and
    /// loss − P at the input in, all of it lost.
    pub fn energy(&self, loss_nmm: f64) -> Energy {
        let p = self.output_power_nmm;
        let (entering_nmm, delivered_nmm) = match self.driver {
            Driver::Input => (p + loss_nmm, p),
            Driver::Output if self.self_locks(loss_nmm) => (loss_nmm, 0.0),
            Driver::Output => (p, p - loss_nmm),
        };
        Energy {
            entering_nmm,
            delivered_nmm,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Driver, PowerFlow};

    /// Limit cases: nothing lost is 1 either way; the output driving loses what it brings at
    /// loss = P (η = 0, self-locked), and η rises to 1 as the loss falls; the energy balance
    /// entering = delivered + lost holds on every branch. Exact arithmetic on small integers.
    #[test]
    fn the_flow_follows_the_sign_of_the_torque() {
        let back = PowerFlow::new(-90.0, 9);
        assert_eq!((back.driver, back.output_power_nmm), (Driver::Output, 10.0));
        assert_eq!(back.efficiency(0.0), 1.0);
        assert_eq!(back.efficiency(4.0), 0.6);
        assert_eq!(back.efficiency(10.0), 0.0);
        assert_eq!(back.efficiency(15.0), -0.5);
        assert!(back.self_locks(10.0) && !back.self_locks(9.0));
        let forward = PowerFlow::new(90.0, 9);
        assert_eq!(forward.driver, Driver::Input);
        assert_eq!(forward.efficiency(15.0), 0.4);
        assert!(!forward.self_locks(1e9));
        assert_eq!(PowerFlow::new(0.0, 9).efficiency(1.0), 0.0);
        assert_eq!(PowerFlow::new(0.0, 9).efficiency(0.0), 1.0);
        for flow in [back, forward] {
            for loss in [0.0, 4.0, 10.0, 15.0] {
                let e = flow.energy(loss);
                assert_eq!(e.entering_nmm - e.delivered_nmm, loss, "{flow:?} {loss}");
            }
        }
    }
}
