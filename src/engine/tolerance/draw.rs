//! The draw of sample k: a ChaCha8 stream of its own (`rand_chacha`: seeded from the study's
//! seed, stream number k), so that sample k's deviations depend on (seed, k) alone and any
//! split of the samples over processes draws the same reducers. ChaCha8 is counter-based:
//! distinct streams of one key do not overlap (2⁶⁴ blocks each).
//!
//! Draw order (fixed; the samples CSV's column order): the parameters of
//! [`model::tolerances::parameters`](crate::model::tolerances::parameters), one draw each, every part independently.

use crate::model::tolerances::{Distribution, Parameter, PartTolerances};
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution as _, StandardNormal, StandardUniform};

/// The drawn values of sample `k`, mm, one per parameter of `params`.
pub fn sample(tol: &PartTolerances, params: &[Parameter], k: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(tol.seed);
    rng.set_stream(k);
    params.iter().map(|p| one(tol, p.kind, &mut rng)).collect()
}

/// One draw of `kind`: σ·z with z standard normal, drawn again beyond the cut at 6σ
/// ([`model::tolerances::NORMAL_CUT_SIGMA`](crate::model::tolerances::NORMAL_CUT_SIGMA); probability 2·10⁻⁹ per draw); or b·(2u − 1) with u
/// uniform in [0, 1).
fn one(tol: &PartTolerances, kind: crate::model::tolerances::Kind, rng: &mut ChaCha8Rng) -> f64 {
    match tol.distribution {
        Distribution::Normal => {
            let cut = crate::model::tolerances::NORMAL_CUT_SIGMA;
            loop {
                let z: f64 = StandardNormal.sample(rng);
                if z.abs() <= cut {
                    return tol.sigma_mm(kind) * z;
                }
            }
        }
        Distribution::Uniform => {
            let u: f64 = StandardUniform.sample(rng);
            tol.band_mm(kind) * (2.0 * u - 1.0)
        }
    }
}
