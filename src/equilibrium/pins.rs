//! Output pins in the disc's holes at one pose.
//!
//! Pin j's centre Q = rw·e^{i(γj + βo)}, its hole's centre H = O_c + rw·e^{iγj},
//! γj = 2πj/M + ψ (fixed frame; ψ the disc rotation, βo the lag of the output behind the disc).
//! With d = Q − H and hole radius R_h = r_pin + e + c, the gap is e + c − |d| (ideal geometry:
//! d = −e·(cos φ, sin φ), gap = c). The pin pushes the hole wall along û = d/|d|; its moment
//! about the disc centre has arm a = rw·e^{iγj} × û (rw·sin(γj − φ) when ideal), positive arms
//! carry a positive output torque. Exact derivatives: ∂gap/∂βo = −(Q − O) × û and ∂gap/∂u = û.

use super::balance::impl_contact;
use super::pin_beam::{series_force, series_linear_stiffness, PinBeam};
use crate::contact::law::{ContactForce, LineContact};
use crate::geometry::{cross, rotate, sin_cos, unit, Vec2};
use crate::model::{ContactLaw, Design};

/// One pin's contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinState {
    pub gap_mm: f64,
    pub force_n: f64,
    pub stiffness_n_per_mm: f64,
    /// Moment arm about the disc centre, mm.
    pub arm_mm: f64,
    /// Direction of the pin's force on the disc (unit, fixed frame).
    pub direction: Vec2,
    /// Contact point on the hole wall, fixed frame, mm.
    pub point: Vec2,
    /// ∂gap/∂βo, mm/rad.
    pub gap_slope_mm: f64,
}

impl PinState {
    pub fn force_vector(&self) -> Vec2 {
        self.force_n * self.direction
    }
}

#[derive(Debug, Clone)]
pub struct Pins {
    pub count: usize,
    /// Unit vectors at 2πj/M.
    pub(super) base: Vec<Vec2>,
    pub(super) circle_radius_mm: f64,
    pub(super) eccentricity_mm: f64,
    pub(super) clearance_mm: f64,
    pub(super) hole_radius_mm: f64,
    contact: LineContact,
    law: ContactLaw,
    /// Bound on the round-off of a pin gap, mm: 16·ε·(c + e + rw), a few ulp of the largest
    /// length it is formed from.
    gap_resolution_mm: f64,
    /// de: the crank's eccentricity minus the design's, mm (the disc centre orbits at e + de;
    /// the holes were bored for e).
    eccentricity_deviation_mm: f64,
    /// Pin j's centre displacement on the flange, in the frame where pin j sits at 2πj/M, mm.
    pin_offsets: Vec<Vec2>,
    /// `hole_offsets[k][j]`: hole j of disc k, in the disc's frame, mm.
    hole_offsets: Vec<Vec<Vec2>>,
    /// (pin, hole) displacements of the disc this model solves, turned with `base`; empty when
    /// its pins and holes are nominal.
    parts: Vec<(Vec2, Vec2)>,
    /// The pins as beams (`reducer.output_pins.support`); none: rigid pins.
    beam: Option<PinBeam>,
    /// c_kk, the pin's bending compliance at this disc's mid-plane, mm/N, in series with the
    /// contact (0: rigid pins).
    beam_compliance_mm_per_n: f64,
    /// The gap that the other discs' pin forces open at this disc's plane, pin by pin, mm:
    /// Σ_{k≠j} c_jk·F_k·(û_j·û_k) (`pin_beam`); empty with one disc or rigid pins.
    beam_gaps_mm: Vec<f64>,
}

/// Unit vectors of the pins' nominal places, (cos 2πj/M, sin 2πj/M).
fn pattern(m: usize) -> Vec<Vec2> {
    (0..m)
        .map(|j| {
            let a = std::f64::consts::TAU * j as f64 / m as f64;
            unit(a)
        })
        .collect()
}

impl Pins {
    pub fn new(design: &Design, law: ContactLaw) -> Self {
        let pin = design.pins.pin_radius_mm;
        let hole = design.hole_radius_mm();
        let m = design.pins.count;
        let base = pattern(m);
        let d = &design.deviations;
        let rw = design.pins.circle_radius_mm;
        let moved = |c: crate::model::CentreDeviation, j: usize| {
            let (x, y) = c.displacement_mm(rw, (base[j].x, base[j].y));
            Vec2::new(x, y)
        };
        let (pin_offsets, hole_offsets) = if d.moves_pins() {
            (
                (0..m).map(|j| moved(d.pin(j), j)).collect(),
                (0..design.discs)
                    .map(|k| (0..m).map(|j| moved(d.hole(k, j), j)).collect())
                    .collect(),
            )
        } else {
            (Vec::new(), Vec::new())
        };
        let pins = Pins {
            count: m,
            base: Vec::new(),
            circle_radius_mm: design.pins.circle_radius_mm,
            eccentricity_mm: design.eccentricity_mm,
            clearance_mm: design.pins.hole_clearance_mm,
            hole_radius_mm: hole,
            contact: LineContact {
                radii_mm: [hole, pin],
                effective_radius_mm: 1.0 / (1.0 / pin - 1.0 / hole),
                ..super::rollers::Rollers::materials(design)
            },
            law,
            gap_resolution_mm: 16.0
                * f64::EPSILON
                * (design.pins.hole_clearance_mm
                    + design.eccentricity_mm
                    + design.pins.circle_radius_mm),
            eccentricity_deviation_mm: d.eccentricity_mm,
            pin_offsets,
            hole_offsets,
            parts: Vec::new(),
            beam: PinBeam::of(design),
            beam_compliance_mm_per_n: 0.0,
            beam_gaps_mm: Vec::new(),
        };
        pins.for_disc(0, 0.0)
    }

    /// The pins as disc k of several sees them (MODEL.md "Several discs"): disc k runs at the
    /// crank phase φ + 2πk/N, so its ideal rotation is 2πk/(N·nc) behind the output flange's,
    /// and its holes are bored that much ahead so that the pins sit centred at the ideal pose:
    /// in the disc's own solve the pin pattern is turned by `phase_rad` = 2πk/(N·nc). The
    /// pins as built, and disc k's holes, turn with it.
    pub fn for_disc(mut self, disc: usize, phase_rad: f64) -> Self {
        let (s, c) = phase_rad.sin_cos();
        let turn = |v: &Vec2| rotate(*v, c, s);
        self.base = pattern(self.count).iter().map(turn).collect();
        if let Some(beam) = &self.beam {
            self.beam_compliance_mm_per_n = beam.own_compliance_mm_per_n(disc);
            self.beam_gaps_mm = if beam.couples() {
                vec![0.0; self.count]
            } else {
                Vec::new()
            };
        }
        self.parts = match self.hole_offsets.get(disc) {
            Some(holes) => self
                .pin_offsets
                .iter()
                .zip(holes)
                .map(|(p, h)| (turn(p), turn(h)))
                .collect(),
            None => Vec::new(),
        };
        self
    }

    /// Bound on the round-off of Σ F·a at a pose whose centre is offset by `offset_mm`:
    /// each contact's force moves by its stiffness times the gap's round-off.
    pub fn moment_resolution(&self, states: &[PinState], offset_mm: f64) -> f64 {
        let gap = self.gap_resolution_mm + 16.0 * f64::EPSILON * offset_mm;
        gap * states
            .iter()
            .map(|s| s.stiffness_n_per_mm * s.arm_mm.abs())
            .sum::<f64>()
    }

    pub fn line_contact(&self) -> &LineContact {
        &self.contact
    }

    /// The pins as beams, when they bend.
    pub fn beam(&self) -> Option<&PinBeam> {
        self.beam.as_ref()
    }

    /// Whether the pins' bending couples this disc to others (`discs::solve_coupled` then
    /// iterates the gaps the other discs open, `set_beam_gaps`).
    pub fn couples_discs(&self) -> bool {
        !self.beam_gaps_mm.is_empty()
    }

    /// The gaps (mm, pin by pin) that the other discs' forces open at this disc's plane.
    pub fn beam_gaps_mm(&self) -> &[f64] {
        &self.beam_gaps_mm
    }

    /// Set the gaps the other discs' forces open, pin by pin, mm (`pin_beam`).
    pub fn set_beam_gaps(&mut self, gaps_mm: &[f64]) {
        self.beam_gaps_mm.copy_from_slice(gaps_mm);
    }

    /// The extra gap of pin j from the other discs' forces, mm (0 without coupling).
    fn beam_gap(&self, j: usize) -> f64 {
        self.beam_gaps_mm.get(j).copied().unwrap_or(0.0)
    }

    /// Evaluate every pin with the disc centre at e·e_φ + `offset`, from the eccentric
    /// direction e_φ = (cos φ, sin φ) and (sin, cos) of the disc rotation ψ, computed once per
    /// crank angle by the caller; `output_lag` is βo.
    ///
    /// The approach of a pin is tiny (~1e-7 mm at small torques) next to the pin and hole
    /// positions (~rw from the origin), so the gap is never formed by subtracting those nearly
    /// equal vectors, whose rounding (a few ulp of rw, ~1e-14 mm) would swamp the balance.
    /// With w = Q − rw·e^{iγ} = rw·e^{iγ}·(e^{iβo} − 1) and O the disc centre, d = w − O and
    ///   e + c − |d| = c − (|d|² − e²)/(|d| + e),  |d|² − e² = 2e·ê·u + |u|² − 2·O·w + |w|²,
    /// every term of which is formed from small quantities.
    pub fn evaluate_at(
        &self,
        ecc: Vec2,
        (s, c): (f64, f64),
        offset: Vec2,
        output_lag: f64,
        out: &mut Vec<PinState>,
    ) {
        out.clear();
        let e = self.eccentricity_mm;
        // The crank's deviation de moves the disc centre off the orbit the holes were bored for,
        // as a bearing offset does.
        let offset = offset + ecc * self.eccentricity_deviation_mm;
        let disc_centre = ecc * e + offset;
        // e^{iβo} − 1 = (−2·sin²(βo/2), sin βo), without cancellation.
        let half = sin_cos(0.5 * output_lag).0;
        let turn = Vec2::new(-2.0 * half * half, sin_cos(output_lag).0);
        let centre_sq = 2.0 * e * ecc.dot(&offset) + offset.norm_squared();
        for (j, unit) in self.base.iter().enumerate() {
            let (cg, sg) = (c * unit.x - s * unit.y, s * unit.x + c * unit.y);
            let mut arm_vec = Vec2::new(cg, sg) * self.circle_radius_mm;
            let mut w = rotate(turn, cg, sg) * self.circle_radius_mm;
            let mut pin = arm_vec + w;
            if let Some(&(pin_d, hole_d)) = self.parts.get(j) {
                // As built: the hole turns with the disc (ψ), the pin with the flange (ψ + βo);
                // w is then the pin centre less the hole centre, both taken from the nominal
                // hole centre, and the moment arm is that of the hole centre as built.
                let hole = rotate(hole_d, c, s);
                let pin_moved = rotate(rotate(pin_d, c, s), 1.0 + turn.x, turn.y);
                w += pin_moved - hole;
                pin += pin_moved;
                arm_vec += hole;
            }
            let d = w - disc_centre;
            let dist = d.norm();
            let u = d / dist;
            let excess = centre_sq - 2.0 * disc_centre.dot(&w) + w.norm_squared();
            let gap_mm = self.clearance_mm - excess / (dist + e) + self.beam_gap(j);
            out.push(self.state(
                gap_mm,
                cross(arm_vec, u),
                u,
                disc_centre + arm_vec,
                -cross(pin, u),
            ));
        }
    }

    /// First-order pins: gap c − βo·a_j − e_φ·u with a_j = rw·sin(γj − φ), force along −e_φ
    /// (ideal pin-in-hole directions; MODEL.md "Equilibrium"), from the eccentric direction e_φ,
    /// (sin, cos) of the disc rotation ψ and the disc centre (u its offset from e·e_φ).
    pub fn first_order_at(
        &self,
        e_phi: Vec2,
        (s, c): (f64, f64),
        disc_centre: Vec2,
        output_lag: f64,
        out: &mut Vec<PinState>,
    ) {
        out.clear();
        let u = -e_phi;
        let offset = disc_centre - e_phi * self.eccentricity_mm;
        for (j, w) in self.base.iter().enumerate() {
            let arm_vec = rotate(*w, c, s) * self.circle_radius_mm;
            let arm = cross(arm_vec, u);
            let gap_mm =
                self.clearance_mm - output_lag * arm - e_phi.dot(&offset) + self.beam_gap(j);
            out.push(self.state(gap_mm, arm, u, disc_centre + arm_vec, -arm));
        }
    }

    /// Move first-order pin states evaluated at lag 0 to `output_lag` (gaps are linear in it).
    pub fn first_order_lagged(&self, output_lag: f64, states: &mut [PinState]) {
        for st in states.iter_mut() {
            let gap_mm = st.gap_mm - output_lag * st.arm_mm;
            let hole = st.point - self.hole_radius_mm * st.direction;
            *st = self.state(gap_mm, st.arm_mm, st.direction, hole, st.gap_slope_mm);
        }
    }

    fn state(
        &self,
        gap_mm: f64,
        arm_mm: f64,
        direction: Vec2,
        hole: Vec2,
        gap_slope_mm: f64,
    ) -> PinState {
        // With bending pins `gap_mm` is the gap of the undeflected pin: its closing is shared
        // by the contact's approach and the pin's own bending, in series.
        let c = self.beam_compliance_mm_per_n;
        // The output flange tilts with the disc (README "Along the face width"): a pin sees no
        // tilt against its hole, and its contact stays 2-D whatever the scene's tilt.
        let cf = if gap_mm < 0.0 {
            series_force(self.law, &self.contact, c, -gap_mm)
        } else {
            ContactForce::NONE
        };
        PinState {
            gap_mm,
            force_n: cf.force_n,
            stiffness_n_per_mm: cf.stiffness_n_per_mm,
            arm_mm,
            direction,
            point: hole + self.hole_radius_mm * direction,
            gap_slope_mm,
        }
    }

    /// Linear-law stiffness, N/mm, when the law is linear; with bending pins the
    /// contact's and the pin's in series, 1/(1/k + c_kk) (`pin_beam::series_linear_stiffness`,
    /// the stiffness `series_force` applies).
    pub fn linear_stiffness(&self) -> Option<f64> {
        (self.law == ContactLaw::PaperLinear)
            .then(|| series_linear_stiffness(&self.contact, self.beam_compliance_mm_per_n))
    }
}

impl_contact!(PinState, |s| s.gap_slope_mm);
