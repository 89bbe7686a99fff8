//! The reducer's mass properties: each disc's mass and inertia from its exact modified profile
//! (the disc as built when the spec was measured), and the inertia at the input.

use crate::geometry::disc_solid;
use crate::geometry::mass_properties::{face_moments, DiscMass, SECTION_TOLERANCE_MM};
use crate::geometry::profile::Profile;
use crate::model::{Design, Modification};

/// The discs' mass properties and the reducer's inertia at the input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// One disc (the discs are identical).
    pub disc: DiscMass,
    /// J_in, kg·mm²: Σ over the discs of m·e² + J_c/nc², plus the output's J_out/nc² (the
    /// output turns at ω/nc); the rollers, pins, crank shaft and its bearings are not in it.
    pub input_inertia_kgmm2: f64,
}

/// The mass properties of `design`'s discs under `modification`, with the disc's form error
/// when it has one: the face inside the profile's polygon within `SECTION_TOLERANCE_MM`, less
/// the output-pin holes and the bore of `disc_solid`, over the face width at the density.
pub fn mass_properties(design: &Design, modification: &Modification) -> MassProperties {
    let profile = Profile::new(design, modification).with_form(&design.deviations.form);
    let holes = disc_solid::pin_holes(&design.pins, design.hole_radius_mm());
    let bore = disc_solid::bore(design);
    let face = face_moments(&profile, &holes, bore.as_ref(), SECTION_TOLERANCE_MM);
    let disc = DiscMass::new(face, design.face_width_mm, design.density_kg_per_mm3);
    let nc = design.teeth as f64;
    let discs =
        design.discs as f64 * disc.input_inertia_kgmm2(design.eccentricity_mm, design.teeth);
    MassProperties {
        disc,
        input_inertia_kgmm2: discs + design.output_inertia_kgmm2 / (nc * nc),
    }
}
