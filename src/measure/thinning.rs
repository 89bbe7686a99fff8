//! Thinning a scan denser than the fit can hold: every k-th profile point along the file's
//! order, k the smallest that brings the Jacobian (points × unknowns) within its bound
//! (`fit::MAX_JACOBIAN_ENTRIES`). Hole points are all kept: they alone fix the rotation
//! modification and the hole radius, a file holds few of them (72 per DXF circle), and a k
//! chosen for a dense profile could leave a hole with none.

use super::{Feature, MeasuredPoint};

/// How a profile was thinned: every `every`-th of `of` profile points, `used` of them kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Thinning {
    pub every: usize,
    pub of: usize,
    pub used: usize,
}

/// The thinning that fits `profile` and `holes` points of `unknowns` each into `max_entries`
/// Jacobian entries: k = ⌈P / room⌉ with room = ⌊max / n⌋ − H the profile points that fit
/// (then ⌈P/k⌉ ≤ room, and k − 1 would keep more than room). `None` when every point fits,
/// or when fewer than `unknowns` + 1 profile points would fit (the fit refuses such a file).
pub fn needed(
    profile: usize,
    holes: usize,
    unknowns: usize,
    max_entries: usize,
) -> Option<Thinning> {
    let room = (max_entries / unknowns.max(1)).saturating_sub(holes);
    if profile <= room || room <= unknowns {
        return None;
    }
    let every = profile.div_ceil(room);
    Some(Thinning {
        every,
        of: profile,
        used: profile.div_ceil(every),
    })
}

/// The points with every `every`-th profile point kept (the 1st, (k+1)th, …, counted along
/// the file's order among the profile points) and every hole point.
pub fn thin(points: &[MeasuredPoint], every: usize) -> Vec<MeasuredPoint> {
    let mut k = 0;
    points
        .iter()
        .filter(|p| {
            if p.feature != Feature::Profile {
                return true;
            }
            k += 1;
            (k - 1) % every == 0
        })
        .copied()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vec2;

    /// k is the smallest that fits: 2^20 + 3 points of 25 unknowns in 2^24 entries hold
    /// 671,088 points; k = 2 keeps 524,290, k = 1 would keep them all.
    #[test]
    fn the_smallest_k_that_fits() {
        let t = needed((1 << 20) + 3, 0, 25, 1 << 24).unwrap();
        assert_eq!((t.every, t.used), (2, (1 << 19) + 2));
        assert!(t.used * 25 <= 1 << 24);
        assert_eq!(needed(671_088, 0, 25, 1 << 24), None);
        // Holes take their room first: 10 hole points leave 671,078 for the profile.
        assert_eq!(needed(671_079, 10, 25, 1 << 24).map(|t| t.every), Some(2));
    }

    /// Hole points are all kept, profile points every k-th in the file's order.
    #[test]
    fn holes_are_kept_and_the_profile_thinned_in_order() {
        let point = |line, feature| MeasuredPoint {
            point: Vec2::new(line as f64, 0.0),
            feature,
            line,
        };
        let points: Vec<MeasuredPoint> = (0..10)
            .map(|i| {
                point(
                    i,
                    if i % 4 == 3 {
                        Feature::Hole(0)
                    } else {
                        Feature::Profile
                    },
                )
            })
            .collect();
        let lines: Vec<usize> = thin(&points, 3).iter().map(|p| p.line).collect();
        // Profile lines 0 1 2 4 5 6 8 9: the 1st, 4th and 7th kept (0, 4, 8); holes 3 and 7.
        assert_eq!(lines, vec![0, 3, 4, 7, 8]);
    }
}
