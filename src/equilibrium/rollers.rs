//! The roller set at one disc pose: gap, force, stiffness and moment arm of every roller.
//!
//! Vectors in the fixed frame. A roller's force on the disc is −F·n (n the outward normal of
//! the disc at the contact); its moment about the disc centre is −F·l (MODEL.md sign: l > 0
//! rollers drive the disc clockwise and close as the lag β grows, ∂gap/∂β = −l, and a
//! displacement u of the disc centre changes the gap by −n·u).
//!
//! Speed: the pose's trigonometry is done once per evaluation, roller centres are precomputed,
//! the closest-point search is warm-started from the roller's last contact parameter, and a
//! roller that provably cannot touch (`Reach`) is not evaluated at all.

use super::balance::impl_contact;
use crate::contact::face_width::FaceWidth;
use crate::contact::hertz_line::{hertz, HertzLine};
use crate::contact::law::{self, ContactForce, LineContact};
use crate::geometry::clearance::{GapFailure, Mesh, Pose};
use crate::geometry::first_order;
use crate::geometry::profile::LocusFrame;
use crate::geometry::{cross, rotate, sin_cos, unit, wrap_pi, Vec2};
use crate::model::{ContactLaw, Design, Face, GeometryMode, Modification};

/// One roller's contact at one pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerState {
    /// Normal gap, mm; for a roller skipped as out of reach, a positive lower bound of it.
    pub gap_mm: f64,
    pub force_n: f64,
    pub stiffness_n_per_mm: f64,
    pub arm_mm: f64,
    /// Outward disc normal at the contact, fixed frame.
    pub normal: Vec2,
    /// Contact point, fixed frame, mm.
    pub point: Vec2,
    /// Locus parameter of the contact (warm start for the next evaluation).
    pub t: f64,
}

impl RollerState {
    /// Force of this roller on the disc, fixed frame, N.
    pub fn force_vector(&self) -> Vec2 {
        -self.force_n * self.normal
    }
}

/// Where a roller was last evaluated exactly, to bound how far its gap can have moved since:
/// the roller centre, seen from the disc, moves by at most |P|·(|Δφ|/nc + |Δβ|) + e·|Δφ| + |Δu|
/// (first order) plus `curvature_bound`·(Δφ² + Δβ²), and the gap moves no more than it does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    pub pose: Pose,
    pub gap_mm: f64,
}

impl Reach {
    /// `reaches` for `count` rollers: as they are when there are that many, else each
    /// roller's reach unknown (no gap yet) at `pose`.
    pub fn size(reaches: &mut Vec<Reach>, count: usize, pose: Pose) {
        if reaches.len() != count {
            let unknown = Reach {
                pose,
                gap_mm: f64::NEG_INFINITY,
            };
            *reaches = vec![unknown; count];
        }
    }
}

/// Trigonometry of one crank angle, shared by every evaluation at that angle: the eccentric
/// direction e_φ and the ideal disc rotation −φ/nc. A lag β then costs only a small rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleTrig {
    pub crank_rad: f64,
    pub e_phi: Vec2,
    /// (sin, cos) of −φ/nc.
    pub ideal: (f64, f64),
    /// e^{i·np·φ/nc}: the lobe factor of every roller's locus point at this angle.
    pub lobe: Vec2,
}

impl AngleTrig {
    pub fn new(crank_rad: f64, teeth: usize) -> Self {
        let turn = crank_rad / teeth as f64;
        let lobe = (teeth + 1) as f64 * turn;
        AngleTrig {
            crank_rad,
            e_phi: unit(crank_rad),
            ideal: (-turn).sin_cos(),
            lobe: unit(lobe),
        }
    }

    /// (sin, cos) of ψ = −φ/nc + β.
    pub fn rotation(&self, lag_rad: f64) -> (f64, f64) {
        let (sb, cb) = sin_cos(lag_rad);
        let (s0, c0) = self.ideal;
        (s0 * cb + c0 * sb, c0 * cb - s0 * sb)
    }
}

/// The rollers of one design under one contact law and geometry mode.
#[derive(Debug, Clone)]
pub struct Rollers {
    pub mesh: Mesh,
    pub(super) design: Design,
    pub law: ContactLaw,
    pub geometry: GeometryMode,
    /// Roller centres, fixed frame.
    pub(super) centres: Vec<Vec2>,
    /// Unit vectors of the roller centres, u_i = (cos 2πi/np, sin 2πi/np).
    pub(super) units: Vec<Vec2>,
    /// Contact modulus, compliances and length of the roller contacts.
    pub(super) materials: LineContact,
    /// Constants of the first-order gaps and arms.
    pub(super) first_order: first_order::Coefficients,
    /// Largest distance of a roller centre from the disc centre, mm.
    reach_radius_mm: f64,
    /// Bound on the second derivative of a gap w.r.t. crank and lag, mm/rad².
    curvature_bound: f64,
    /// Linear-law stiffness (π/4)·E*·L, N/mm.
    linear_stiffness: f64,
    /// A foot closer to the locus than this is the nearest point of Γ (`Tracker::certified_mm`
    /// of the clearance sweep: 0.9 of the locus's reach, and of r'); a foot farther may be a
    /// local nearest point on a flank the roller has left.
    certified_mm: f64,
    /// Bound on the round-off of an exact gap at zero centre offset, mm: a gap is a sum of
    /// terms no larger than the positions it is measured between (Rp, e) and the
    /// modifications, so it is resolved to a few ulp of their sum, 16·ε·(Rp + e + |ΔRp| + |ΔRrp|).
    gap_resolution_mm: f64,
    /// The contact along the face width when it is not uniform (a crown or a tilt,
    /// `with_face`); `None`: the 2-D contact of length B.
    face: Option<FaceWidth>,
    /// Slices the line load is reported at (`Face::slices`).
    slices: usize,
}

impl Rollers {
    pub fn new(design: &Design, m: &Modification, law: ContactLaw, geometry: GeometryMode) -> Self {
        let mesh = Mesh::new(design, m);
        let centres: Vec<Vec2> = (0..design.rollers).map(|i| mesh.roller_centre(i)).collect();
        let units = (0..design.rollers).map(|i| mesh.roller_unit(i)).collect();
        // The parts as built move a roller centre, or the disc centre's orbit, by micrometres.
        let reach = design.roller_circle_radius_mm
            + mesh.largest_roller_offset_mm()
            + design.eccentricity_mm
            + mesh.eccentricity_deviation_mm.abs();
        // |∂²gap/∂β²| ≤ |P| + |P|²/ρ, ρ the smallest convex radius of Γ (the distance field's
        // Hessian is bounded by 1/ρ), doubled for safety and for the crank terms.
        // A form error bends the flank by up to |w''|/|C'|², |C'| ≥ R' − e·np.
        let slowest = (mesh.profile.locus_radius_mm
            - mesh.profile.eccentricity_mm * design.rollers as f64)
            .max(1e-6);
        let ripple = mesh.profile.form().bend_bound() / (slowest * slowest);
        let mut convex =
            mesh.profile.locus().min_convex_radius().radius_mm - mesh.profile.offset_mm;
        if ripple > 0.0 {
            convex = 1.0 / (1.0 / convex.max(1e-6) + ripple);
        }
        let curvature_bound = 2.0 * (reach + reach * reach / convex.max(1e-6));
        let mut r = Rollers {
            mesh,
            design: design.clone(),
            law,
            geometry,
            centres,
            units,
            first_order: first_order::Coefficients::new(design, m),
            materials: Self::materials(design),
            reach_radius_mm: reach,
            curvature_bound,
            certified_mm: 0.0,
            linear_stiffness: 0.0,
            gap_resolution_mm: 16.0
                * f64::EPSILON
                * (reach + m.shift_mm.abs() + m.equidistant_mm.abs()),
            face: None,
            slices: 1,
        };
        r.linear_stiffness = law::paper_linear_stiffness(&r.line_contact(0.0));
        r.certified_mm = crate::geometry::clearance::certified_mm(&r.mesh.profile);
        r
    }

    pub fn count(&self) -> usize {
        self.design.rollers
    }

    /// These rollers with their contacts along the face `face` (MODEL.md "Along the face
    /// width"): each roller's force the sum over the face of the contact law per unit length
    /// (`contact::face_width`). A uniform face (no crown, no tilt) keeps the 2-D contact, bit
    /// for bit, whatever its slices.
    pub fn with_face(mut self, face: &Face) -> Self {
        self.slices = face.slices.max(1);
        self.face = (!face.is_uniform()).then(|| {
            FaceWidth::new(
                face,
                self.design.face_width_mm,
                self.materials.contact_modulus_mpa,
            )
        });
        self
    }

    /// These rollers with the face summed over its slices even where the closed form holds
    /// (`FaceWidth::by_slices`): the Winkler reference of the closed form, for tests and
    /// benchmarks.
    pub fn with_face_by_slices(self, face: &Face) -> Self {
        let mut r = self.with_face(face);
        r.face = r.face.map(FaceWidth::by_slices);
        r
    }

    /// The gap of roller state `s` to its first touch, mm: its 2-D gap (at the middle of the
    /// face) less what a tilt or crown closes beyond it (`FaceWidth::closing_mm`); the 2-D gap
    /// on a uniform face. Zero where the roller starts to carry force.
    pub fn touch_gap_mm(&self, s: &RollerState) -> f64 {
        match &self.face {
            None => s.gap_mm,
            Some(face) => {
                let t = face.approach_slope((-s.normal.x, -s.normal.y));
                s.gap_mm - face.closing_mm(self.law, t)
            }
        }
    }

    /// The face along which the contacts vary, when it is not uniform.
    pub fn face(&self) -> Option<&FaceWidth> {
        self.face.as_ref()
    }

    /// The face width B, mm.
    pub fn face_width_mm(&self) -> f64 {
        self.design.face_width_mm
    }

    /// Slices the line load is reported at.
    pub fn slices(&self) -> usize {
        self.slices
    }

    /// The linear law's stiffness k = (π/4)·E*·L, N/mm.
    pub fn linear_stiffness(&self) -> f64 {
        self.linear_stiffness
    }

    /// Bound on the round-off of Σ F·l at a pose whose centre is offset by `offset_mm` from
    /// e·(cos φ, sin φ): each contact's force moves by its stiffness times the gap's round-off.
    pub fn moment_resolution(&self, states: &[RollerState], offset_mm: f64) -> f64 {
        let gap = self.gap_resolution_mm + 16.0 * f64::EPSILON * offset_mm;
        gap * states
            .iter()
            .map(|s| s.stiffness_n_per_mm * s.arm_mm.abs())
            .sum::<f64>()
    }

    /// Contact description for the laws: disc flank of signed curvature κ against a roller.
    /// A flat or nearly flat flank's radius is capped at Rp (the disc's own size), where the
    /// 2-D logarithmic displacement field of the log law is cut off.
    pub fn line_contact(&self, curvature_per_mm: f64) -> LineContact {
        let d = &self.design;
        let rrp = d.roller_radius_mm;
        let flank = (1.0 / curvature_per_mm.abs()).min(d.roller_circle_radius_mm);
        LineContact {
            radii_mm: [flank, rrp],
            effective_radius_mm: 1.0 / self.inverse_effective_radius(curvature_per_mm),
            ..self.materials
        }
    }

    /// 1/R* = max(κ + 1/r_rp, 1/Rp) of a roller contact where the disc's curvature is κ
    /// (1/mm, convex positive): floored at the roller circle's curvature, the flattest the
    /// flank is modelled (`line_contact`).
    #[inline(always)]
    pub fn inverse_effective_radius(&self, curvature_per_mm: f64) -> f64 {
        let d = &self.design;
        (curvature_per_mm + 1.0 / d.roller_radius_mm).max(1.0 / d.roller_circle_radius_mm)
    }

    /// The materials and length of every roller and output-pin contact (the rollers' material
    /// is the pins'; radii left to `line_contact` and the pins' hole).
    pub(super) fn materials(d: &Design) -> LineContact {
        LineContact {
            contact_modulus_mpa: d.contact_modulus_mpa(),
            compliance_per_mpa: [
                d.disc_material.compliance_per_mpa(),
                d.roller_material.compliance_per_mpa(),
            ],
            length_mm: d.face_width_mm,
            radii_mm: [f64::NAN; 2],
            effective_radius_mm: f64::NAN,
        }
    }

    /// Signed curvature of the disc profile at a roller's contact, 1/mm (positive convex).
    pub fn curvature(&self, s: &RollerState) -> f64 {
        self.mesh.profile.curvature(s.t)
    }

    /// Hertz pressure and half-width of a roller state over the whole face (p0 = sqrt(F·E*/
    /// (π·L·R*)), b = sqrt(4·F·R*/(π·L·E*))): the 2-D model's, a uniform face's. A face that is
    /// not uniform takes the peak slice's from `hertz_and_line_loads`, the one the sweep calls.
    pub fn hertz(&self, s: &RollerState) -> HertzLine {
        hertz(&self.line_contact(self.curvature(s)), s.force_n)
    }

    /// The line load (N/mm) of roller state `s` in each slice, its force/(B/n), into `out`
    /// (`slices` entries; `FaceWidth::line_loads`): F/B on a uniform face; 0 out of contact;
    /// with its Hertz pressure and half-width and the peak line load (N/mm): on a face that is
    /// not uniform, those of the peak slice's line load q, returned with the line loads rather
    /// than computed again (Hertz per unit length: p0 = sqrt(q·E*/(π·R*)),
    /// b = sqrt(4·q·R*/(π·E*))); else `hertz`.
    pub fn hertz_and_line_loads(&self, s: &RollerState, out: &mut [f64]) -> (HertzLine, f64) {
        match &self.face {
            _ if s.force_n <= 0.0 => out.fill(0.0),
            None => out.fill(s.force_n / self.design.face_width_mm),
            Some(face) => {
                let c = self.line_contact(self.curvature(s));
                let t = face.approach_slope((-s.normal.x, -s.normal.y));
                let peak = face.line_loads(self.law, &c, -s.gap_mm, t, out);
                let unit = LineContact {
                    length_mm: 1.0,
                    ..c
                };
                return (hertz(&unit, peak), peak);
            }
        }
        (self.hertz(s), out.iter().copied().fold(0.0, f64::max))
    }

    /// The force of a roller at `gap_mm` whose contact is at locus parameter `t` with outward
    /// disc normal `normal` (fixed frame: the tilt's slope along the face, t = n·(θy, −θx)).
    fn contact_force(&self, gap_mm: f64, t: f64, normal: Vec2) -> ContactForce {
        if let Some(face) = &self.face {
            let c = match self.law {
                // The linear law reads E* and the length alone.
                ContactLaw::PaperLinear => self.materials,
                ContactLaw::HertzNonlinear => self.line_contact(self.mesh.profile.curvature(t)),
            };
            let slope = face.approach_slope((-normal.x, -normal.y));
            return face.force(self.law, &c, -gap_mm, slope);
        }
        if gap_mm >= 0.0 {
            return ContactForce::NONE;
        }
        match self.law {
            ContactLaw::PaperLinear => ContactForce::linear(self.linear_stiffness, -gap_mm),
            ContactLaw::HertzNonlinear => {
                let c = self.line_contact(self.mesh.profile.curvature(t));
                law::force(self.law, &c, -gap_mm)
            }
        }
    }

    /// A lower bound on roller i's gap at `pose`, from where it was last evaluated.
    fn gap_lower_bound(&self, reach: &Reach, pose: &Pose) -> f64 {
        let dphi = (pose.crank_rad - reach.pose.crank_rad).abs();
        let dlag = (pose.lag_rad - reach.pose.lag_rad).abs();
        let du = (pose.centre_offset_mm - reach.pose.centre_offset_mm).norm();
        let nc = self.design.teeth as f64;
        let orbit = self.design.eccentricity_mm + self.mesh.eccentricity_deviation_mm.abs();
        let first = self.reach_radius_mm * (dphi / nc + dlag) + orbit * dphi + du;
        reach.gap_mm - first - self.curvature_bound * (dphi * dphi + dlag * dlag)
    }

    /// Evaluate every roller at `pose`. `states` holds the previous evaluation (its `t` is the
    /// warm start) or is empty.
    pub fn evaluate(&self, pose: &Pose, states: &mut Vec<RollerState>) -> Result<(), GapFailure> {
        let trig = AngleTrig::new(pose.crank_rad, self.design.teeth);
        self.evaluate_at(pose, &trig, states, &mut [])
    }

    /// Evaluate at `pose`, with the angle's trigonometry computed once by the caller, skipping
    /// rollers whose `reaches` entry proves a positive gap (they get zero force and the bound as
    /// gap). With an empty `reaches` every roller is evaluated; otherwise an evaluated roller's
    /// entry is updated.
    pub fn evaluate_at(
        &self,
        pose: &Pose,
        trig: &AngleTrig,
        states: &mut Vec<RollerState>,
        reaches: &mut [Reach],
    ) -> Result<(), GapFailure> {
        let n = self.count();
        if states.len() != n {
            states.clear();
            states.resize(
                n,
                RollerState {
                    gap_mm: 0.0,
                    force_n: 0.0,
                    stiffness_n_per_mm: 0.0,
                    arm_mm: 0.0,
                    normal: Vec2::zeros(),
                    point: Vec2::zeros(),
                    t: f64::NAN,
                },
            );
            for (i, s) in states.iter_mut().enumerate() {
                s.t = self.mesh.foot_guess(i, pose);
            }
        }
        let (s, c) = trig.rotation(pose.lag_rad);
        let orbit = self.design.eccentricity_mm + self.mesh.eccentricity_deviation_mm;
        let centre = trig.e_phi * orbit + pose.centre_offset_mm;
        for (i, st) in states.iter_mut().enumerate() {
            if let Some(reach) = reaches.get(i) {
                let bound = self.gap_lower_bound(reach, pose);
                // A tilt closes a section by up to `reach_mm` beyond the 2-D gap, the largest
                // |θ|·|z| − crown(z) over the face.
                if bound > self.face.as_ref().map_or(0.0, |f| f.reach_mm) {
                    (st.gap_mm, st.force_n, st.stiffness_n_per_mm) = (bound, 0.0, 0.0);
                    continue;
                }
            }
            *st = match self.geometry {
                GeometryMode::Exact => {
                    let (state, nearest) = self.exact_state(i, pose, trig, st.t, centre, (s, c))?;
                    if nearest || reaches.is_empty() {
                        state
                    } else {
                        self.nearest_state(i, pose, trig, state, centre, (s, c))?
                    }
                }
                GeometryMode::FirstOrder => {
                    let term = self.first_order_term(i, trig.e_phi);
                    self.first_order_from_term(i, pose, trig.e_phi, term)
                }
            };
            if let Some(reach) = reaches.get_mut(i) {
                *reach = Reach {
                    pose: *pose,
                    gap_mm: st.gap_mm,
                };
            }
        }
        Ok(())
    }

    /// A state whose foot was followed from the last evaluation but is not proven the nearest
    /// point of Γ (`certified_mm`), checked against the scanning search from scratch
    /// (`Mesh::roller_gap`) and followed from there when that is nearer: a gap stored as a
    /// reach must be the roller's true gap, or its lower bound could prove a contact away.
    fn nearest_state(
        &self,
        i: usize,
        pose: &Pose,
        trig: &AngleTrig,
        followed: RollerState,
        centre: Vec2,
        rotation: (f64, f64),
    ) -> Result<RollerState, GapFailure> {
        let fresh = self.mesh.roller_gap(i, pose, None)?;
        if fresh.gap_mm >= followed.gap_mm - 1e-12 * self.design.roller_circle_radius_mm {
            return Ok(followed);
        }
        Ok(self
            .exact_state(i, pose, trig, fresh.t, centre, rotation)?
            .0)
    }

    /// Exact state of roller i, and whether its foot is proven the nearest point of Γ. The
    /// roller centre is e^{−iβ}·L(t_i) + w in the disc frame
    /// (L the unmodified locus, t_i = 2πi/np + φ/nc, w the excess of the parts as built and
    /// the bearing offset seen from the disc, `Mesh::centre_excess`), and the gap is formed
    /// from small quantities (`Profile::closest_point_in_frame`).
    fn exact_state(
        &self,
        i: usize,
        pose: &Pose,
        trig: &AngleTrig,
        t_start: f64,
        centre: Vec2,
        (s, c): (f64, f64),
    ) -> Result<(RollerState, bool), GapFailure> {
        let unit = self.units[i];
        let (s0, c0) = trig.ideal;
        // e^{i·t_i} = e^{i·2πi/np}·e^{iφ/nc}, and e^{iφ/nc} = conj(e^{−iφ/nc}).
        let base = rotate(unit, c0, -s0);
        let t_ref = self.mesh.locus_parameter(i, &Pose::ideal(pose.crank_rad));
        let frame = LocusFrame {
            t_ref,
            r_ref: self.design.roller_circle_radius_mm,
            base,
            lobe: trig.lobe,
        };
        let excess = self
            .mesh
            .centre_excess(i, trig.e_phi, pose.centre_offset_mm);
        let w = rotate(excess, c, -s);
        let s_start = wrap_pi(t_start - t_ref);
        let foot = self
            .mesh
            .profile
            .closest_point_in_frame(&frame, pose.lag_rad, w, s_start)
            .map_err(|detail| GapFailure {
                roller: i,
                pose: *pose,
                detail,
            })?;
        let gap_mm =
            (self.mesh.profile.offset_mm - self.mesh.roller_radius(i)) + foot.locus_distance_mm;
        let normal = rotate(foot.normal, c, s);
        let cf = self.contact_force(gap_mm, foot.t, normal);
        let p = rotate(self.centres[i] - centre, c, -s);
        let nearest = foot.locus_distance_mm.abs() < self.certified_mm;
        let state = RollerState {
            gap_mm,
            force_n: cf.force_n,
            stiffness_n_per_mm: cf.stiffness_n_per_mm,
            arm_mm: cross(p, foot.normal),
            normal,
            point: centre + rotate(foot.point, c, s),
            t: foot.t,
        };
        Ok((state, nearest))
    }

    /// First-order gap at zero lag and arm of roller i (`first_order::roller`), from the unit
    /// vector of the eccentric direction instead of trigonometry per roller:
    /// cos φi = u_i·e_φ, sin φi = e_φ × u_i.
    fn first_order_term(&self, i: usize, e_phi: Vec2) -> (f64, f64) {
        let u = self.units[i];
        self.first_order.at(u.dot(&e_phi), cross(e_phi, u))
    }

    /// First-order state of roller i from its term (g_i, l_i) at `pose`: gap g_i − l_i·β − n·u
    /// (u the centre offset) and arm l_i. The normal points from the pitch point e·np·e_φ to
    /// the roller centre Rp·u_i, as for the unmodified profile:
    /// n = (u_i − K1·e_φ)/|u_i − K1·e_φ|, K1 = e·np/Rp.
    fn first_order_from_term(
        &self,
        i: usize,
        pose: &Pose,
        e_phi: Vec2,
        (gap0, arm): (f64, f64),
    ) -> RollerState {
        let towards = self.units[i] - self.first_order.k1 * e_phi;
        let normal = towards / towards.norm();
        let gap_mm = gap0 - arm * pose.lag_rad - normal.dot(&pose.centre_offset_mm);
        let t = self.mesh.foot_guess(i, pose);
        let cf = self.contact_force(gap_mm, t, normal);
        RollerState {
            gap_mm,
            force_n: cf.force_n,
            stiffness_n_per_mm: cf.stiffness_n_per_mm,
            arm_mm: arm,
            normal,
            point: self.centres[i] - self.design.roller_radius_mm * normal,
            t,
        }
    }

    /// First-order gaps at zero lag and arms of every roller at the eccentric direction
    /// e_φ = (cos φ, sin φ): (g_i, l_i).
    pub fn first_order_terms(&self, e_phi: Vec2, out: &mut Vec<(f64, f64)>) {
        out.clear();
        out.extend((0..self.count()).map(|i| self.first_order_term(i, e_phi)));
    }

    /// First-order states of every roller at `pose` from their `first_order_terms` at the
    /// pose's crank angle: the same as `evaluate` in first-order geometry without recomputing
    /// the terms.
    pub fn first_order_states(
        &self,
        pose: &Pose,
        e_phi: Vec2,
        terms: &[(f64, f64)],
        states: &mut Vec<RollerState>,
    ) {
        states.clear();
        states.extend(
            terms
                .iter()
                .enumerate()
                .map(|(i, &term)| self.first_order_from_term(i, pose, e_phi, term)),
        );
    }
}

// ∂gap/∂β = −l (MODEL.md sign convention, `geometry::clearance`).
impl_contact!(RollerState, |s| -s.arm_mm);
