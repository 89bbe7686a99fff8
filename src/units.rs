//! Every unit conversion of the tool, in one place.
//!
//! The engine works in mm, N, N·mm, rad and MPa. The spec's keys and the outputs' keys name
//! other units (N·m, GPa, deg, arcsec, arcmin, µm, h); a value crosses between the two only
//! through these functions, at the edges: `spec` (input), the quantity registry and `report`
//! (output), and the command line.

use std::f64::consts::PI;

/// Arcseconds in a radian.
pub const ARCSEC_PER_RAD: f64 = 180.0 * 3600.0 / PI;
/// Arcminutes in a radian.
pub const ARCMIN_PER_RAD: f64 = 180.0 * 60.0 / PI;
/// N·mm in a N·m.
pub const NMM_PER_NM: f64 = 1000.0;
/// MPa in a GPa.
pub const MPA_PER_GPA: f64 = 1000.0;
/// µm in a mm.
pub const UM_PER_MM: f64 = 1000.0;

/// rad → arcsec.
#[inline]
pub fn arcsec(rad: f64) -> f64 {
    rad * ARCSEC_PER_RAD
}

/// rad → arcmin.
#[inline]
pub fn arcmin(rad: f64) -> f64 {
    rad * ARCMIN_PER_RAD
}

/// arcsec → rad.
#[inline]
pub fn rad_from_arcsec(arcsec: f64) -> f64 {
    arcsec / ARCSEC_PER_RAD
}

/// rad → deg.
#[inline]
pub fn deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// deg → rad.
#[inline]
pub fn rad(deg: f64) -> f64 {
    deg.to_radians()
}

/// N·m → N·mm.
#[inline]
pub fn nmm(nm: f64) -> f64 {
    nm * NMM_PER_NM
}

/// N·mm → N·m.
#[inline]
pub fn nm(nmm: f64) -> f64 {
    nmm / NMM_PER_NM
}

/// A torsional compliance in arcmin/(kN·m) as rad/(N·mm).
#[inline]
pub fn rad_per_nmm_from_arcmin_per_knm(arcmin_per_knm: f64) -> f64 {
    arcmin_per_knm / ARCMIN_PER_RAD / (1e3 * NMM_PER_NM)
}

/// A torsional compliance in rad/(N·mm) as arcmin/(kN·m).
pub fn arcmin_per_knm(rad_per_nmm: f64) -> f64 {
    rad_per_nmm * ARCMIN_PER_RAD * (1e3 * NMM_PER_NM)
}

/// Torsional stiffness N·mm/rad → N·m/arcmin.
#[inline]
pub fn nm_per_arcmin(nmm_per_rad: f64) -> f64 {
    nm(nmm_per_rad) / ARCMIN_PER_RAD
}

/// GPa → MPa.
#[inline]
pub fn mpa(gpa: f64) -> f64 {
    gpa * MPA_PER_GPA
}

/// MPa → GPa.
#[inline]
pub fn gpa(mpa: f64) -> f64 {
    mpa / MPA_PER_GPA
}

/// mm → µm.
#[inline]
pub fn um(mm: f64) -> f64 {
    mm * UM_PER_MM
}

/// µm → mm.
#[inline]
pub fn mm_from_um(um: f64) -> f64 {
    um / UM_PER_MM
}

/// W in a N·mm/s.
pub const W_PER_NMM_PER_S: f64 = 1e-3;

/// mm → m.
#[inline]
pub fn m_from_mm(mm: f64) -> f64 {
    mm * 1e-3
}

/// rpm → rad/s: n·2π/60.
#[inline]
pub fn rad_per_s(rpm: f64) -> f64 {
    rpm * std::f64::consts::TAU / 60.0
}

/// N·mm/s → W.
#[inline]
pub fn w(nmm_per_s: f64) -> f64 {
    nmm_per_s * W_PER_NMM_PER_S
}

/// mm² in a m².
pub const MM2_PER_M2: f64 = 1e6;

/// A density in kg/m³ as kg/mm³.
#[inline]
pub fn kg_per_mm3(kg_per_m3: f64) -> f64 {
    kg_per_m3 * 1e-9
}

/// A density in kg/mm³ as kg/m³.
#[inline]
pub fn kg_per_m3(kg_per_mm3: f64) -> f64 {
    kg_per_mm3 * 1e9
}

/// A moment of inertia in kg·m² as kg·mm².
#[inline]
pub fn kgmm2(kgm2: f64) -> f64 {
    kgm2 * MM2_PER_M2
}

/// A moment of inertia in kg·mm² as kg·m².
#[inline]
pub fn kgm2(kgmm2: f64) -> f64 {
    kgmm2 / MM2_PER_M2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The conversions against their definitions: a full turn is 360° = 21600′ = 1296000″,
    /// and each pair of functions inverts.
    #[test]
    fn conversions_match_their_definitions() {
        let turn = 2.0 * PI;
        assert!((arcsec(turn) - 1_296_000.0).abs() < 1e-6);
        assert!((arcmin(turn) - 21_600.0).abs() < 1e-9);
        assert!((deg(turn) - 360.0).abs() < 1e-12);
        assert!((rad_from_arcsec(arcsec(0.3)) - 0.3).abs() < 1e-15);
        assert!((rad(deg(1.25)) - 1.25).abs() < 1e-15);
        assert_eq!(nm(nmm(2.5)), 2.5);
        assert_eq!(gpa(mpa(206.0)), 206.0);
        assert_eq!(mm_from_um(um(0.015)), 0.015);
        assert!((kg_per_m3(kg_per_mm3(7850.0)) - 7850.0).abs() < 1e-9);
        assert_eq!(kgm2(kgmm2(0.25)), 0.25);
    }
}
