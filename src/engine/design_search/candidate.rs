//! One point of the design space: its discrete choices and continuous values, the figures that
//! follow from its geometry alone (envelope, mass) and the spec that checks it.

use crate::geometry::disc_solid;
use crate::geometry::mass_properties::{face_moments, DiscMass, SECTION_TOLERANCE_MM};
use crate::geometry::profile::Profile;
use crate::model::requirements::{Continuous, Requirements};
use crate::model::{Crowning, Friction, OutputPins, PinMode, RollerMode};
use crate::spec::requirements::STEEL_DENSITY_KG_PER_M3;
use std::fmt::Write;

/// A discrete choice: the disc's teeth nc (the ratio), the output pins M and the discs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Choice {
    pub teeth: usize,
    pub pins: usize,
    pub discs: usize,
}

/// A design of the search: a choice and the eight continuous values, mm, in the order of
/// [`Continuous::KEYS`] (e, Rp, Rrp, B, rw, pin radius, ΔRp, ΔRrp).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    pub choice: Choice,
    pub x: [f64; 8],
}

/// Indices into `Candidate::x`.
pub const E: usize = 0;
pub const RP: usize = 1;
pub const RRP: usize = 2;
pub const B: usize = 3;
pub const RW: usize = 4;
pub const RPIN: usize = 5;
pub const SHIFT: usize = 6;
pub const EQUIDISTANT: usize = 7;

impl Candidate {
    /// The design at `u` (eight numbers in [0, 1]) of the requirements' ranges.
    pub fn at(choice: Choice, space: &Continuous, u: &[f64; 8]) -> Candidate {
        let ranges = space.ranges();
        let mut x = [0.0; 8];
        for k in 0..8 {
            x[k] = ranges[k].at(u[k]);
        }
        Candidate { choice, x }
    }

    /// np = nc + 1.
    pub fn rollers(&self) -> usize {
        self.choice.teeth + 1
    }

    /// Outer diameter, mm: 2·(Rp + Rrp + w), w the housing wall beyond the rollers.
    pub fn outer_diameter_mm(&self, req: &Requirements) -> f64 {
        2.0 * (self.x[RP] + self.x[RRP] + req.envelope.housing_wall_mm)
    }

    /// Axial length, mm: discs·B + the axial allowance (bearings, covers).
    pub fn axial_length_mm(&self, req: &Requirements) -> f64 {
        self.choice.discs as f64 * self.x[B] + req.envelope.axial_allowance_mm
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
        let rollers = self.rollers() as f64 * PI * x[RRP] * x[RRP];
        let pins = m * PI * x[RPIN] * x[RPIN];
        discs * self.disc_mass(req).mass_kg
            + req.density_kg_per_mm3 * x[B] * discs * (rollers + pins)
    }

    /// One disc's mass properties (`geometry::mass_properties`), as `check` computes them.
    fn disc_mass(&self, req: &Requirements) -> DiscMass {
        let x = &self.x;
        let profile = Profile::from_parts(
            self.rollers(),
            x[E],
            x[RP] + x[SHIFT],
            x[RRP] + x[EQUIDISTANT],
            0.0,
        );
        let pins = OutputPins {
            count: self.choice.pins,
            circle_radius_mm: x[RW],
            pin_radius_mm: x[RPIN],
            hole_clearance_mm: req.search.hole_clearance_mm,
            support: None,
        };
        let hole = x[RPIN] + x[E] + req.search.hole_clearance_mm;
        let holes = disc_solid::pin_holes(&pins, hole);
        let face = face_moments(&profile, &holes, None, SECTION_TOLERANCE_MM);
        DiscMass::new(face, x[B], req.density_kg_per_mm3)
    }

    /// Crank period of the loaded curves under the requirements' tilt, in mesh periods
    /// (`model::requirements::loaded_mesh_periods`).
    pub fn loaded_mesh_periods(&self, req: &Requirements) -> usize {
        crate::model::requirements::loaded_mesh_periods(
            self.choice.teeth,
            self.choice.pins,
            !req.misalignment.is_zero(),
        )
    }
}

/// A number as YAML that reads back as the same double (Rust's shortest round-trip form).
fn num(x: f64) -> String {
    format!("{x:?}")
}

/// A running scene's (rated, peak, duty) `misalignment` and `face_slices`, each when the
/// requirements give it (the torsion scene stays aligned: its face is uniform, one slice,
/// unless crowned).
fn face_text(s: &mut String, req: &Requirements) {
    let m = &req.misalignment;
    if !m.is_zero() {
        let _ = writeln!(
            s,
            "    misalignment: {{ about_x_mrad: {}, about_y_mrad: {} }}",
            num(1e3 * m.about_x_rad),
            num(1e3 * m.about_y_rad)
        );
    }
    if req.face_slices > 1 {
        let _ = writeln!(s, "    face_slices: {}", req.face_slices);
    }
}

/// `modification.crowning` of the requirements' crowning: the same keys and values (nothing
/// for `Crowning::None`).
fn crowning_text(s: &mut String, c: &Crowning) {
    let _ = match *c {
        Crowning::None => Ok(()),
        Crowning::Circular {
            radius_mm,
            start_mm,
        } => writeln!(
            s,
            "  crowning: {{ kind: circular, radius_mm: {}, start_mm: {} }}",
            num(radius_mm),
            num(start_mm)
        ),
        Crowning::Logarithmic {
            design_load_n,
            end_drop_mm,
            load_coefficient,
            crowned_fraction,
        } => writeln!(
            s,
            "  crowning: {{ kind: logarithmic, design_load_n: {}, end_drop_mm: {}, \
             load_coefficient: {}, crowned_fraction: {} }}",
            num(design_load_n),
            num(end_drop_mm),
            num(load_coefficient),
            num(crowned_fraction)
        ),
    };
}

/// `reducer.friction` of the requirements' friction: the same keys and values.
fn friction_text(s: &mut String, f: &Friction) {
    let _ = writeln!(s, "  friction:");
    let _ = writeln!(s, "    model: {}", f.model.name());
    if let Some(r) = &f.rollers {
        let _ = match r.mode {
            RollerMode::Fixed => writeln!(s, "    rollers: {{ mode: fixed, mu: {} }}", num(r.mu)),
            RollerMode::Rotating { bore_radius_mm } => writeln!(
                s,
                "    rollers: {{ mode: rotating, mu: {}, bore_radius_mm: {} }}",
                num(r.mu),
                num(bore_radius_mm)
            ),
        };
    }
    if let Some(p) = &f.output_pins {
        let _ = match p.mode {
            PinMode::Fixed => writeln!(s, "    output_pins: {{ mode: fixed, mu: {} }}", num(p.mu)),
            PinMode::Sleeve { bore_radius_mm } => writeln!(
                s,
                "    output_pins: {{ mode: sleeve, mu: {}, bore_radius_mm: {} }}",
                num(p.mu),
                num(bore_radius_mm)
            ),
        };
    }
    if let Some(b) = &f.crank_bearing {
        let _ = writeln!(
            s,
            "    crank_bearing: {{ mu: {}, bore_diameter_mm: {} }}",
            num(b.mu),
            num(b.bore_diameter_mm)
        );
    }
    let t0 = &f.no_load_torque_nmm;
    let t0 = if t0.is_constant() {
        num(t0.max_nmm())
    } else {
        let pairs: Vec<String> = (t0.points().iter())
            .map(|[n, t]| format!("[{}, {}]", num(*n), num(*t)))
            .collect();
        format!("[{}]", pairs.join(", "))
    };
    let _ = writeln!(s, "    no_load_torque_nmm: {t0}");
}

/// The spec of `c` under `req`: its reducer, the scenes the requirements need and their
/// limits; `steps` crank angles per mesh period (the screen runs a quarter of the full
/// check's, every fourth of its angles). `header` is written first as comments.
///
/// Scenes: `mesh` (unloaded, one mesh period: clearance and lost motion), `rated` (the rated
/// torque and speed over the loaded period: forces, pressure, TE, bearing life; with
/// `friction` the efficiency), `peak` (the peak torque, when above the rated: forces and
/// pressure; no bearing, whose life is the rated scene's), `duty` (the duty cycle's bins over
/// the loaded period, when one is given: its life and, with friction, its efficiency by
/// energy; every bin judged on the forces and pressure) and `torsion` (the catalogue loop at
/// the rated torque, when a rigidity, torsional lost motion or hysteresis is asked for).
pub fn spec_text(
    req: &Requirements,
    c: &Candidate,
    name: &str,
    steps: usize,
    header: &str,
) -> String {
    let x = &c.x;
    let np = c.rollers();
    let mesh_deg = 360.0 / np as f64;
    let periods = c.loaded_mesh_periods(req);
    let mut s = String::new();
    for line in header.lines() {
        let _ = writeln!(s, "# {line}");
    }
    let _ = writeln!(
        s,
        "name: {}",
        serde_json::to_string(name).unwrap_or_default()
    );
    let _ = writeln!(s, "reducer:");
    let _ = writeln!(s, "  teeth: {}", c.choice.teeth);
    let _ = writeln!(s, "  rollers: {np}");
    let _ = writeln!(s, "  eccentricity_mm: {}", num(x[E]));
    let _ = writeln!(s, "  roller_circle_radius_mm: {}", num(x[RP]));
    let _ = writeln!(s, "  roller_radius_mm: {}", num(x[RRP]));
    let _ = writeln!(s, "  face_width_mm: {}", num(x[B]));
    let _ = writeln!(s, "  discs: {}", c.choice.discs);
    let _ = writeln!(s, "  output_pins:");
    let _ = writeln!(s, "    count: {}", c.choice.pins);
    let _ = writeln!(s, "    circle_radius_mm: {}", num(x[RW]));
    let _ = writeln!(s, "    pin_radius_mm: {}", num(x[RPIN]));
    let _ = writeln!(
        s,
        "    hole_clearance_mm: {}",
        num(req.search.hole_clearance_mm)
    );
    let _ = writeln!(s, "  material:");
    let _ = writeln!(
        s,
        "    youngs_modulus_gpa: {}",
        num(crate::units::gpa(req.material.youngs_modulus_mpa))
    );
    let _ = writeln!(s, "    poisson_ratio: {}", num(req.material.poisson_ratio));
    // The density only when it is not the check's default, so the check's mass is the search's.
    let density = crate::units::kg_per_m3(req.density_kg_per_mm3);
    if (density / STEEL_DENSITY_KG_PER_M3 - 1.0).abs() > 1e-12 {
        let _ = writeln!(s, "    density_kg_per_m3: {}", num(density));
    }
    if let Some(b) = &req.crank_bearing {
        let _ = writeln!(s, "  crank_bearing:");
        let _ = writeln!(
            s,
            "    dynamic_load_rating_n: {}",
            num(b.dynamic_load_rating_n)
        );
        let _ = writeln!(s, "    life_exponent: {}", num(b.life_exponent));
    }
    if let Some(f) = &req.friction {
        friction_text(&mut s, f);
    }
    if let Some(t) = &req.thermal {
        let _ = writeln!(
            s,
            "  thermal: {{ housing_area_m2: {}, heat_transfer_w_per_m2k: {}, ambient_c: {} }}",
            num(t.housing_area_m2),
            num(t.heat_transfer_w_per_m2k),
            num(t.ambient_c)
        );
    }
    let _ = writeln!(s, "modification:");
    let _ = writeln!(s, "  shift_mm: {}", num(x[SHIFT]));
    let _ = writeln!(s, "  equidistant_mm: {}", num(x[EQUIDISTANT]));
    crowning_text(&mut s, &req.crowning);
    let _ = writeln!(s, "scenes:");
    let _ = writeln!(s, "  - name: mesh");
    let _ = writeln!(
        s,
        "    crank: {{ from_deg: 0.0, to_deg: {}, steps: {steps} }}",
        num(mesh_deg)
    );
    let _ = writeln!(s, "    effects: [clearance]");
    let loaded = format!(
        "    crank: {{ from_deg: 0.0, to_deg: {}, steps: {} }}",
        num(mesh_deg * periods as f64),
        steps * periods
    );
    let _ = writeln!(s, "  - name: rated");
    let _ = writeln!(
        s,
        "    output_torque_nm: {}",
        num(crate::units::nm(req.rated_torque_nmm))
    );
    if let Some(n) = req.input_speed_rpm {
        let _ = writeln!(s, "    input_speed_rpm: {}", num(n));
    }
    let _ = writeln!(s, "{loaded}");
    face_text(&mut s, req);
    let running = match req.friction {
        Some(_) => "    effects: [bearing, efficiency]",
        None => "    effects: [bearing]",
    };
    let _ = writeln!(s, "{running}");
    if req.peak_torque_nmm > req.rated_torque_nmm {
        let _ = writeln!(s, "  - name: peak");
        let _ = writeln!(
            s,
            "    output_torque_nm: {}",
            num(crate::units::nm(req.peak_torque_nmm))
        );
        let _ = writeln!(s, "{loaded}");
        face_text(&mut s, req);
        let _ = writeln!(s, "    effects: [roller_contact, output_pins]");
    }
    if let Some(bins) = &req.duty_cycle {
        let _ = writeln!(s, "  - name: duty");
        let _ = writeln!(s, "    duty_cycle:");
        for b in bins {
            let _ = writeln!(
                s,
                "      - {{ output_torque_nm: {}, input_speed_rpm: {}, time_share: {} }}",
                num(crate::units::nm(b.output_torque_nmm)),
                num(b.input_speed_rpm),
                num(b.time_share)
            );
        }
        let _ = writeln!(s, "{loaded}");
        face_text(&mut s, req);
        let _ = writeln!(s, "{running}");
    }
    if req.needs_torsion() {
        let _ = writeln!(s, "  - name: torsion");
        let _ = writeln!(
            s,
            "    torque_sweep: {{ rated_nm: {}, steps: 8 }}",
            num(crate::units::nm(req.rated_torque_nmm))
        );
        let _ = writeln!(
            s,
            "    crank: {{ from_deg: 0.0, to_deg: {}, steps: 4 }}",
            num(mesh_deg)
        );
        // A crowned face is uneven even untilted: the loop cuts it into the requirements'
        // slices (the spec's rule for every scene that loads a crowned face).
        if req.crowning != Crowning::None {
            let _ = writeln!(s, "    face_slices: {}", req.face_slices);
        }
        let _ = writeln!(s, "    effects: [output_pins]");
    }
    if !req.limits.entries.is_empty() {
        let _ = writeln!(s, "limits:");
        for l in &req.limits.entries {
            let _ = writeln!(s, "  {}: {}", l.def.key, num(l.value));
        }
    }
    s
}
