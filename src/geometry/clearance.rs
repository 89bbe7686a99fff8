//! Unloaded tooth contact analysis: the gap of every roller, angular backlash, unloaded TE,
//! lost motion and the whole-mesh minimum clearance (MODEL.md "Clearance").
//!
//! Sign conventions (fixed frame at the input axis, angles counter-clockwise):
//! - crank φ; disc centre at e·(cos φ, sin φ) + u (u: bearing deflection, zero when rigid);
//! - disc rotation ψ = −φ/nc + β, β the lag (positive opposes the motion);
//! - gap > 0 clearance, gap < 0 interference;
//! - moment arm l > 0: a contact force on that roller turns the disc clockwise (drives it), and
//!   the roller's gap closes as β grows: ∂gap/∂β = −l exactly.

use super::profile::{ClosestPointFailure, LocusFrame, Profile};
use super::{cross, rotate, sin_cos, unit, wrap_pi, Vec2};
use crate::model::results::{BacklashCurves, ClearanceSweep, MinClearance, MinCoverage};
use crate::model::{Design, Modification};
use crate::progress::{Progress, Silent};
use crate::units;
use rayon::prelude::*;
use std::f64::consts::{PI, TAU};
use std::sync::Arc;

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
        Self::new(crank_rad, lag_rad, Vec2::zeros())
    }

    pub fn new(crank_rad: f64, lag_rad: f64, centre_offset_mm: Vec2) -> Self {
        Pose {
            crank_rad,
            lag_rad,
            centre_offset_mm,
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

/// A disc profile meshing with a fixed ring of rollers, as built (MODEL.md "Part deviations"):
/// roller i's centre is Rp·(cos 2πi/np, sin 2πi/np) moved by its deviation, its radius its own,
/// and the disc centre orbits at the crank's eccentricity e + de while the profile keeps the e it
/// was ground with.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub profile: Profile,
    pub teeth: usize,
    pub rollers: usize,
    /// e of the profile (the design's), mm.
    pub eccentricity_mm: f64,
    pub roller_circle_radius_mm: f64,
    pub roller_radius_mm: f64,
    /// de: the crank's eccentricity minus the profile's, mm.
    pub eccentricity_deviation_mm: f64,
    /// Every roller as built; empty when every roller is nominal.
    pub parts: Arc<[RollerPart]>,
}

/// One roller as built: its centre's displacement from its nominal place (fixed frame, mm) and
/// its radius (mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerPart {
    pub offset_mm: Vec2,
    pub radius_mm: f64,
}

impl Mesh {
    /// The mesh of `design` as built, its profile as ground (`Profile::as_ground`).
    pub fn new(design: &Design, modification: &Modification) -> Self {
        let d = &design.deviations;
        let rp = design.roller_circle_radius_mm;
        let parts: Vec<RollerPart> = if d.moves_rollers() {
            (0..design.rollers)
                .map(|i| {
                    let a = design.roller_angle(i);
                    let r = d.roller(i);
                    let (x, y) = r.centre.displacement_mm(rp, (a.cos(), a.sin()));
                    RollerPart {
                        offset_mm: Vec2::new(x, y),
                        radius_mm: design.roller_radius_mm + r.radius_mm,
                    }
                })
                .collect()
        } else {
            Vec::new()
        };
        Mesh {
            profile: Profile::as_ground(design, modification),
            teeth: design.teeth,
            rollers: design.rollers,
            eccentricity_mm: design.eccentricity_mm,
            roller_circle_radius_mm: rp,
            roller_radius_mm: design.roller_radius_mm,
            eccentricity_deviation_mm: d.eccentricity_mm,
            parts: parts.into(),
        }
    }

    /// Roller i's displacement from its nominal centre, fixed frame, mm.
    #[inline]
    pub fn roller_offset(&self, i: usize) -> Vec2 {
        self.parts.get(i).map_or(Vec2::zeros(), |p| p.offset_mm)
    }

    /// Roller i's radius as built, mm.
    #[inline]
    pub fn roller_radius(&self, i: usize) -> f64 {
        self.parts
            .get(i)
            .map_or(self.roller_radius_mm, |p| p.radius_mm)
    }

    /// The largest distance of a roller centre from its nominal place, mm.
    pub fn largest_roller_offset_mm(&self) -> f64 {
        self.parts
            .iter()
            .map(|p| p.offset_mm.norm())
            .fold(0.0, f64::max)
    }

    /// Every gap repeats with the mesh period (`first_period`): the rollers are alike and
    /// evenly spaced, the teeth alike. A roller off its place or size, or a form error of the
    /// disc, breaks that (the crank eccentricity and the grinding errors do not: they act on
    /// every roller and tooth alike).
    pub fn is_periodic(&self) -> bool {
        self.parts.is_empty() && !self.profile.has_form()
    }

    /// The part of roller i's centre, seen from the disc centre, that the nominal locus form
    /// does not hold, fixed frame: the roller's displacement, less the crank eccentricity's
    /// deviation de·e_φ and the bearing offset u.
    #[inline]
    pub fn centre_excess(&self, i: usize, e_phi: Vec2, offset: Vec2) -> Vec2 {
        self.roller_offset(i) - e_phi * self.eccentricity_deviation_mm - offset
    }

    /// Disc rotation ψ = −φ/nc + β.
    pub fn disc_rotation(&self, pose: &Pose) -> f64 {
        -pose.crank_rad / self.teeth as f64 + pose.lag_rad
    }

    /// Disc centre in the fixed frame: (e + de)·(cos φ, sin φ) + u.
    pub fn disc_centre(&self, pose: &Pose) -> Vec2 {
        unit(pose.crank_rad) * (self.eccentricity_mm + self.eccentricity_deviation_mm)
            + pose.centre_offset_mm
    }

    /// Roller i's nominal centre, Rp·(cos 2πi/np, sin 2πi/np), fixed frame.
    pub fn nominal_centre(&self, i: usize) -> Vec2 {
        let a = std::f64::consts::TAU * i as f64 / self.rollers as f64;
        unit(a) * self.roller_circle_radius_mm
    }

    /// Unit vector of roller i's nominal place: its nominal centre over Rp (so formed, the
    /// sweeps' roller frames are the same to the last bit as before parts as built existed).
    pub fn roller_unit(&self, i: usize) -> Vec2 {
        self.nominal_centre(i) / self.roller_circle_radius_mm
    }

    /// Centre of roller i in the fixed frame: its nominal centre plus its displacement.
    pub fn roller_centre(&self, i: usize) -> Vec2 {
        self.nominal_centre(i) + self.roller_offset(i)
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
        // In the disc frame the roller centre is q = e^{−iβ}·C0(t_i) + e^{−iψ}·x, C0 the
        // unmodified locus (radius Rp), t_i = 2πi/np + φ/nc its locus parameter at β = 0
        // (np·t_i ≡ np·φ/nc mod 2π) and x the excess of the parts as built and the bearing
        // offset (`centre_excess`). The closest point is found from that form, without the
        // rounding of subtracting vectors of size Rp (see `closest_point_near_locus`).
        let t_i = self.locus_parameter(i, &Pose::ideal(pose.crank_rad));
        let (s, c) = self.disc_rotation(pose).sin_cos();
        let excess = self.centre_excess(i, unit(pose.crank_rad), pose.centre_offset_mm);
        let w = rotate(excess, c, -s);
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
                    < foot.signed_distance_mm.abs() - 1e-9 * self.roller_radius(i);
                if nearer {
                    foot = precise(scan.t)?;
                }
            }
        }
        Ok(RollerGap {
            // ΔRrp + the signed distance to C (MODEL.md), summed small to small.
            gap_mm: (self.profile.offset_mm - self.roller_radius(i)) + foot.locus_distance_mm,
            t: foot.t,
            point: foot.point,
            normal: foot.normal,
            arm_mm: cross(p, foot.normal),
        })
    }

    /// Lag at which roller i's gap first closes at crank φ as the disc turns the way `sign`
    /// says (+1: β grows, the forward backlash; −1: β falls, the reverse), from scratch; `None`
    /// when it does not close within half a roller pitch (π/np) that way.
    ///
    /// The way its nearest flank at β = 0 closes (the sign of its arm), Newton from β = 0
    /// (`close_from`). The other way that flank opens, and the roller closes on another part
    /// of the profile, or on the same flank once its foot has slid past a root: the far side of
    /// its tooth space, nearer than its own flank when the roller sits beyond the centre of
    /// curvature of a sharp root. It is reached by `march` and closed by Newton.
    pub fn closing_lag_toward(
        &self,
        i: usize,
        crank_rad: f64,
        sign: f64,
    ) -> Result<Option<f64>, GapFailure> {
        let pose = Pose::ideal(crank_rad);
        let g = self.roller_gap(i, &pose, None)?;
        let rate = self.gap_rate_bound_mm(self.roller_in_disc(i, &pose).norm());
        let reach = PI / self.rollers as f64;
        let rp = self.roller_circle_radius_mm;
        let gap_arm = |g: &RollerGap| (g.gap_mm, g.arm_mm);
        let next = |lag, _: &RollerGap| {
            self.roller_gap(i, &Pose::lagging(crank_rad, lag), None)
                .ok()
        };
        let reached = march(sign, rate, reach, rp, g, gap_arm, next);
        Ok(reached.and_then(|r| {
            r.closing(sign, |lag, g| {
                self.close_from(i, Pose::lagging(crank_rad, lag), g)
            })
        }))
    }

    /// A bound on how fast a roller's gap changes with the lag, |∂gap/∂β| = |l| (mm), for a
    /// roller centre at `radius_mm` from the disc centre: the arm is the distance from the disc
    /// centre to the normal at the foot, at most |p|, and at most `Profile::arm_bound_mm`
    /// (e·nc without a form error).
    pub fn gap_rate_bound_mm(&self, radius_mm: f64) -> f64 {
        self.profile.arm_bound_mm().min(radius_mm)
    }

    /// Newton on gap(β) = 0 (∂gap/∂β = −l) from `pose`, where roller i's gap is `g`.
    ///
    /// `None` when the roller cannot close within half a roller pitch of disc rotation: its arm
    /// is too small or of the wrong sign, or following it would push the roller centre so deep
    /// into the disc that the nearest flank is no longer its own. Steps are damped to a tenth
    /// of that reach.
    fn close_from(&self, i: usize, mut pose: Pose, mut g: RollerGap) -> Option<f64> {
        let reach = std::f64::consts::PI / self.rollers as f64;
        for _ in 0..60 {
            if g.arm_mm.abs() < 1e-9 * self.roller_circle_radius_mm {
                return None;
            }
            let step = (g.gap_mm / g.arm_mm).clamp(-0.1 * reach, 0.1 * reach);
            pose.lag_rad += step;
            if pose.lag_rad.abs() > reach {
                return None;
            }
            g = self.roller_gap(i, &pose, Some(g.t)).ok()?;
            // Converged when the step is negligible or the gap is closed to its round-off (a few
            // ulp of Rp). The step test alone cannot be met once round-off in the gap, divided
            // by the arm, exceeds 1e-15 + 1e-12·|β| rad: such a roller would be reported as not
            // closing, and the backlash would depend on round-off.
            let closed = g.gap_mm.abs() <= 32.0 * f64::EPSILON * self.roller_circle_radius_mm;
            if closed || step.abs() <= 1e-15 + 1e-12 * pose.lag_rad.abs() {
                // The warm start follows one flank. If another part of the profile is nearer
                // at this lag (a roller wedged into a root sharper than the shift: one side
                // opens while the other still interferes), the roller has not closed.
                if let Ok(fresh) = self.roller_gap(i, &pose, None) {
                    if fresh.gap_mm < g.gap_mm - 1e-12 * self.roller_circle_radius_mm {
                        return None;
                    }
                }
                return Some(pose.lag_rad);
            }
        }
        None
    }
}

/// Proven-free steps of `march` before it probes.
const MARCH_STEPS: usize = 64;

/// Where `march` leaves a roller.
enum Reached<G> {
    /// The flank nearest the roller closes the way the disc turns from this lag, with this
    /// state there: the start of the Newton iteration that closes it.
    Flank(f64, G),
    /// The gap closes at this lag, bracketed by `probe`.
    Closed(f64),
}

impl<G> Reached<G> {
    /// The closing lag: bracketed, or by `newton` from the flank's lag and state. Newton's root
    /// is taken when it lies beyond that lag (`march` proved the gap open before); from β = 0
    /// it may lie either side (a roller that interferes closes behind).
    fn closing(self, sign: f64, newton: impl FnOnce(f64, G) -> Option<f64>) -> Option<f64> {
        match self {
            Reached::Closed(b) => Some(b),
            Reached::Flank(lag, g) => {
                newton(lag, g).filter(|&b| lag == 0.0 || sign * b >= sign * lag)
            }
        }
    }
}

/// Turns the disc from β = 0 the way `sign` says until the flank nearest the roller closes
/// that way (its arm l has the sign of `sign`); `None` when the roller is proven open up to
/// `limit` (rad), or interferes at β = 0 on a flank that opens that way (it holds the disc the
/// other way).
///
/// The gap changes by at most `rate_mm` per radian of lag (`Mesh::gap_rate_bound_mm`): from a
/// gap g the next g/rate rad are free, and each step is that long (at least the round-off of a
/// closed gap). Nothing closes between the steps, whatever flank is nearest; `gap_arm` reads
/// (gap, l) from a state and `next` is the nearest foot at a lag, from the state before. After
/// `MARCH_STEPS` such steps it probes (`probe`).
fn march<G>(
    sign: f64,
    rate_mm: f64,
    limit: f64,
    rp: f64,
    mut g: G,
    gap_arm: impl Fn(&G) -> (f64, f64),
    mut next: impl FnMut(f64, &G) -> Option<G>,
) -> Option<Reached<G>> {
    let (mut lag, mut free) = (0.0, 0.0);
    for _ in 0..MARCH_STEPS {
        let (gap, arm) = gap_arm(&g);
        let closes = sign * arm > 1e-9 * rp;
        if lag == 0.0 && (closes || gap <= 0.0) {
            return closes.then_some(Reached::Flank(lag, g));
        }
        free = gap.max(32.0 * f64::EPSILON * rp) / rate_mm;
        if sign * lag + free > limit {
            return None;
        }
        if closes {
            return Some(Reached::Flank(lag, g));
        }
        lag += sign * free;
        g = next(lag, &g)?;
    }
    probe(sign, (lag, g), free, limit, |g| gap_arm(g).0, next)
}

/// After `MARCH_STEPS` proven-free steps, which a roller near a root can take with its gap a
/// micrometre and its arm near zero (the gap grows by a fraction of itself per step, and its
/// foot has yet to pass the root), the gap is probed at lags whose distance from there doubles
/// from the last step, up to `limit`. The first probe at which it is closed and the open lag
/// before it bracket a closing, which bisection narrows to the closing lags' stopping rule
/// (1e-15 + 1e-12·|β| rad). Not a proof: a flank that the roller touches and leaves again
/// between two probes is missed.
fn probe<G>(
    sign: f64,
    (mut lag, mut g): (f64, G),
    mut step: f64,
    limit: f64,
    gap: impl Fn(&G) -> f64,
    mut next: impl FnMut(f64, &G) -> Option<G>,
) -> Option<Reached<G>> {
    let shut = loop {
        step *= 2.0;
        let at = sign * (sign * lag + step).min(limit);
        let h = next(at, &g)?;
        if gap(&h) <= 0.0 {
            break at;
        }
        if sign * at >= limit {
            return None;
        }
        (lag, g) = (at, h);
    };
    let (mut open, mut shut) = ((lag, g), shut);
    for _ in 0..200 {
        if (shut - open.0).abs() <= 1e-15 + 1e-12 * shut.abs() {
            break;
        }
        let mid = 0.5 * (open.0 + shut);
        let h = next(mid, &open.1)?;
        if gap(&h) > 0.0 {
            open = (mid, h);
        } else {
            shut = mid;
        }
    }
    Some(Reached::Closed(shut))
}

/// Gaps closer than this count as equal when locating the minimum, so that mirror-symmetric
/// rollers with equal gaps report the first (lowest roller index, earliest angle) whatever the
/// last bit of round-off says. A picometre: far below any tolerance that matters.
pub const TIE_MM: f64 = 1e-9 * 1e-3;

/// Crank angles one worker sweeps in sequence, each roller warm-started from the angle before
/// and from nothing before the chunk. Fixed (as the loaded sweep's `CHUNK`), so that the results
/// are the same bit for bit however many threads share the chunks.
pub const CHUNK: usize = 64;

/// What a clearance sweep computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// The gap of every roller at every crank angle, and the smallest.
    Gaps,
    /// The gaps, and the closing lag of every roller: backlash both ways and lost motion.
    Backlash,
}

/// The smallest gap over every roller and crank angle at the ideal pose (β = 0): the
/// whole-mesh interference check, without the backlash work of `sweep`.
///
/// Gaps repeat with the mesh period with the roller index shifted by one (crank φ + 2π/np puts
/// roller i where roller i − 1 was at φ, turned by one tooth, and the profile is the same
/// after a tooth): a uniform sweep over whole mesh periods needs only its first period.
pub fn min_gap(mesh: &Mesh, crank_rad: &[f64]) -> Result<MinClearance, GapFailure> {
    let crank = first_period(mesh, crank_rad);
    Ok(sweep(mesh, crank, Scope::Gaps, &Silent)?.min)
}

/// The leading mesh period of a uniform sweep that covers at least one whole period on its
/// grid; otherwise, and for rollers as built that are not alike (`Mesh::is_periodic`), the
/// whole sweep.
pub fn first_period<'a>(mesh: &Mesh, crank_rad: &'a [f64]) -> &'a [f64] {
    let n = crank_rad.len();
    if n < 2 || !mesh.is_periodic() {
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

/// Gaps at every crank angle, and with `Scope::Backlash` the backlash both ways and the lost
/// motion.
///
/// Each roller's closest point is followed from angle to angle in its locus frame
/// (`Profile::closest_point_in_frame`, a Newton step or two from the foot of the angle before)
/// and accepted when its distance from the locus proves it the nearest point of Γ
/// (`Tracker::certified_mm`); otherwise, and at a failure, the roller is evaluated from scratch
/// (`Mesh::roller_gap` with its scanning search). Closing lags
/// follow the same way (`Tracker::closing_lag`), each roller's the way its nearest flank
/// closes; the other way it is turned until another flank closes, while that can still come
/// before the backlash found (`Tracker::closing_toward`). Chunks of `CHUNK` angles run in
/// parallel and write their rows in place.
/// `progress` hears of every chunk of crank angles done.
pub fn sweep(
    mesh: &Mesh,
    crank_rad: &[f64],
    scope: Scope,
    progress: &dyn Progress,
) -> Result<ClearanceSweep, GapFailure> {
    let columns = Tracker::new(mesh).sweep(crank_rad, scope, progress)?;
    let min = smallest(mesh, crank_rad, &columns.gap_mm)?;
    let backlash = (scope == Scope::Backlash).then(|| {
        let lost_motion_rad = columns
            .forward_rad
            .iter()
            .zip(&columns.reverse_rad)
            .map(|(a, b)| a + b)
            .collect();
        BacklashCurves {
            forward_rad: columns.forward_rad,
            reverse_rad: columns.reverse_rad,
            lost_motion_rad,
        }
    });
    Ok(ClearanceSweep {
        gap_mm: columns.gap_mm,
        min,
        coverage: MinCoverage::Angles(crank_rad.len()),
        backlash,
    })
}

/// The smallest gap of the columns \[roller\]\[angle\] (`lowest` over every angle, below an
/// infinite gap); its place on the tooth from the roller's closest point evaluated from scratch.
fn smallest(
    mesh: &Mesh,
    crank_rad: &[f64],
    gap_mm: &[Vec<f64>],
) -> Result<MinClearance, GapFailure> {
    let none = MinClearance {
        gap_mm: f64::INFINITY,
        roller: 0,
        crank_rad: 0.0,
        tooth_phase: 0.0,
    };
    let min = lowest(crank_rad, gap_mm, 0..crank_rad.len(), Some(none)).unwrap_or(none);
    on_tooth(mesh, min)
}

/// The smallest gap of the columns \[roller\]\[angle\] at the angles `angles`, scanned angle by
/// angle, roller by roller, below `min` (none: the first gap is the first minimum), a new
/// minimum only when lower by more than `TIE_MM`; its tooth phase left 0.
pub(super) fn lowest(
    crank_rad: &[f64],
    gap_mm: &[Vec<f64>],
    angles: std::ops::Range<usize>,
    mut min: Option<MinClearance>,
) -> Option<MinClearance> {
    for k in angles {
        for (i, gaps) in gap_mm.iter().enumerate() {
            if min.is_none_or(|m| gaps[k] < m.gap_mm - TIE_MM) {
                min = Some(MinClearance {
                    gap_mm: gaps[k],
                    roller: i,
                    crank_rad: crank_rad[k],
                    tooth_phase: 0.0,
                });
            }
        }
    }
    min
}

/// `min` with where its roller's closest point lies on its tooth, when it is a gap (finite), at
/// its crank φ and the ideal pose: 0 at the root, 0.5 at the tip (`MinClearance::tooth_phase`),
/// from the closest point found afresh.
pub fn on_tooth(mesh: &Mesh, mut min: MinClearance) -> Result<MinClearance, GapFailure> {
    if min.gap_mm.is_finite() {
        let tooth = TAU / mesh.teeth as f64;
        let foot = mesh.roller_gap(min.roller, &Pose::ideal(min.crank_rad), None)?;
        min.tooth_phase = foot.t.rem_euclid(tooth) / tooth;
    }
    Ok(min)
}

/// The curves of a sweep, \[roller\]\[angle\] and \[angle\]; the backlash columns are empty for
/// `Scope::Gaps`.
struct Columns {
    gap_mm: Vec<Vec<f64>>,
    forward_rad: Vec<f64>,
    reverse_rad: Vec<f64>,
}

/// One chunk's rows of the columns.
struct Rows<'a> {
    gap_mm: Vec<&'a mut [f64]>,
    /// Forward and reverse backlash, with `Scope::Backlash`.
    backlash: Option<(&'a mut [f64], &'a mut [f64])>,
}

impl Columns {
    fn new(rollers: usize, angles: usize, scope: Scope) -> Self {
        let backlash = if scope == Scope::Backlash { angles } else { 0 };
        Columns {
            gap_mm: vec![vec![0.0; angles]; rollers],
            forward_rad: vec![0.0; backlash],
            reverse_rad: vec![0.0; backlash],
        }
    }

    /// The rows of the chunks of `CHUNK` angles, in order.
    fn chunks(&mut self, angles: usize) -> Vec<Rows<'_>> {
        let mut gap_mm: Vec<_> = self
            .gap_mm
            .iter_mut()
            .map(|c| c.chunks_mut(CHUNK))
            .collect();
        let mut backlash = self
            .forward_rad
            .chunks_mut(CHUNK)
            .zip(self.reverse_rad.chunks_mut(CHUNK));
        (0..angles.div_ceil(CHUNK))
            .map(|_| Rows {
                // The next piece of every roller's column.
                gap_mm: gap_mm.iter_mut().filter_map(Iterator::next).collect(),
                backlash: backlash.next(),
            })
            .collect()
    }
}

/// A roller's gap at one lag, found in its locus frame.
#[derive(Debug, Clone, Copy)]
struct Found {
    gap_mm: f64,
    arm_mm: f64,
    /// The foot's offset s = t − t_ref in the frame.
    s: f64,
    /// The foot is proven the nearest point of Γ.
    nearest: bool,
}

/// What a roller carries from one crank angle to the next within a chunk.
#[derive(Debug, Clone, Copy, Default)]
struct Warm {
    /// The foot offset of the gap at β = 0.
    gap: Option<f64>,
    /// The closing lag and its foot offset.
    closing: Option<(f64, f64)>,
}

/// Roller i at one crank angle: its locus frame, the excess of the parts as built over the
/// locus form in the disc frame at β = 0 (`Mesh::centre_excess` turned by −ψ), and r' − its
/// radius (the gap is this plus its centre's distance from the locus).
#[derive(Clone, Copy)]
struct Seat {
    frame: LocusFrame,
    excess: Vec2,
    offset_mm: f64,
}

/// How close to the locus a foot must be to be proven the nearest point of Γ
/// (`Tracker::certified_mm`): 0.9 of the locus's reach and of r', less twice the form error's
/// largest |w| (the formed profile is within |w| of the offset curve, so a foot of it that
/// margin inside the reach is still the nearest).
pub fn certified_mm(profile: &Profile) -> f64 {
    0.9 * profile.locus_reach_bound_mm().min(profile.offset_mm) - 2.0 * profile.form().bound_mm()
}

/// The constants of a sweep of one mesh.
struct Tracker<'a> {
    mesh: &'a Mesh,
    /// Roller i's direction e^{i·2πi/np}.
    units: Vec<Vec2>,
    /// A foot of the normal from a roller centre closer to the locus than this is the nearest
    /// point of the locus (`Profile::locus_reach_bound_mm`, with a tenth off for its round-off)
    /// and, the centre then being outside the disc (this is also below r'), its offset is the
    /// nearest point of Γ: every point of the disc is at least r' from the outside of the
    /// locus, and at least r' − d from a point d inside it, distances the offset attains.
    certified_mm: f64,
    /// Where a roller's foot is sought at the start of a chunk, as an offset s = t − t_ref in
    /// its frame: `Mesh::foot_guess` at β = 0, the roller's own locus parameter t_ref turned
    /// back by the profile's rotation (reduced to within half a tooth pitch).
    first_s: f64,
    /// The radius extrema of the locus in turn (`Profile::arc_ends`).
    arc_ends: Vec<Vec2>,
    /// The largest moment arm of a foot (`Profile::arm_bound_mm`), the march's rate.
    arm_bound_mm: f64,
}

impl<'a> Tracker<'a> {
    fn new(mesh: &'a Mesh) -> Self {
        let profile = &mesh.profile;
        Tracker {
            mesh,
            units: (0..mesh.rollers).map(|i| mesh.roller_unit(i)).collect(),
            certified_mm: certified_mm(profile),
            first_s: wrap_pi(-profile.rotation_rad),
            arc_ends: profile.arc_ends(),
            arm_bound_mm: profile.arm_bound_mm(),
        }
    }

    /// Every chunk of `crank_rad`, in parallel; the first failure in crank order.
    fn sweep(
        &self,
        crank_rad: &[f64],
        scope: Scope,
        progress: &dyn Progress,
    ) -> Result<Columns, GapFailure> {
        let mut columns = Columns::new(self.mesh.rollers, crank_rad.len(), scope);
        let outcomes: Vec<Result<(), GapFailure>> = crank_rad
            .par_chunks(CHUNK)
            .zip(columns.chunks(crank_rad.len()))
            .map(|(crank, mut rows)| {
                let done = self.chunk(crank, &mut rows);
                progress.advance(crank.len() as u64);
                done
            })
            .collect();
        outcomes.into_iter().collect::<Result<(), _>>()?;
        Ok(columns)
    }

    /// One chunk, each roller followed from the angle before.
    fn chunk(&self, crank_rad: &[f64], rows: &mut Rows<'_>) -> Result<(), GapFailure> {
        let mesh = self.mesh;
        let (nc, np) = (mesh.teeth as f64, mesh.rollers as f64);
        let mut warm = vec![Warm::default(); mesh.rollers];
        let mut seated = Vec::with_capacity(mesh.rollers);
        for (k, &phi) in crank_rad.iter().enumerate() {
            seated.clear();
            // Roller i's frame: t_ref = 2πi/np + φ/nc, the roller centre e^{i·t_ref}·Rp −
            // e·e^{i·np·t_ref} at β = 0, with e^{i·np·t_ref} = e^{i·np·φ/nc} for every roller.
            let turn = phi / nc;
            let (st, ct) = turn.sin_cos();
            let (mut forward, mut reverse) = (f64::INFINITY, f64::INFINITY);
            let e_phi = unit(phi);
            for (i, w) in warm.iter_mut().enumerate() {
                let frame = LocusFrame {
                    t_ref: TAU * i as f64 / np + turn,
                    r_ref: mesh.roller_circle_radius_mm,
                    base: rotate(self.units[i], ct, st),
                    lobe: unit(np * turn),
                };
                // The parts as built, in the disc frame at β = 0 (ψ = −φ/nc).
                let excess = mesh.centre_excess(i, e_phi, Vec2::zeros());
                let frame = Seat {
                    frame,
                    excess: rotate(excess, ct, st),
                    offset_mm: mesh.profile.offset_mm - mesh.roller_radius(i),
                };
                let g = self.gap(i, phi, &frame, w.gap)?;
                w.gap = Some(g.s);
                rows.gap_mm[i][k] = g.gap_mm;
                if rows.backlash.is_none() {
                    continue;
                }
                w.closing = self.closing_lag(i, phi, &frame, &g, w.closing);
                match w.closing {
                    Some((b, _)) if g.arm_mm > 0.0 => forward = forward.min(b),
                    Some((b, _)) if g.arm_mm < 0.0 => reverse = reverse.min(-b),
                    _ => {}
                }
                seated.push((frame, g));
            }
            if let Some((f, r)) = &mut rows.backlash {
                self.other_ways(phi, &seated, &mut forward, &mut reverse);
                f[k] = forward;
                r[k] = reverse;
            }
        }
        Ok(())
    }

    /// Each roller the way its nearest flank at β = 0 opens (both ways when its arm is too small
    /// to close either), where it may close first on another part of the profile: the backlash
    /// each way lowered to such a closing lag (`closing_toward`), unless the roller is proven
    /// open up to it (`stays_open`). `seated` holds every roller's seat and gap at β = 0.
    fn other_ways(&self, phi: f64, seated: &[(Seat, Found)], forward: &mut f64, reverse: &mut f64) {
        let rp = self.mesh.roller_circle_radius_mm;
        let reach = PI / self.mesh.rollers as f64;
        for (i, (frame, g)) in seated.iter().enumerate() {
            for (sign, best) in [(1.0, &mut *forward), (-1.0, &mut *reverse)] {
                let limit = best.min(reach);
                if sign * g.arm_mm > 1e-9 * rp || self.stays_open(frame, g, sign, limit) {
                    continue;
                }
                if let Some(b) = self.closing_toward(i, phi, frame, g, sign, limit) {
                    *best = best.min(sign * b);
                }
            }
        }
    }

    /// Roller i's gap at β = 0, followed from the foot offset `warm` (at the start of a chunk
    /// from `first_s`, the roller's own parameter turned by the profile's rotation), or from
    /// scratch when it is not proven the nearest point.
    fn gap(
        &self,
        i: usize,
        phi: f64,
        frame: &Seat,
        warm: Option<f64>,
    ) -> Result<Found, GapFailure> {
        self.nearest(i, phi, frame, 0.0, warm.unwrap_or(self.first_s))
    }

    /// Roller i's gap at lag β from the nearest point of Γ: followed from the offset `s_start`,
    /// or from scratch when the foot followed is not proven the nearest point.
    fn nearest(
        &self,
        i: usize,
        phi: f64,
        frame: &Seat,
        lag_rad: f64,
        s_start: f64,
    ) -> Result<Found, GapFailure> {
        match self.follow(frame, lag_rad, s_start) {
            Ok(g) if g.nearest => Ok(g),
            _ => self.afresh(i, phi, frame, lag_rad),
        }
    }

    /// The gap at lag β from the closest point followed in `frame` from the offset `s_start`.
    fn follow(
        &self,
        frame: &Seat,
        lag_rad: f64,
        s_start: f64,
    ) -> Result<Found, ClosestPointFailure> {
        let mesh = self.mesh;
        // The roller centre in the disc frame: e^{−iβ}·(e^{i·t_ref}·Rp − e·e^{i·np·t_ref} + x),
        // x the parts' excess at β = 0 (`Seat::excess`).
        let (sb, cb) = sin_cos(lag_rad);
        let w = rotate(frame.excess, cb, -sb);
        let foot = mesh
            .profile
            .closest_point_in_frame(&frame.frame, lag_rad, w, s_start)?;
        let f = &frame.frame;
        let p = rotate(self.centre(frame), cb, -sb);
        Ok(Found {
            gap_mm: frame.offset_mm + foot.locus_distance_mm,
            arm_mm: cross(p, foot.normal),
            s: wrap_pi(foot.t - f.t_ref),
            nearest: foot.locus_distance_mm.abs() < self.certified_mm,
        })
    }

    /// The roller centre in the disc frame at β = 0: e^{i·t_ref}·Rp − e·e^{i·np·t_ref} + x.
    fn centre(&self, frame: &Seat) -> Vec2 {
        let f = &frame.frame;
        f.base * f.r_ref - f.lobe * self.mesh.eccentricity_mm + frame.excess
    }

    /// The gap at lag β from scratch (`Mesh::roller_gap`, with its scanning search).
    fn afresh(&self, i: usize, phi: f64, frame: &Seat, lag_rad: f64) -> Result<Found, GapFailure> {
        let g = self
            .mesh
            .roller_gap(i, &Pose::lagging(phi, lag_rad), None)?;
        Ok(Found {
            gap_mm: g.gap_mm,
            arm_mm: g.arm_mm,
            s: wrap_pi(g.t - frame.frame.t_ref),
            nearest: true,
        })
    }

    /// Roller i's closing lag and its foot offset: the Newton iteration of `Mesh::close_from`
    /// on gap(β) = 0, from the previous angle's closing lag when there is one, else from β = 0
    /// with the gap just found (whose first step is the first-order closing lag g/l).
    ///
    /// A roller whose arm at β = 0 is too small does not close (as in the cold iteration). A
    /// warm start that does not close the roller, or closes it on the other side of β = 0
    /// than g/l or with its arm turned over, is run again from β = 0: a roller closes, and
    /// where, as the cold-start iteration says.
    fn closing_lag(
        &self,
        i: usize,
        phi: f64,
        frame: &Seat,
        at_zero: &Found,
        warm: Option<(f64, f64)>,
    ) -> Option<(f64, f64)> {
        // The cold iteration's first test: an arm too small at β = 0 (a roller on the
        // centreline of a tooth or a tooth space) does not close, whatever a warm start finds.
        if at_zero.arm_mm.abs() < 1e-9 * self.mesh.roller_circle_radius_mm {
            return None;
        }
        if let Some((lag, s)) = warm {
            if let Ok(start) = self.follow(frame, lag, s) {
                if let Some((b, g)) = self.close(i, phi, frame, lag, start) {
                    let same_side = b * at_zero.gap_mm * at_zero.arm_mm >= 0.0;
                    if same_side && g.arm_mm * at_zero.arm_mm > 0.0 {
                        return Some((b, g.s));
                    }
                }
            }
        }
        self.close(i, phi, frame, 0.0, *at_zero)
            .map(|(b, g)| (b, g.s))
    }

    /// Roller i's closing lag the way `sign` turns the disc, below `limit` (rad), where its
    /// nearest flank at β = 0 opens (`Mesh::closing_lag_toward`): `march` to where the nearest
    /// flank closes, then Newton.
    fn closing_toward(
        &self,
        i: usize,
        phi: f64,
        frame: &Seat,
        at_zero: &Found,
        sign: f64,
        limit: f64,
    ) -> Option<f64> {
        // `Mesh::gap_rate_bound_mm`, its arm bound computed once.
        let rate = self.arm_bound_mm.min(self.centre(frame).norm());
        let rp = self.mesh.roller_circle_radius_mm;
        let gap_arm = |g: &Found| (g.gap_mm, g.arm_mm);
        let next = |lag, g: &Found| self.nearest(i, phi, frame, lag, g.s).ok();
        march(sign, rate, limit, rp, *at_zero, gap_arm, next)?.closing(sign, |lag, g| {
            self.close(i, phi, frame, lag, g).map(|(b, _)| b)
        })
    }

    /// Whether the roller, its nearest foot at β = 0 on an arc of the locus whose arm has the
    /// sign opposite to `sign`, is proven not to close the way `sign` turns the disc within
    /// `limit` (rad), without turning it.
    ///
    /// To close that way, the roller centre q must come within |r''| (the locus distance at
    /// which its gap is zero, `Seat::offset_mm`) of an arc whose arm has the sign of `sign`.
    /// From the foot's arc that takes passing one of its ends (`Profile::arc_ends`, those on
    /// either side of the foot's parameter t) or another arc: C meets a ball about q of radius below the reach of the locus in one arc,
    /// the one through the nearest foot (a second would hold a local minimum of the distance,
    /// which within the reach is the nearest point, Federer 1959, Thm 4.8 (12)). So such an
    /// arc is at least ρ = min(distance to the ends, the certified reach) from q, and q, turning
    /// on a circle of radius |p|, needs at least (ρ − |r''|)/|p| rad to come within |r''| of it.
    /// A form error breaks the offset form the arcs are read from: no proof then.
    fn stays_open(&self, frame: &Seat, at_zero: &Found, sign: f64, limit: f64) -> bool {
        if sign * at_zero.arm_mm >= 0.0 || self.mesh.profile.has_form() {
            return false;
        }
        // The gap's own bound first (`march`'s first step), without the arc's ends.
        if at_zero.gap_mm > self.arm_bound_mm * limit {
            return true;
        }
        let q = self.centre(frame);
        let ends = self.arc_ends.len();
        let t = frame.frame.t_ref + at_zero.s;
        let k = (t * (ends / 2) as f64 / PI).floor() as i64;
        let end = |k: i64| (q - self.arc_ends[k.rem_euclid(ends as i64) as usize]).norm();
        let rho = end(k).min(end(k + 1)).min(self.certified_mm);
        (rho - frame.offset_mm.abs()) / q.norm() > limit
    }

    /// Newton on gap(β) = 0 from lag β with gap g (`Mesh::close_from`): the closing lag and
    /// the gap found there, or `None` when the roller does not close within half a roller pitch.
    fn close(
        &self,
        i: usize,
        phi: f64,
        frame: &Seat,
        mut lag: f64,
        mut g: Found,
    ) -> Option<(f64, Found)> {
        let mesh = self.mesh;
        let rp = mesh.roller_circle_radius_mm;
        let reach = PI / mesh.rollers as f64;
        // The state two iterations back: a roller just past a tip or root, its small arm
        // pointing away from the flank it would close on, is thrown back and forth between two
        // lags by the clamped steps. Every step being a function of the state, a state seen
        // before repeats forever and the roller never closes: said at once instead of after
        // the 60 iterations of `Mesh::close_from`.
        let mut before = [(f64::NAN, f64::NAN); 2];
        for _ in 0..60 {
            if g.arm_mm.abs() < 1e-9 * rp {
                return None;
            }
            let step = (g.gap_mm / g.arm_mm).clamp(-0.1 * reach, 0.1 * reach);
            lag += step;
            if lag.abs() > reach {
                return None;
            }
            if before[0] == (lag, g.s) {
                return None;
            }
            before = [before[1], (lag, g.s)];
            g = self.follow(frame, lag, g.s).ok()?;
            let closed = g.gap_mm.abs() <= 32.0 * f64::EPSILON * rp;
            if closed || step.abs() <= 1e-15 + 1e-12 * lag.abs() {
                // A foot not proven the nearest point: if another part of the profile is nearer
                // at this lag, the roller has not closed (`Mesh::close_from`).
                if !g.nearest {
                    if let Ok(fresh) = mesh.roller_gap(i, &Pose::lagging(phi, lag), None) {
                        if fresh.gap_mm < g.gap_mm - 1e-12 * rp {
                            return None;
                        }
                    }
                }
                return Some((lag, g));
            }
        }
        None
    }
}
