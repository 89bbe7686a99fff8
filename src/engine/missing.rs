//! Why a scene's results lack a quantity whose effect the scene computes (the spec's coverage,
//! `spec::coverage`, has let it through): the words of the error of a golden
//! (`engine::golden::computed`) and of an optimisation objective (`engine::optimise::problem`)
//! whose quantity the run left out. The registry's readers return `None` beyond their effect
//! when the scene's results cannot hold the quantity; the reasons are read here from the
//! results.

use crate::model::quantity::{self, Quantity};
use crate::model::results::SceneResult;

/// "scene `rated` computed no `torque_nm` (disc torque share Tk): a disc's share of the torque
/// is computed with several discs only": the quantity, that the scene did not compute it, and
/// why when `r` says.
pub fn not_computed(q: &Quantity, r: &SceneResult) -> String {
    let what = format!("scene `{}` computed no `{}` ({})", r.name, q.key, q.label);
    match why(q, r) {
        Some(why) => format!("{what}: {why}"),
        None => what,
    }
}

/// Why `r` lacks `q` (a curve, or a scalar of one), where its results tell.
fn why(q: &Quantity, r: &SceneResult) -> Option<String> {
    let is = |c: &Quantity| q == c || q.of == Some(c.key);
    let angles = r.crank_rad.len();
    if is(&quantity::RATIO) && angles < 3 {
        Some(format!(
            "a ratio needs at least 3 crank angles, the scene has {angles}"
        ))
    } else if is(&quantity::DISC_TORQUE) && r.discs.len() == 1 {
        Some("a disc's share of the torque is computed with several discs only".to_string())
    } else if (is(&quantity::HYSTERESIS_LOSS) || is(&quantity::HYSTERESIS_ENERGY))
        && r.reducer.torsion.as_ref().is_some_and(|t| !t.friction)
    {
        Some("its torsion loop has no friction to lose (give `reducer.friction`)".to_string())
    } else {
        None
    }
}
