//! One point of the design space: its discrete choices and continuous values, the figures that
//! follow from its geometry alone (envelope, mass) and the spec that checks it, built as the
//! spec's raw form (no text).

use crate::error::Result;
use crate::geometry::disc_solid;
use crate::geometry::mass_properties::DiscMass;
use crate::geometry::profile::Profile;
use crate::model::requirements::{loaded_mesh_periods, Continuous, Requirements, Variables};
use crate::model::strength::PartStrength;
use crate::model::{Crowning, Friction, Material, OutputPins, PinMode, RollerMode};
use crate::spec::raw::*;
use crate::spec::requirements::STEEL_DENSITY_KG_PER_M3;
use crate::spec::Spec;
use crate::units;

/// A discrete choice: the disc's teeth nc (the ratio), the output pins M and the discs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Choice {
    pub teeth: usize,
    pub pins: usize,
    pub discs: usize,
}

/// A design of the search: a choice and the eight continuous values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    pub choice: Choice,
    pub x: Variables<f64>,
}

impl Candidate {
    /// The design at `u` (eight numbers in [0, 1]) of the requirements' ranges.
    pub fn at(choice: Choice, space: &Continuous, u: &[f64; 8]) -> Candidate {
        let ranges = space.to_array();
        let x = std::array::from_fn(|k| ranges[k].at(u[k]));
        Candidate {
            choice,
            x: Variables::from_array(x),
        }
    }

    /// np = nc + 1.
    pub fn rollers(&self) -> usize {
        self.choice.teeth + 1
    }

    /// Outer diameter, mm: 2·(Rp + Rrp + w), w the housing wall beyond the rollers.
    pub fn outer_diameter_mm(&self, req: &Requirements) -> f64 {
        2.0 * (self.x.roller_circle_radius_mm
            + self.x.roller_radius_mm
            + req.envelope.housing_wall_mm)
    }

    /// Axial length, mm: discs·B + the axial allowance (bearings, covers).
    pub fn axial_length_mm(&self, req: &Requirements) -> f64 {
        self.choice.discs as f64 * self.x.face_width_mm + req.envelope.axial_allowance_mm
    }

    /// Hole radius rh = rpin + e + hole clearance, mm (`Design::hole_radius_mm`).
    pub fn hole_radius_mm(&self, req: &Requirements) -> f64 {
        self.x.pin_radius_mm + self.x.eccentricity_mm + req.search.hole_clearance_mm
    }

    /// Mass of the parts that carry the torque, kg: discs × the disc's mass from its exact
    /// modified profile less its M holes of radius rh = rpin + e + hole clearance (the check's
    /// own `geometry::mass_properties`, with no bore: the requirements give none), plus the np
    /// rollers and M pins as cylinders as long as the discs' stack,
    /// ρ·B·discs·(np·π·Rrp² + M·π·rpin²); ρ the requirements' density (steel 7,850 kg/m³ by
    /// default).
    pub fn mass_kg(&self, req: &Requirements) -> f64 {
        use std::f64::consts::PI;
        let x = &self.x;
        let m = self.choice.pins as f64;
        let discs = self.choice.discs as f64;
        let rollers = self.rollers() as f64 * PI * x.roller_radius_mm * x.roller_radius_mm;
        let pins = m * PI * x.pin_radius_mm * x.pin_radius_mm;
        discs * self.disc_mass(req).mass_kg
            + req.density_kg_per_mm3 * x.face_width_mm * discs * (rollers + pins)
    }

    /// One disc's mass properties (`geometry::mass_properties`), as `check` computes them.
    fn disc_mass(&self, req: &Requirements) -> DiscMass {
        let x = &self.x;
        let profile = Profile::from_parts(
            self.rollers(),
            x.eccentricity_mm,
            x.roller_circle_radius_mm + x.shift_mm,
            x.roller_radius_mm + x.equidistant_mm,
            0.0,
        );
        let pins = OutputPins {
            count: self.choice.pins,
            circle_radius_mm: x.pin_circle_radius_mm,
            pin_radius_mm: x.pin_radius_mm,
            hole_clearance_mm: req.search.hole_clearance_mm,
            support: None,
        };
        let holes = disc_solid::pin_holes(&pins, self.hole_radius_mm(req));
        DiscMass::of_face(
            &profile,
            &holes,
            None,
            x.face_width_mm,
            req.density_kg_per_mm3,
        )
    }
}

/// The validated spec of `c` under `req` (`raw_spec`, checked as any spec is: the same rules,
/// face and bearing checks), named `name`, with no text; an error names its key path.
pub fn spec(req: &Requirements, c: &Candidate, name: &str, steps: usize) -> Result<Spec> {
    crate::spec::from_raw(&format!("{name}.yaml"), raw_spec(req, c, name, steps))
}

/// The spec of `c` under `req` in the spec's own raw form (what its YAML reads as), named
/// `name`, with `steps` crank angles per mesh period (the screen runs a quarter of the full
/// check's, every fourth of its angles): its reducer, the scenes the requirements need and
/// their limits. [`spec`] validates it; the front's designs are written from it (`engine::commands::spec_text`).
///
/// Scenes: `mesh` (unloaded, one mesh period: clearance and lost motion), `rated` (the rated
/// torque and speed over the loaded period: forces, pressure, TE, bearing life; with
/// `friction` the efficiency), `peak` (the peak torque, when above the rated: forces and
/// pressure; no bearing, whose life is the rated scene's), `duty` (the duty cycle's bins over
/// the loaded period, when one is given: its life and, with friction, its efficiency by
/// energy; every bin judged on the forces and pressure) and `torsion` (the catalogue loop at
/// the rated torque, when a rigidity, torsional lost motion or hysteresis is asked for).
pub(crate) fn raw_spec(req: &Requirements, c: &Candidate, name: &str, steps: usize) -> RawSpec {
    let x = &c.x;
    RawSpecOf {
        name: name.to_string(),
        reducer: RawReducer {
            teeth: c.choice.teeth as i64,
            rollers: c.rollers() as i64,
            discs: c.choice.discs as i64,
            eccentricity_mm: x.eccentricity_mm,
            roller_circle_radius_mm: x.roller_circle_radius_mm,
            roller_radius_mm: x.roller_radius_mm,
            face_width_mm: x.face_width_mm,
            output_pins: RawOutputPins {
                count: c.choice.pins as i64,
                circle_radius_mm: x.pin_circle_radius_mm,
                pin_radius_mm: x.pin_radius_mm,
                hole_clearance_mm: req.search.hole_clearance_mm,
                support: req.pin_support.map(|s| RawPinSupport {
                    kind: s.kind.name().to_string(),
                    length_mm: s.length_mm,
                    disc_positions_mm: s.disc_positions_mm[..c.choice.discs].to_vec(),
                }),
            },
            material: RawMaterial {
                density_kg_per_m3: density_unless_steel(req),
                ..raw_material(&req.material, &req.strength.disc)
            },
            roller_material: (req.roller_material).map(|m| raw_material(&m, &req.strength.rollers)),
            crank_bearing: req.crank_bearing.map(|b| RawCrankBearing {
                dynamic_load_rating_n: b.dynamic_load_rating_n,
                life_exponent: Some(b.life_exponent),
                outer_diameter_mm: None,
                static_load_rating_n: b.static_load_rating_n,
            }),
            friction: req.friction.as_ref().map(raw_friction),
            thermal: req.thermal.as_ref().map(|t| RawThermal {
                housing_area_m2: t.housing_area_m2,
                heat_transfer_w_per_m2k: t.heat_transfer_w_per_m2k,
                ambient_c: t.ambient_c,
            }),
            ..RawReducer::default()
        },
        modification: RawModification {
            shift_mm: x.shift_mm,
            equidistant_mm: x.equidistant_mm,
            rotation_deg: 0.0,
            crowning: raw_crowning(&req.crowning),
        },
        scenes: raw_scenes(req, c, steps),
        limits: (req.limits.entries.iter())
            .map(|l| (l.def.key.to_string(), RawLimit::Bound(l.value)))
            .collect(),
        optimise: None,
        golden: Vec::new(),
        golden_root: None,
        accuracy: None,
        measured_profile: None,
        tolerances: None,
    }
}

/// The scenes of [`raw_spec`]; the torsion scene stays aligned (its face is uniform, one
/// slice, unless crowned: then the spec's rule cuts every loaded crowned face into slices).
fn raw_scenes(req: &Requirements, c: &Candidate, steps: usize) -> Vec<RawScene> {
    let m = &req.misalignment;
    let mesh_deg = 360.0 / c.rollers() as f64;
    // The crank period of the loaded curves under the requirements' tilt, in mesh periods.
    let periods = loaded_mesh_periods(c.choice.teeth, c.choice.pins, !m.is_zero());
    let crank = |to_deg: f64, steps: usize| RawCrank {
        from_deg: 0.0,
        to_deg,
        steps: steps as i64,
    };
    let scene = |name: &str, effects: &[&str]| RawScene {
        name: name.to_string(),
        crank: crank(mesh_deg, steps),
        effects: effects.iter().map(|e| e.to_string()).collect(),
        ..RawScene::default()
    };
    // A running scene (rated, peak, duty): the loaded period, the requirements' tilt and slices.
    let loaded = |name: &str, effects: &[&str]| RawScene {
        crank: crank(mesh_deg * periods as f64, steps * periods),
        misalignment: (!m.is_zero()).then_some(RawMisalignment {
            about_x_mrad: 1e3 * m.about_x_rad,
            about_y_mrad: 1e3 * m.about_y_rad,
        }),
        face_slices: (req.face_slices > 1).then_some(req.face_slices as i64),
        ..scene(name, effects)
    };
    let running: &[&str] = match req.friction {
        Some(_) => &["bearing", "efficiency"],
        None => &["bearing"],
    };
    // The strength limits are judged in the scene at speed: the rated one, or the duty cycle's
    // (its bins carry the speeds; the rated scene then has none).
    let running_with_strength = |here: bool| {
        let strength: &[&str] = match here && req.needs_strength() {
            true => &["strength"],
            false => &[],
        };
        [running, strength].concat()
    };
    let mut scenes = vec![scene("mesh", &["clearance"])];
    scenes.push(RawScene {
        output_torque_nm: Some(units::nm(req.rated_torque_nmm)),
        input_speed_rpm: req.input_speed_rpm,
        ..loaded("rated", &running_with_strength(req.duty_cycle.is_none()))
    });
    if req.peak_torque_nmm > req.rated_torque_nmm {
        scenes.push(RawScene {
            output_torque_nm: Some(units::nm(req.peak_torque_nmm)),
            ..loaded("peak", &["roller_contact", "output_pins"])
        });
    }
    if let Some(bins) = &req.duty_cycle {
        let bins = (bins.iter())
            .map(|b| RawDutyBin {
                output_torque_nm: units::nm(b.output_torque_nmm),
                input_speed_rpm: b.input_speed_rpm,
                time_share: b.time_share,
            })
            .collect();
        scenes.push(RawScene {
            duty_cycle: Some(bins),
            ..loaded("duty", &running_with_strength(true))
        });
    }
    if req.needs_torsion() {
        scenes.push(RawScene {
            torque_sweep: Some(RawTorqueSweep {
                rated_nm: units::nm(req.rated_torque_nmm),
                steps: 8,
            }),
            crank: crank(mesh_deg, 4),
            face_slices: (req.crowning != Crowning::None).then_some(req.face_slices as i64),
            ..scene("torsion", &["output_pins"])
        });
    }
    scenes
}

/// A spec's material of `m` with the strength `s` (its yield strength and S–N law).
fn raw_material(m: &Material, s: &PartStrength) -> RawMaterial {
    RawMaterial {
        youngs_modulus_gpa: units::gpa(m.youngs_modulus_mpa),
        poisson_ratio: m.poisson_ratio,
        yield_strength_mpa: s.yield_strength_mpa,
        contact_fatigue: s.contact_fatigue.map(|f| RawContactFatigue {
            pressure_mpa: f.pressure_mpa,
            cycles: f.cycles,
            exponent: f.exponent,
            endurance_pressure_mpa: f.endurance_pressure_mpa,
        }),
        density_kg_per_m3: None,
    }
}

/// `modification.crowning` of the requirements' crowning: the same keys and values.
fn raw_crowning(c: &Crowning) -> Option<RawCrowning> {
    let kind = |kind: &str| RawCrowning {
        kind: kind.to_string(),
        ..RawCrowning::default()
    };
    match *c {
        Crowning::None => None,
        Crowning::Circular {
            radius_mm,
            start_mm,
        } => Some(RawCrowning {
            radius_mm: Some(radius_mm),
            start_mm: Some(start_mm),
            ..kind("circular")
        }),
        Crowning::Logarithmic {
            design_load_n,
            end_drop_mm,
            load_coefficient,
            crowned_fraction,
        } => Some(RawCrowning {
            design_load_n: Some(design_load_n),
            end_drop_mm: Some(end_drop_mm),
            load_coefficient: Some(load_coefficient),
            crowned_fraction: Some(crowned_fraction),
            ..kind("logarithmic")
        }),
    }
}

/// `reducer.friction` of the requirements' friction: the same keys and values.
fn raw_friction(f: &Friction) -> RawFriction {
    RawFriction {
        model: Some(f.model.name().to_string()),
        rollers: f.rollers.as_ref().map(|r| {
            let (mode, bore_radius_mm) = match r.mode {
                RollerMode::Fixed => ("fixed", None),
                RollerMode::Rotating { bore_radius_mm } => ("rotating", Some(bore_radius_mm)),
            };
            RawRollerFriction {
                mode: mode.to_string(),
                mu: r.mu,
                bore_radius_mm,
            }
        }),
        output_pins: f.output_pins.as_ref().map(|p| {
            let (mode, bore_radius_mm) = match p.mode {
                PinMode::Fixed => ("fixed", None),
                PinMode::Sleeve { bore_radius_mm } => ("sleeve", Some(bore_radius_mm)),
            };
            RawPinFriction {
                mode: mode.to_string(),
                mu: p.mu,
                bore_radius_mm,
            }
        }),
        crank_bearing: f.crank_bearing.as_ref().map(|b| RawBearingFriction {
            mu: b.mu,
            bore_diameter_mm: b.bore_diameter_mm,
        }),
        no_load_torque_nmm: Some(if f.no_load_torque_nmm.is_constant() {
            RawNoLoad::Constant(f.no_load_torque_nmm.max_nmm())
        } else {
            RawNoLoad::Table(f.no_load_torque_nmm.points().to_vec())
        }),
    }
}

/// The requirements' density, kg/m³, only when it is not the check's default (steel's), so
/// that the check's mass is the search's.
fn density_unless_steel(req: &Requirements) -> Option<f64> {
    let density = units::kg_per_m3(req.density_kg_per_mm3);
    ((density / STEEL_DENSITY_KG_PER_M3 - 1.0).abs() > 1e-12).then_some(density)
}
