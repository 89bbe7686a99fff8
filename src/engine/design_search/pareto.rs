//! Pareto dominance over objectives to minimise (a maximised objective enters negated).

/// Objectives this close, relative to their size, are equal for the front: a difference
/// within it is the round-off of the solves (1e-8 relative and less on the shipped
/// requirements), not a trade a designer could use.
pub const EQUAL_WITHIN: f64 = 1e-6;

/// `a` dominates `b`: no worse in every objective and better in one.
pub fn dominates(a: &[f64], b: &[f64]) -> bool {
    let mut better = false;
    for (x, y) in a.iter().zip(b) {
        if x > y {
            return false;
        }
        better |= x < y;
    }
    better
}

/// `a` dominates `b` within `EQUAL_WITHIN`: no worse in every objective beyond round-off
/// (x ≤ y + EQUAL_WITHIN·max(|x|, |y|)) and better beyond it in one. Two designs equal
/// within it in every objective dominate neither the other.
pub fn dominates_within(a: &[f64], b: &[f64]) -> bool {
    let mut better = false;
    for (&x, &y) in a.iter().zip(b) {
        let tolerance = EQUAL_WITHIN * x.abs().max(y.abs());
        if x > y + tolerance {
            return false;
        }
        better |= x < y - tolerance;
    }
    better
}

/// Indices of the front of `points`, in their order: the points no other point dominates,
/// exactly or within `EQUAL_WITHIN` (so that a design better than another only by round-off
/// in one objective and worse in another does not pass for a trade); of several points with
/// the same objectives only the first is kept (none dominates another, and the front lists
/// each trade once). When dominance within round-off goes round in a circle (three or more
/// objectives) and would leave no point, the exact front is kept.
pub fn front(points: &[&[f64]]) -> Vec<usize> {
    let exact: Vec<usize> = (0..points.len())
        .filter(|&i| {
            !points
                .iter()
                .enumerate()
                .any(|(j, p)| dominates(p, points[i]) || (j < i && p.iter().eq(points[i].iter())))
        })
        .collect();
    let within: Vec<usize> = (exact.iter().copied())
        .filter(|&i| {
            !exact
                .iter()
                .any(|&j| dominates_within(points[j], points[i]))
        })
        .collect();
    if within.is_empty() {
        exact
    } else {
        within
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn front_keeps_the_trades() {
        // (1, 3), (2, 2), (3, 1) trade; (3, 3) is dominated by (2, 2); the repeat of (1, 3) goes.
        let p: Vec<&[f64]> = vec![
            &[1.0, 3.0],
            &[3.0, 3.0],
            &[2.0, 2.0],
            &[3.0, 1.0],
            &[1.0, 3.0],
        ];
        assert_eq!(front(&p), vec![0, 2, 3]);
        assert!(dominates(&[1.0, 1.0], &[1.0, 2.0]));
        assert!(!dominates(&[1.0, 2.0], &[1.0, 2.0]));
    }

    /// The pair: a contact pressure lower by 4.7e-8 relative (round-off) and 1.4 g
    /// heavier is not a trade; the lighter design dominates within round-off, the heavier one
    /// leaves the front. A pressure lower by 1e-5 relative is a trade and both stay.
    #[test]
    fn round_off_is_no_trade() {
        let light = [1.0, 1221.0733351];
        let heavy = [1.0014, 1221.073277816332];
        assert!(dominates_within(&light, &heavy));
        assert!(!dominates_within(&heavy, &light));
        assert_eq!(front(&[&heavy, &light]), vec![1]);
        let lower = [1.0014, 1221.0733351 * (1.0 - 1e-5)];
        assert_eq!(front(&[&lower, &light]), vec![0, 1]);
    }
}
