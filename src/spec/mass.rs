//! `reducer.material.density_kg_per_m3`, `reducer.output_inertia_kgm2` and
//! `reducer.roller_inertia_kgm2`: what the discs' mass and the inertia at the input are
//! computed from.

use super::raw::RawReducer;
use super::values::{finite, positive, zero_or_positive};
use crate::error::{Error, Result};
use crate::model::{Design, RollerMode};
use crate::{numeric, units};

/// Default density of every part (a spec's and the requirements'): steel, 7,850 kg/m³.
pub const STEEL_DENSITY_KG_PER_M3: f64 = 7850.0;

/// The mass inputs of a reducer, engine units.
pub(super) struct MassInputs {
    pub density_kg_per_mm3: f64,
    pub output_inertia_kgmm2: f64,
}

/// The disc's density (> 0, steel's by default) and the output's inertia (≥ 0, 0 by
/// default). A density under `roller_material` is refused: only the discs' mass is computed,
/// and a value that changes nothing would mislead.
pub(super) fn inputs(raw: &RawReducer) -> Result<MassInputs> {
    if let Some(d) = raw.roller_material.and_then(|m| m.density_kg_per_m3) {
        return Err(Error::invalid(
            "reducer.roller_material.density_kg_per_m3",
            format!(
                "the rollers' and pins' mass is not computed (only the discs', from \
                 `reducer.material.density_kg_per_m3`), so {} kg/m³ would change nothing: \
                 remove it",
                numeric::input(d)
            ),
        ));
    }
    let density = raw
        .material
        .density_kg_per_m3
        .unwrap_or(STEEL_DENSITY_KG_PER_M3);
    let density = positive("reducer.material.density_kg_per_m3", density)?;
    let key = "reducer.output_inertia_kgm2";
    let output = zero_or_positive(key, finite(key, raw.output_inertia_kgm2.unwrap_or(0.0))?)?;
    Ok(MassInputs {
        density_kg_per_mm3: units::kg_per_mm3(density),
        output_inertia_kgmm2: units::kgmm2(output),
    })
}

/// `reducer.roller_inertia_kgm2`, kg·mm² (0 when not given): ≥ 0, and only for rollers that
/// turn on their pins (`reducer.friction.rollers.mode: rotating`): a fixed roller does not
/// spin, and a value that changes nothing would mislead.
pub(super) fn roller_inertia(kgm2: Option<f64>, design: &Design) -> Result<f64> {
    let key = "reducer.roller_inertia_kgm2";
    let Some(j) = kgm2 else {
        return Ok(0.0);
    };
    let j = zero_or_positive(key, finite(key, j)?)?;
    let rollers = design.friction.and_then(|f| f.rollers).map(|r| r.mode);
    if !matches!(rollers, Some(RollerMode::Rotating { .. })) {
        return Err(Error::invalid(
            key,
            format!(
                "the rollers spin only when they turn on their pins \
                 (`reducer.friction.rollers.mode: rotating`); here they {}, so {} kg·m² would \
                 change nothing: remove it or give rotating rollers",
                match rollers {
                    Some(_) => "are fixed",
                    None => "have no friction mode given",
                },
                numeric::input(j)
            ),
        ));
    }
    Ok(units::kgmm2(j))
}
