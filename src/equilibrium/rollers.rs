//! The roller set at one disc pose: gap, force, stiffness and moment arm of every roller.
//!
//! Vectors in the fixed frame. A roller's force on the disc is −F·n (n the outward normal of
//! the disc at the contact); its moment about the disc centre is −F·l (MODEL.md sign: l > 0
//! rollers drive the disc clockwise and close as the lag β grows, ∂gap/∂β = −l, and a
//! displacement u of the disc centre changes the gap by −n·u).

use crate::contact::hertz_line::{hertz, HertzLine};
use crate::contact::law::{self, ContactForce, LineContact};
use crate::geometry::clearance::{GapFailure, Mesh, Pose};
use crate::geometry::first_order;
use crate::geometry::{rotate, Vec2};
use crate::spec::{ContactLaw, Design, GeometryMode, Modification};

/// One roller's contact at one pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerState {
    pub gap_mm: f64,
    pub force_n: f64,
    pub stiffness_n_per_mm: f64,
    pub arm_mm: f64,
    /// Outward disc normal at the contact, fixed frame.
    pub normal: Vec2,
    /// Contact point, fixed frame, mm.
    pub point: Vec2,
    /// Signed curvature of the disc profile at the contact, 1/mm (positive convex).
    pub curvature_per_mm: f64,
    /// Locus parameter of the contact (warm start for the next evaluation).
    pub t: f64,
}

impl RollerState {
    /// Force of this roller on the disc, fixed frame, N.
    pub fn force_vector(&self) -> Vec2 {
        -self.force_n * self.normal
    }
}

/// The rollers of one design under one contact law and geometry mode.
#[derive(Debug, Clone)]
pub struct Rollers {
    pub mesh: Mesh,
    design: Design,
    modification: Modification,
    pub law: ContactLaw,
    pub geometry: GeometryMode,
}

impl Rollers {
    pub fn new(design: &Design, m: &Modification, law: ContactLaw, geometry: GeometryMode) -> Self {
        Rollers {
            mesh: Mesh::new(design, m),
            design: design.clone(),
            modification: *m,
            law,
            geometry,
        }
    }

    pub fn count(&self) -> usize {
        self.design.rollers
    }

    /// Contact description for the laws: disc flank of signed curvature κ against a roller.
    /// A flat or nearly flat flank's radius is capped at Rp (the disc's own size), where the
    /// 2-D logarithmic displacement field of the log law is cut off.
    pub fn line_contact(&self, curvature_per_mm: f64) -> LineContact {
        let d = &self.design;
        let rrp = d.roller_radius_mm;
        let rp = d.roller_circle_radius_mm;
        let flank = (1.0 / curvature_per_mm.abs()).min(rp);
        let inv_r = (curvature_per_mm + 1.0 / rrp).max(1.0 / rp);
        LineContact {
            contact_modulus_mpa: d.contact_modulus_mpa(),
            compliance_per_mpa: [
                d.disc_material.compliance_per_mpa(),
                d.roller_material.compliance_per_mpa(),
            ],
            length_mm: d.face_width_mm,
            radii_mm: [flank, rrp],
            effective_radius_mm: 1.0 / inv_r,
        }
    }

    /// Hertz pressure and half-width of a roller state.
    pub fn hertz(&self, s: &RollerState) -> HertzLine {
        hertz(&self.line_contact(s.curvature_per_mm), s.force_n)
    }

    fn contact_force(&self, gap_mm: f64, curvature_per_mm: f64) -> ContactForce {
        if gap_mm >= 0.0 {
            return ContactForce::NONE;
        }
        law::force(self.law, &self.line_contact(curvature_per_mm), -gap_mm)
    }

    /// Evaluate every roller at `pose`. `states` holds the previous evaluation (its `t` is the
    /// warm start) or is empty.
    pub fn evaluate(&self, pose: &Pose, states: &mut Vec<RollerState>) -> Result<(), GapFailure> {
        let n = self.count();
        let warm = states.len() == n;
        if !warm {
            states.clear();
        }
        let psi = self.mesh.disc_rotation(pose);
        let (s, c) = psi.sin_cos();
        let centre = self.mesh.disc_centre(pose);
        for i in 0..n {
            let t_start = if warm { Some(states[i].t) } else { None };
            let state = match self.geometry {
                GeometryMode::Exact => {
                    let g = self.mesh.roller_gap(i, pose, t_start)?;
                    let normal = rotate(g.normal, c, s);
                    let curvature = self.mesh.profile.curvature(g.t);
                    let cf = self.contact_force(g.gap_mm, curvature);
                    RollerState {
                        gap_mm: g.gap_mm,
                        force_n: cf.force_n,
                        stiffness_n_per_mm: cf.stiffness_n_per_mm,
                        arm_mm: g.arm_mm,
                        normal,
                        point: centre + rotate(g.point, c, s),
                        curvature_per_mm: curvature,
                        t: g.t,
                    }
                }
                GeometryMode::FirstOrder => self.first_order_state(i, pose),
            };
            if warm {
                states[i] = state;
            } else {
                states.push(state);
            }
        }
        Ok(())
    }

    /// First-order state: closed-form gap and arm; the normal points from the pitch point
    /// (e·np along the eccentric direction) to the roller centre, as for the unmodified profile.
    fn first_order_state(&self, i: usize, pose: &Pose) -> RollerState {
        let fo = first_order::roller(&self.design, &self.modification, i, pose.crank_rad);
        let roller = self.mesh.roller_centre(i);
        let (s, c) = pose.crank_rad.sin_cos();
        let pitch = Vec2::new(c, s) * (self.design.eccentricity_mm * self.design.rollers as f64);
        let normal = (roller - pitch).normalize();
        let gap_mm = fo.gap_mm - fo.arm_mm * pose.lag_rad - normal.dot(&pose.centre_offset_mm);
        let t = self.mesh.locus_parameter(i, pose);
        let curvature = self.mesh.profile.curvature(t);
        let cf = self.contact_force(gap_mm, curvature);
        RollerState {
            gap_mm,
            force_n: cf.force_n,
            stiffness_n_per_mm: cf.stiffness_n_per_mm,
            arm_mm: fo.arm_mm,
            normal,
            point: roller - self.design.roller_radius_mm * normal,
            curvature_per_mm: curvature,
            t,
        }
    }
}

/// Moment of the rollers' forces that balances the load, Σ F·l (N·mm), its slope ∂/∂β = Σ k·l²,
/// and its scale Σ |F·l| (for relative residuals).
pub fn moment(states: &[RollerState]) -> (f64, f64, f64) {
    states.iter().fold((0.0, 0.0, 0.0), |(m, dm, scale), s| {
        (
            m + s.force_n * s.arm_mm,
            dm + s.stiffness_n_per_mm * s.arm_mm * s.arm_mm,
            scale + (s.force_n * s.arm_mm).abs(),
        )
    })
}
