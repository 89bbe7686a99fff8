//! `reducer.material.density_kg_per_m3`, `reducer.output_inertia_kgm2` and
//! `reducer.roller_inertia_kgm2`: what the discs' mass and the inertia at the input are
//! computed from.

use super::raw::RawReducer;
use super::values::{finite, within, zero_or_positive};
use crate::error::{Error, Result};
use crate::model::{Design, RollerMode};
use crate::{numeric, units};

/// Default density of every part (a spec's and the requirements'): steel, 7,850 kg/m³.
pub const STEEL_DENSITY_KG_PER_M3: f64 = 7850.0;

/// Smallest and largest density of a disc, kg/m³: an aerogel's (about 1) to four times
/// osmium's 22,590, the densest element; beyond them a mass, and the unbalance it makes, is
/// no part's.
const DENSITY_KG_PER_M3: (f64, f64) = (1.0, 1e5);

/// A density (kg/m³) written at `key` (steel's when not given), within `DENSITY_KG_PER_M3`:
/// a spec's discs and the requirements' parts.
pub(super) fn density(key: &str, kg_per_m3: Option<f64>) -> Result<f64> {
    let value = kg_per_m3.unwrap_or(STEEL_DENSITY_KG_PER_M3);
    let why = "a solid part lies between an aerogel (about 1 kg/m³) and osmium (22,590 kg/m³)";
    within(key, value, DENSITY_KG_PER_M3, "kg/m³", why)
}

/// The mass inputs of a reducer, engine units.
pub(super) struct MassInputs {
    pub density_kg_per_mm3: f64,
    pub output_inertia_kgmm2: f64,
}

/// The disc's density (`density`, steel's by default) and the output's inertia (≥ 0, 0 by
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
    let density = density(
        "reducer.material.density_kg_per_m3",
        raw.material.density_kg_per_m3,
    )?;
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
