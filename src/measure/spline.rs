//! B-splines of a DXF drawing (SPLINE entities): degree p, knots u_0..u_m, control points P_i
//! with weights w_i (all 1 unless rational), evaluated by de Boor's algorithm in homogeneous
//! coordinates (Piegl & Tiller, "The NURBS Book", 2nd ed., A4.1 with A2.1 for the knot span):
//! C(u) = Σ N_i,p(u)·w_i·P_i / Σ N_i,p(u)·w_i on the domain [u_p, u_{m−p}].

use crate::geometry::Vec2;

/// A (possibly rational) B-spline curve in the plane.
#[derive(Debug, Clone, PartialEq)]
pub struct Spline {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub control: Vec<Vec2>,
    /// One per control point; all 1 for a non-rational spline.
    pub weights: Vec<f64>,
}

impl Spline {
    /// Why these numbers are no B-spline, if they are not: m + 1 = n + p + 2 knots for n + 1
    /// control points of degree p ≥ 1, knots non-decreasing, a domain of positive length,
    /// positive weights.
    pub fn problem(&self) -> Option<String> {
        let (p, n) = (self.degree, self.control.len());
        if p == 0 || n <= p {
            return Some(format!(
                "a spline of degree {p} needs more than {p} control points, it has {n}"
            ));
        }
        if self.knots.len() != n + p + 1 {
            return Some(format!(
                "{} knots for {n} control points of degree {p}: a B-spline has {}",
                self.knots.len(),
                n + p + 1
            ));
        }
        if self.knots.windows(2).any(|k| k[1] < k[0]) {
            return Some("its knots decrease".into());
        }
        if self.knots[n] <= self.knots[p] {
            return Some("its parameter domain is empty".into());
        }
        if self.weights.len() != n || !self.weights.iter().all(|w| *w > 0.0) {
            return Some("its weights are not one positive number per control point".into());
        }
        None
    }

    /// The parameter domain [u_p, u_n] (n + 1 = control points).
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.control.len()])
    }

    /// C(u), u clamped to the domain.
    pub fn point(&self, u: f64) -> Vec2 {
        let p = self.degree;
        let (lo, hi) = self.domain();
        let u = u.clamp(lo, hi);
        let k = self.span(u);
        // de Boor on (w·x, w·y, w).
        let mut d: Vec<[f64; 3]> = (0..=p)
            .map(|j| {
                let i = j + k - p;
                let w = self.weights[i];
                [w * self.control[i].x, w * self.control[i].y, w]
            })
            .collect();
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = j + k - p;
                let span = self.knots[i + p + 1 - r] - self.knots[i];
                let a = if span > 0.0 {
                    (u - self.knots[i]) / span
                } else {
                    0.0
                };
                let before = d[j - 1];
                for (x, b) in d[j].iter_mut().zip(before) {
                    *x = (1.0 - a) * b + a * *x;
                }
            }
        }
        Vec2::new(d[p][0] / d[p][2], d[p][1] / d[p][2])
    }

    /// The knot span k of u in the domain: u_k ≤ u < u_{k+1}, the last non-empty span at the
    /// domain's end (A2.1). By bisection of the non-decreasing knots u_{p+1} .. u_{n−1}: log n
    /// steps, where a walk from u_p costs n per point, n² for a curve sampled along it.
    fn span(&self, u: f64) -> usize {
        let (p, n) = (self.degree, self.control.len());
        p + self.knots[p + 1..n].partition_point(|&knot| knot <= u)
    }

    /// `count` points at equal steps of the parameter over the domain, the end left out (a
    /// closed curve's end is its start).
    pub fn sample(&self, count: usize) -> Vec<Vec2> {
        let (lo, hi) = self.domain();
        (0..count)
            .map(|k| self.point(lo + (hi - lo) * k as f64 / count as f64))
            .collect()
    }

    /// Whether the curve ends where it starts (to 1e-9 of its control polygon's size).
    pub fn is_closed(&self) -> bool {
        let (lo, hi) = self.domain();
        let size = self
            .control
            .iter()
            .map(|c| c.norm())
            .fold(0.0, f64::max)
            .max(1.0);
        (self.point(lo) - self.point(hi)).norm() <= 1e-9 * size
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The full circle as a rational quadratic B-spline (The NURBS Book, Ex. 7.2: nine control
    /// points on the square around it, weights 1 at the corners' neighbours and √2/2 at the
    /// corners, double interior knots): every point is on the circle to rounding (1e-12 of
    /// its radius), and the curve is closed. A non-rational evaluation (weights ignored) is
    /// off by up to 7 % of the radius.
    #[test]
    fn a_rational_quadratic_spline_is_the_circle() {
        let (r, c) = (7.5, Vec2::new(3.0, -2.0));
        let square = [
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (-1.0, 1.0),
            (-1.0, 0.0),
            (-1.0, -1.0),
            (0.0, -1.0),
            (1.0, -1.0),
            (1.0, 0.0),
        ];
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let spline = Spline {
            degree: 2,
            knots: vec![
                0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
            ],
            control: square
                .iter()
                .map(|&(x, y)| c + Vec2::new(x, y) * r)
                .collect(),
            weights: (0..9).map(|i| if i % 2 == 1 { h } else { 1.0 }).collect(),
        };
        assert_eq!(spline.problem(), None);
        assert!(spline.is_closed());
        for p in spline.sample(1000) {
            assert!(((p - c).norm() - r).abs() < 1e-12 * r, "{p}");
        }
    }

    /// The span by bisection is the one a walk from u_p finds (the first k with u_{k+1} > u,
    /// at most n − 1), on knots with repeats inside and at both clamped ends, at every knot,
    /// between knots and at the domain's ends.
    #[test]
    fn the_span_is_the_walks() {
        let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.5, 3.0, 3.0, 3.0, 4.0, 4.0, 4.0];
        let n = knots.len() - 3;
        let spline = Spline {
            degree: 2,
            knots: knots.clone(),
            control: vec![Vec2::zeros(); n],
            weights: vec![1.0; n],
        };
        let walk = |u: f64| {
            let mut k = 2;
            while k + 1 < n && knots[k + 1] <= u {
                k += 1;
            }
            k
        };
        for i in 0..=80 {
            let u = 4.0 * i as f64 / 80.0;
            assert_eq!(spline.span(u), walk(u), "u = {u}");
        }
    }

    /// Degree 1 is the control polygon: the point at a knot is its control point, and halfway
    /// between two knots the midpoint.
    #[test]
    fn degree_one_is_the_polygon() {
        let control = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 4.0),
        ];
        let spline = Spline {
            degree: 1,
            knots: vec![0.0, 0.0, 1.0, 2.0, 2.0],
            control: control.clone(),
            weights: vec![1.0; 3],
        };
        assert_eq!(spline.point(1.0), control[1]);
        assert_eq!(spline.point(1.5), Vec2::new(2.0, 2.0));
        assert_eq!(spline.point(2.0), control[2]);
    }
}
