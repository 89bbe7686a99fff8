//! Pareto dominance over objectives to minimise (a maximised objective enters negated).

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

/// Indices of the non-dominated points of `points`, in their order; of several points with the
/// same objectives only the first is kept (none dominates another, and the front lists each
/// trade once).
pub fn front(points: &[&[f64]]) -> Vec<usize> {
    (0..points.len())
        .filter(|&i| {
            !points
                .iter()
                .enumerate()
                .any(|(j, p)| dominates(p, points[i]) || (j < i && p.iter().eq(points[i].iter())))
        })
        .collect()
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
}
