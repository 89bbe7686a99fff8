//! Unloaded tooth contact analysis: the gap of every roller, angular backlash, unloaded TE,
//! lost motion and the whole-mesh minimum clearance (MODEL.md "Clearance").
//!
//! Sign conventions (fixed frame at the input axis, angles counter-clockwise):
//! - crank φ; disc centre at e·(cos φ, sin φ) + u (u: bearing deflection, zero when rigid);
//! - disc rotation ψ = −φ/nc + β, β the lag (positive opposes the motion);
//! - gap > 0 clearance, gap < 0 interference;
//! - moment arm l > 0: a contact force on that roller turns the disc clockwise (drives it), and
//!   the roller's gap closes as β grows: ∂gap/∂β = −l exactly.

use super::profile::LocusFrame;
use super::profile::{ClosestPointFailure, Profile};
use super::{cross, rotate, Vec2};
use crate::model::results::{ClearanceSweep, MinClearance};
use crate::model::{Design, Modification};
use crate::units;
use std::f64::consts::TAU;

/// Pose of the disc at one crank angle. Fixed frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Crank angle φ, rad.
    pub crank_rad: f64,
    /// Lag β of the disc behind its ideal rotation −φ/nc, rad.
    pub lag_rad: f64,
    /// Displacement of the disc centre from e·(cos φ, sin φ), mm.
    pub centre_offset_mm: Vec2,
}

impl Pose {
    pub fn ideal(crank_rad: f64) -> Self {
        Self::lagging(crank_rad, 0.0)
    }

    pub fn lagging(crank_rad: f64, lag_rad: f64) -> Self {
        Pose {
            crank_rad,
            lag_rad,
            centre_offset_mm: Vec2::zeros(),
        }
    }
}

/// Contact geometry of one roller against the disc at one pose. Disc frame, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerGap {
    /// Normal gap (signed distance of the roller centre to Γ, minus Rrp); < 0 is interference.
    pub gap_mm: f64,
    /// Locus parameter of the contact point.
    pub t: f64,
    /// Contact point on Γ.
    pub point: Vec2,
    /// Outward normal of Γ at the contact point; the roller pushes the disc along −normal.
    pub normal: Vec2,
    /// Moment arm about the disc centre, mm (sign as in the module doc).
    pub arm_mm: f64,
}

/// A roller whose closest point could not be found: names the roller and the pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GapFailure {
    pub roller: usize,
    pub pose: Pose,
    pub detail: ClosestPointFailure,
}

impl std::fmt::Display for GapFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "closest point of roller {} did not converge at crank {:.4}° (lag {:.3e} rad) after {} iterations",
            self.roller,
            units::deg(self.pose.crank_rad),
            self.pose.lag_rad,
            self.detail.iterations
        )
    }
}

/// A disc profile meshing with a fixed ring of rollers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mesh {
    pub profile: Profile,
    pub teeth: usize,
    pub rollers: usize,
    pub eccentricity_mm: f64,
    pub roller_circle_radius_mm: f64,
    pub roller_radius_mm: f64,
}

impl Mesh {
    pub fn new(design: &Design, modification: &Modification) -> Self {
        Mesh {
            profile: Profile::new(design, modification),
            teeth: design.teeth,
            rollers: design.rollers,
            eccentricity_mm: design.eccentricity_mm,
            roller_circle_radius_mm: design.roller_circle_radius_mm,
            roller_radius_mm: design.roller_radius_mm,
        }
    }

    /// Disc rotation ψ = −φ/nc + β.
    pub fn disc_rotation(&self, pose: &Pose) -> f64 {
        -pose.crank_rad / self.teeth as f64 + pose.lag_rad
    }

    /// Disc centre in the fixed frame.
    pub fn disc_centre(&self, pose: &Pose) -> Vec2 {
        let (s, c) = pose.crank_rad.sin_cos();
        Vec2::new(c, s) * self.eccentricity_mm + pose.centre_offset_mm
    }

    /// Centre of roller i in the fixed frame: Rp·(cos 2πi/np, sin 2πi/np).
    pub fn roller_centre(&self, i: usize) -> Vec2 {
        let a = std::f64::consts::TAU * i as f64 / self.rollers as f64;
        Vec2::new(a.cos(), a.sin()) * self.roller_circle_radius_mm
    }

    /// Centre of roller i in the disc frame: Rot(−ψ)·(roller − disc centre).
    pub fn roller_in_disc(&self, i: usize, pose: &Pose) -> Vec2 {
        let (s, c) = self.disc_rotation(pose).sin_cos();
        rotate(self.roller_centre(i) - self.disc_centre(pose), c, -s)
    }

    /// The roller's own locus parameter, the Newton start: 2πi/np + φ/nc − β.
    pub fn locus_parameter(&self, i: usize, pose: &Pose) -> f64 {
        std::f64::consts::TAU * i as f64 / self.rollers as f64 + pose.crank_rad / self.teeth as f64
            - pose.lag_rad
    }

    /// Where the foot of roller i lies to first order, the seed of its closest-point search:
    /// its own locus parameter turned back by the profile rotation, 2πi/np + φ/nc − β − Δδ (a
    /// rotation of the profile is a lag of the disc; exact at whole tooth pitches).
    pub fn foot_guess(&self, i: usize, pose: &Pose) -> f64 {
        self.locus_parameter(i, pose) - self.profile.rotation_rad
    }

    /// Exact gap of roller i at `pose`; `t_start` warm-starts the closest-point search.
    pub fn roller_gap(
        &self,
        i: usize,
        pose: &Pose,
        t_start: Option<f64>,
    ) -> Result<RollerGap, GapFailure> {
        let p = self.roller_in_disc(i, pose);
        let t0 = t_start.unwrap_or_else(|| self.foot_guess(i, pose));
        // In the disc frame the roller centre is q = e^{−iβ}·C0(t_i) − e^{−iψ}·u, C0 the
        // unmodified locus (radius Rp) and t_i = 2πi/np + φ/nc its locus parameter at β = 0
        // (np·t_i ≡ np·φ/nc mod 2π). The closest point is found from that form, without the
        // rounding of subtracting vectors of size Rp (see `closest_point_near_locus`).
        let t_i = std::f64::consts::TAU * i as f64 / self.rollers as f64
            + pose.crank_rad / self.teeth as f64;
        let (s, c) = self.disc_rotation(pose).sin_cos();
        let w = -rotate(pose.centre_offset_mm, c, -s);
        let precise = |start: f64| {
            self.profile
                .closest_point_near_locus(t_i, self.roller_circle_radius_mm, pose.lag_rad, w, start)
                .map_err(|detail| GapFailure {
                    roller: i,
                    pose: *pose,
                    detail,
                })
        };
        let mut foot = precise(t0)?;
        if t_start.is_none() {
            // A cold start follows the roller's own flank; the scanning search also finds an
            // opposite flank that may be nearer (a roller pushed across its tooth space), and
            // the precise iteration is then restarted there.
            if let Ok(scan) = self.profile.closest_point(p, t0) {
                let nearer = scan.signed_distance_mm.abs()
                    < foot.signed_distance_mm.abs() - 1e-9 * self.roller_radius_mm;
                if nearer {
                    foot = precise(scan.t)?;
                }
            }
        }
        Ok(RollerGap {
            // ΔRrp + the signed distance to C (MODEL.md), summed small to small.
            gap_mm: (self.profile.offset_mm - self.roller_radius_mm) + foot.locus_distance_mm,
            t: foot.t,
            point: foot.point,
            normal: foot.normal,
            arm_mm: cross(p, foot.normal),
        })
    }

    /// Lag at which roller i's gap closes at crank φ (Newton on gap(β) = 0, ∂gap/∂β = −l).
    ///
    /// `None` when the roller cannot close within half a roller pitch of disc rotation: its arm
    /// is too small or of the wrong sign, or following it would push the roller centre so deep
    /// into the disc that the nearest flank is no longer its own. Such a roller never sets the
    /// backlash, which is the smallest closing lag. Steps are damped to a tenth of that reach.
    pub fn closing_lag(&self, i: usize, crank_rad: f64) -> Result<Option<f64>, GapFailure> {
        let reach = std::f64::consts::PI / self.rollers as f64;
        let mut pose = Pose::ideal(crank_rad);
        let mut g = self.roller_gap(i, &pose, None)?;
        for _ in 0..60 {
            if g.arm_mm.abs() < 1e-9 * self.roller_circle_radius_mm {
                return Ok(None);
            }
            let step = (g.gap_mm / g.arm_mm).clamp(-0.1 * reach, 0.1 * reach);
            pose.lag_rad += step;
            if pose.lag_rad.abs() > reach {
                return Ok(None);
            }
            g = match self.roller_gap(i, &pose, Some(g.t)) {
                Ok(g) => g,
                Err(_) => return Ok(None),
            };
            // Converged when the step is negligible or the gap is closed to its round-off (a few
            // ulp of Rp). The step test alone cannot be met once round-off in the gap, divided
            // by the arm, exceeds 1e-15 + 1e-12·|β| rad: such a roller was wrongly reported as
            // not closing, and the backlash then depended on round-off.
            let closed = g.gap_mm.abs() <= 32.0 * f64::EPSILON * self.roller_circle_radius_mm;
            if closed || step.abs() <= 1e-15 + 1e-12 * pose.lag_rad.abs() {
                // The warm start follows one flank. If another part of the profile is nearer
                // at this lag (a roller wedged into a root sharper than the shift: one side
                // opens while the other still interferes), the roller has not closed.
                if let Ok(fresh) = self.roller_gap(i, &pose, None) {
                    if fresh.gap_mm < g.gap_mm - 1e-12 * self.roller_circle_radius_mm {
                        return Ok(None);
                    }
                }
                return Ok(Some(pose.lag_rad));
            }
        }
        Ok(None)
    }
}

/// Gaps closer than this count as equal when locating the minimum, so that mirror-symmetric
/// rollers with equal gaps report the first (lowest roller index, earliest angle) whatever the
/// last bit of round-off says. A picometre: far below any tolerance that matters.
const TIE_MM: f64 = 1e-9 * 1e-3;

/// The smallest gap over every roller and crank angle at the ideal pose (β = 0): the
/// whole-mesh interference check, without the backlash work of `sweep`.
///
/// Gaps repeat with the mesh period with the roller index shifted by one (crank φ + 2π/np puts
/// roller i where roller i − 1 was at φ, turned by one tooth, and the profile is the same
/// after a tooth): a uniform sweep over whole mesh periods needs only its first period. Each
/// roller's closest point is found once from scratch (the scanning search), then followed
/// from angle to angle in its locus frame (`Profile::closest_point_in_frame`), with the
/// angle's trigonometry computed once for all rollers.
pub fn min_gap(mesh: &Mesh, crank_rad: &[f64]) -> Result<MinClearance, GapFailure> {
    let crank = first_period(mesh, crank_rad);
    let tooth = TAU / mesh.teeth as f64;
    let np = mesh.rollers as f64;
    let units: Vec<Vec2> = (0..mesh.rollers)
        .map(|i| mesh.roller_centre(i) / mesh.roller_circle_radius_mm)
        .collect();
    let mut warm: Vec<f64> = Vec::with_capacity(mesh.rollers);
    let mut min = MinClearance {
        gap_mm: f64::INFINITY,
        roller: 0,
        crank_rad: 0.0,
        tooth_phase: 0.0,
    };
    let offset = mesh.profile.offset_mm - mesh.roller_radius_mm;
    for &phi in crank {
        let pose = Pose::ideal(phi);
        let turn = phi / mesh.teeth as f64;
        let (st, ct) = turn.sin_cos();
        let lobe = Vec2::new((np * turn).cos(), (np * turn).sin());
        for i in 0..mesh.rollers {
            let (gap_mm, t) = match warm.get(i) {
                None => {
                    let g = mesh.roller_gap(i, &pose, None)?;
                    warm.push(g.t);
                    (g.gap_mm, g.t)
                }
                Some(&t_prev) => {
                    let t_ref = TAU * i as f64 / np + turn;
                    let frame = LocusFrame {
                        t_ref,
                        r_ref: mesh.roller_circle_radius_mm,
                        base: rotate(units[i], ct, st),
                        lobe,
                    };
                    let s_start = super::wrap_pi(t_prev - t_ref);
                    let foot = mesh
                        .profile
                        .closest_point_in_frame(&frame, 0.0, Vec2::zeros(), s_start)
                        .map_err(|detail| GapFailure {
                            roller: i,
                            pose,
                            detail,
                        })?;
                    warm[i] = foot.t;
                    (offset + foot.locus_distance_mm, foot.t)
                }
            };
            if gap_mm < min.gap_mm - TIE_MM {
                min = MinClearance {
                    gap_mm,
                    roller: i,
                    crank_rad: phi,
                    tooth_phase: t.rem_euclid(tooth) / tooth,
                };
            }
        }
    }
    Ok(min)
}

/// The leading mesh period of a uniform sweep that covers at least one whole period on its
/// grid; otherwise the whole sweep.
pub fn first_period<'a>(mesh: &Mesh, crank_rad: &'a [f64]) -> &'a [f64] {
    let n = crank_rad.len();
    if n < 2 {
        return crank_rad;
    }
    let h = crank_rad[1] - crank_rad[0];
    let span = crank_rad[n - 1] - crank_rad[0];
    let uniform = (span - h * (n - 1) as f64).abs() <= 1e-9 * span.abs().max(1.0);
    let per_period = TAU / mesh.rollers as f64 / h;
    let m = per_period.round();
    if uniform && m >= 1.0 && (per_period - m).abs() < 1e-9 && (m as usize) <= n {
        &crank_rad[..m as usize]
    } else {
        crank_rad
    }
}

/// Gaps and backlash at every crank angle.
pub fn sweep(mesh: &Mesh, crank_rad: &[f64]) -> Result<ClearanceSweep, GapFailure> {
    let n = mesh.rollers;
    let mut gap_mm = vec![Vec::with_capacity(crank_rad.len()); n];
    let mut backlash_rad = Vec::with_capacity(crank_rad.len());
    let mut backlash_reverse_rad = Vec::with_capacity(crank_rad.len());
    let mut min = MinClearance {
        gap_mm: f64::INFINITY,
        roller: 0,
        crank_rad: 0.0,
        tooth_phase: 0.0,
    };
    let tooth = std::f64::consts::TAU / mesh.teeth as f64;
    for &phi in crank_rad {
        let pose = Pose::ideal(phi);
        let (mut forward, mut reverse) = (f64::INFINITY, f64::INFINITY);
        for (i, gaps) in gap_mm.iter_mut().enumerate() {
            let g = mesh.roller_gap(i, &pose, None)?;
            gaps.push(g.gap_mm);
            if g.gap_mm < min.gap_mm - TIE_MM {
                min = MinClearance {
                    gap_mm: g.gap_mm,
                    roller: i,
                    crank_rad: phi,
                    tooth_phase: g.t.rem_euclid(tooth) / tooth,
                };
            }
            match mesh.closing_lag(i, phi)? {
                Some(b) if g.arm_mm > 0.0 => forward = forward.min(b),
                Some(b) if g.arm_mm < 0.0 => reverse = reverse.min(-b),
                _ => {}
            }
        }
        backlash_rad.push(forward);
        backlash_reverse_rad.push(reverse);
    }
    let lost_motion_rad = backlash_rad
        .iter()
        .zip(&backlash_reverse_rad)
        .map(|(a, b)| a + b)
        .collect();
    Ok(ClearanceSweep {
        gap_mm,
        backlash_rad,
        backlash_reverse_rad,
        lost_motion_rad,
        min,
    })
}
