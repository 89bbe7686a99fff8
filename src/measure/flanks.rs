//! Per-flank deviation summaries of a measured disc, as a gear inspection sheet gives them:
//! the profile form deviation f_f, the profile slope deviation f_H and the total profile
//! deviation F of every measured flank, over the arc length along the profile in mm.
//!
//! Definitions after ISO 1328-1:2013 §3.3 (f_fα, f_Hα, F_α) and ISO/TR 10064-1 §5 (how
//! they are evaluated), adapted to a cycloid flank:
//! - the abscissa. An involute's profile deviations are plotted over the roll length (the
//!   developed length of the base-circle tangent, proportional to the roll angle); a cycloid
//!   flank has no base circle, and its analogue is the arc length s along the profile, mm,
//!   measured from the flank's root towards its tip. It is taken on the identified modified
//!   profile Γ without form error (the reference the deviations are measured from):
//!   s(t) = ∫ |Γ'(τ)| dτ from the root, by Gauss–Legendre quadrature (`arc_length_mm`);
//! - the deviation d of a point is its normal distance from Γ, mm, positive where material is
//!   missing (this tool's sign throughout; an inspection chart plots plus material upwards);
//! - the mean line is the least-squares line of d over s (the standard's "mean profile line"
//!   for an unmodified design profile: the design trace here is Γ itself, d = 0);
//! - F = max d − min d, the range of the deviations themselves (the distance between two
//!   copies of the design trace enclosing the measured trace);
//! - f_f = the range of d about the mean line (two copies of the mean line enclosing it); it
//!   can exceed F when the mean line tilts against the trace's extremes (both are ranges,
//!   about different lines);
//! - f_H = the rise of the mean line from the root-most to the tip-most measured point:
//!   positive when material missing grows towards the tip.
//!
//! The evaluation range. ISO evaluates over the range L_α that excludes the tip break (about
//! 92 % of the active length); this profile model has no tip break or root fillet, and the
//! points may cover part of a flank only, so every summary is over the flank's measured extent
//! [s_from, s_to], which is reported beside it. Two flanks summarised over different extents
//! are not comparable value for value: f_H in particular scales with the extent.
//!
//! Flanks: tooth i spans t ∈ [2πi/nc, 2π(i+1)/nc], root at both ends and tip at its middle;
//! flank `a` runs root to tip with increasing t, flank `b` tip to the next root.

use super::fitted::{FittedPoint, FormError};
use crate::geometry::profile::Profile;
use std::f64::consts::{PI, TAU};

/// One flank of one tooth: the deviation of its points from the identified modified profile
/// (form error plus residual), summarised over arc length. Lengths and deviations in mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flank {
    /// Tooth i spans t ∈ [2πi/nc, 2π(i+1)/nc]: root, tip at its middle, root.
    pub tooth: usize,
    /// `a`: root to tip with increasing t; `b`: tip to the next root.
    pub side: char,
    pub points: usize,
    /// The summaries; None with fewer than 3 points or without extent.
    pub summary: Option<FlankSummary>,
}

/// A flank's summaries over its measured extent, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlankSummary {
    /// Arc length along the profile from the flank's root to its root-most and its tip-most
    /// measured point, mm.
    pub from_mm: f64,
    pub to_mm: f64,
    /// Total deviation F: max d − min d.
    pub total_mm: f64,
    /// Form deviation f_f: range of d about its least-squares line over s.
    pub form_mm: f64,
    /// Slope deviation f_H: rise of that line from `from_mm` to `to_mm` (positive: more
    /// material missing towards the tip).
    pub slope_mm: f64,
}

/// The flank of a locus parameter: (tooth, side 0 for `a`, 1 for `b`).
pub fn flank_of(t: f64, teeth: usize) -> (usize, usize) {
    let half = PI / teeth as f64;
    let k = ((t.rem_euclid(TAU) / half).floor() as usize).min(2 * teeth - 1);
    (k / 2, k % 2)
}

/// The locus parameter of the root of flank (tooth, side), rad: the start of `a`, the end of
/// `b`.
fn root_of(tooth: usize, side: usize, teeth: usize) -> f64 {
    TAU * (tooth + side) as f64 / teeth as f64
}

/// Every flank of the disc (2·nc, tooth by tooth, `a` before `b`), summarised from the fitted
/// profile points: their deviation from `reference` (the identified modified profile without
/// form error) is w(t) plus the residual.
pub fn flanks(
    reference: &Profile,
    profile: &[FittedPoint],
    form: &FormError,
    teeth: usize,
) -> Vec<Flank> {
    let mut groups: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 2 * teeth];
    for p in profile {
        let (tooth, side) = flank_of(p.t, teeth);
        let deviation = form.value_mm(p.t) + p.residual_mm;
        groups[2 * tooth + side].push((p.t.rem_euclid(TAU), deviation));
    }
    groups
        .iter_mut()
        .enumerate()
        .map(|(g, pts)| {
            let (tooth, side) = (g / 2, g % 2);
            let along = arc_from_root(reference, pts, root_of(tooth, side, teeth));
            Flank {
                tooth,
                side: if side == 0 { 'a' } else { 'b' },
                points: pts.len(),
                summary: summarise(&along),
            }
        })
        .collect()
}

/// (s, d) of a flank's (t, d), s the arc length from the root at `root` (the points sorted
/// from the root outwards): each s the previous one plus the arc between the two points, so
/// the quadrature covers the flank once however many points there are.
fn arc_from_root(reference: &Profile, pts: &mut [(f64, f64)], root: f64) -> Vec<(f64, f64)> {
    pts.sort_by(|a, b| (a.0 - root).abs().total_cmp(&(b.0 - root).abs()));
    let mut last = (root, 0.0);
    pts.iter()
        .map(|&(t, d)| {
            let s = last.1 + arc_length_mm(reference, last.0, t).abs();
            last = (t, s);
            (s, d)
        })
        .collect()
}

/// The summaries of a flank's (s, d), s ascending; None below 3 points or without extent.
pub fn summarise(pts: &[(f64, f64)]) -> Option<FlankSummary> {
    if pts.len() < 3 {
        return None;
    }
    let (from, to) = (pts[0].0, pts[pts.len() - 1].0);
    let n = pts.len() as f64;
    let ms = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let md = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sss: f64 = pts.iter().map(|p| (p.0 - ms).powi(2)).sum();
    if sss <= 0.0 || to <= from {
        return None;
    }
    let slope = pts.iter().map(|p| (p.0 - ms) * (p.1 - md)).sum::<f64>() / sss;
    let range = |f: &dyn Fn(&(f64, f64)) -> f64| {
        let (lo, hi) = crate::numeric::extent(pts.iter().map(f));
        hi - lo
    };
    Some(FlankSummary {
        from_mm: from,
        to_mm: to,
        total_mm: range(&|p| p.1),
        form_mm: range(&|p| p.1 - md - slope * (p.0 - ms)),
        slope_mm: slope * (to - from),
    })
}

/// Gauss–Legendre nodes and weights on [−1, 1], 5 points (exact for polynomials of degree 9;
/// Abramowitz & Stegun 25.4.29).
const GAUSS_5: [(f64, f64); 5] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// Panels per flank of the composite rule. |Γ'| changes fastest near the root (on the paper's
/// disc from 19 to 63 mm/rad over a flank): against a 2000-panel reference the 5-point rule
/// on 1/16 of a flank is off by up to 5e-10 mm over a third of a flank, on 1/32 by < 1e-13 mm
/// (`tests/it/flanks.rs` checks 1e-12 mm against an extrapolated polyline).
const PANELS_PER_FLANK: f64 = 32.0;

/// Arc length of `profile` from t0 to t1 (negative when t1 < t0), mm: ∫ |Γ'(t)| dt by the
/// composite 5-point Gauss–Legendre rule on equal panels of at most 1/32 of a flank in t
/// (|Γ'| = |C'|·(1 − r'κ_C) is smooth on a regular profile: no cusp, no undercut). Between
/// neighbouring measured points it is one panel: five evaluations of Γ'.
pub fn arc_length_mm(profile: &Profile, t0: f64, t1: f64) -> f64 {
    let flank = PI / (profile.rollers - 1).max(1) as f64;
    let panels = ((t1 - t0).abs() / flank * PANELS_PER_FLANK).ceil().max(1.0);
    let h = (t1 - t0) / panels;
    (0..panels as usize)
        .map(|k| {
            let mid = t0 + h * (k as f64 + 0.5);
            GAUSS_5
                .iter()
                .map(|(x, w)| w * profile.speed(mid + 0.5 * h * x))
                .sum::<f64>()
                * 0.5
                * h
        })
        .sum()
}
