//! The form error of a disc as built, w(t) along the profile normal (MODEL.md "Measured
//! profiles"): its Fourier series, and the piecewise quintic table the profile evaluates.
//!
//! Every closest point on a formed profile needs w, w′ and w″ two or three times, and summing
//! the harmonics each time would dominate an as-built clearance sweep. The table holds, on N
//! equal intervals of the period, the quintic Hermite interpolant of w from the series' exact
//! w, w′, w″ at the nodes; N is chosen from the interpolant's error bound so that the table is
//! the series to a picometre (`TABLE_ERROR_MM`).

use super::cos_sin_of_orders;
use crate::model::FormTerm;
use std::f64::consts::TAU;

/// The largest |w − table| the table may have, mm (a picometre: a thousandth of the
/// nanometre the clearance is verified to, and about the round-off of a point at Rp ≈ 50 mm).
pub const TABLE_ERROR_MM: f64 = 1e-12;

/// The fewest and most intervals of a table.
const MIN_INTERVALS: usize = 64;
const MAX_INTERVALS: usize = 1 << 22;

/// w(t) = w0 + Σ_k (a_k·cos kt + b_k·sin kt), mm, t the locus parameter (period 2π).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FormError {
    /// (a_k, b_k) of every order k from 1 to the highest, zeros where there is no term.
    dense: Vec<(f64, f64)>,
    /// w0, the order-0 cosine, apart from the table.
    constant_mm: f64,
    /// Per interval i of [ih, (i+1)h], the coefficients c0..c5 of the quintic in
    /// s = t/h − i ∈ [0, 1] (empty without harmonics).
    table: Vec<[f64; 6]>,
    /// 1/h = N/2π.
    per_rad: f64,
}

impl FormError {
    pub fn new(form: &[FormTerm]) -> Self {
        let highest = form.iter().map(|f| f.order).max().unwrap_or(0);
        let mut dense = vec![(0.0, 0.0); highest];
        let mut constant_mm = 0.0;
        for f in form {
            match f.order {
                0 => constant_mm += f.cos_mm,
                k => {
                    dense[k - 1].0 += f.cos_mm;
                    dense[k - 1].1 += f.sin_mm;
                }
            }
        }
        let mut w = FormError {
            dense,
            constant_mm,
            table: Vec::new(),
            per_rad: 0.0,
        };
        w.table = w.build_table();
        w
    }

    /// Whether there is any form error.
    pub fn is_some(&self) -> bool {
        !self.dense.is_empty() || self.constant_mm != 0.0
    }

    /// w(t), w′(t), w″(t) from the table: mm, mm/rad, mm/rad². Within `TABLE_ERROR_MM` of
    /// the series in w (`table_error_bound_mm`); w′ and w″ are the interpolant's own, so the
    /// profile stays one smooth (C²) curve whose feet and curvature agree with its points.
    #[inline]
    pub fn jet(&self, t: f64) -> (f64, f64, f64) {
        if self.table.is_empty() {
            return (self.constant_mm, 0.0, 0.0);
        }
        let n = self.table.len();
        let x = super::wrap_tau(t) * self.per_rad;
        let i = (x as usize).min(n - 1);
        let s = x - i as f64;
        let [w, d1, d2] = quintic_at(self.table[i], s);
        let h = self.per_rad;
        (self.constant_mm + w, d1 * h, d2 * h * h)
    }

    /// w, w′, w″ summed from the series: the harmonics cos(kt), sin(kt) by powers of e^{it}
    /// ([`geometry::cos_sin_of_orders`](crate::geometry::cos_sin_of_orders): one sine and cosine per call; rounding grows as k·ε).
    pub fn series_jet(&self, t: f64) -> (f64, f64, f64) {
        let harmonics = cos_sin_of_orders(t, 1..=self.dense.len());
        let (mut w, mut d1, mut d2) = (self.constant_mm, 0.0, 0.0);
        for (k, (&(a, b), (c, s))) in self.dense.iter().zip(harmonics).enumerate() {
            let k = (k + 1) as f64;
            let v = a * c + b * s;
            w += v;
            d1 += k * (b * c - a * s);
            d2 -= k * k * v;
        }
        (w, d1, d2)
    }

    /// The bound on |w − table|: quintic Hermite interpolation on intervals of h errs by at
    /// most max|w⁽⁶⁾|·max|(x−a)³(x−b)³|/6! = max|w⁽⁶⁾|·h⁶/(64·720) (the Hermite remainder,
    /// e.g. Burden & Faires, Numerical Analysis, Thm 3.9), with max|w⁽⁶⁾| ≤ Σ k⁶·|c_k|.
    pub fn table_error_bound_mm(&self) -> f64 {
        if self.table.is_empty() {
            return 0.0;
        }
        hermite_bound(self.sixth_derivative_bound(), TAU / self.table.len() as f64)
    }

    /// The intervals of the table: N on [0, 2π).
    pub fn table_intervals(&self) -> usize {
        self.table.len()
    }

    /// The largest |w″| the form error can reach, mm/rad²: Σ k²·amplitude.
    pub fn bend_bound(&self) -> f64 {
        self.amplitudes().map(|(k, a)| k * k * a).sum()
    }

    /// The largest |w′| the form error can reach, mm/rad: Σ k·amplitude.
    pub fn slope_bound(&self) -> f64 {
        self.amplitudes().map(|(k, a)| k * a).sum()
    }

    /// The largest |w| the form error can reach, mm: Σ amplitude.
    pub fn bound_mm(&self) -> f64 {
        self.constant_mm.abs() + self.amplitudes().map(|(_, a)| a).sum::<f64>()
    }

    fn sixth_derivative_bound(&self) -> f64 {
        self.amplitudes().map(|(k, a)| k.powi(6) * a).sum()
    }

    /// (order, amplitude) of every harmonic from order 1.
    fn amplitudes(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        (self.dense.iter().enumerate()).map(|(i, (a, b))| ((i + 1) as f64, a.hypot(*b)))
    }

    /// The table: the fewest intervals, a power of two, whose bound meets `TABLE_ERROR_MM`.
    fn build_table(&mut self) -> Vec<[f64; 6]> {
        let m6 = self.sixth_derivative_bound();
        if m6 == 0.0 {
            return Vec::new();
        }
        let mut n = MIN_INTERVALS;
        while n < MAX_INTERVALS && hermite_bound(m6, TAU / n as f64) > TABLE_ERROR_MM {
            n *= 2;
        }
        let h = TAU / n as f64;
        self.per_rad = n as f64 / TAU;
        let constant = self.constant_mm;
        // The nodes' w (less the constant), h·w′ and h²·w″: the derivatives in s.
        let node = |i: usize| {
            let (w, d1, d2) = self.series_jet(TAU * i as f64 / n as f64);
            [w - constant, h * d1, h * h * d2]
        };
        let mut left = node(0);
        (0..n)
            .map(|i| {
                let right = if i + 1 == n { node(0) } else { node(i + 1) };
                let c = quintic(left, right);
                left = right;
                c
            })
            .collect()
    }
}

/// max|w⁽⁶⁾|·h⁶/46080, the quintic Hermite remainder on an interval of h.
fn hermite_bound(m6: f64, h: f64) -> f64 {
    m6 * h.powi(6) / 46080.0
}

/// The coefficients c0..c5 of the quintic on s ∈ [0, 1] with value, first and second
/// derivative [p, m, a] at s = 0 (`l`) and s = 1 (`r`).
fn quintic(l: [f64; 3], r: [f64; 3]) -> [f64; 6] {
    let ([p0, m0, a0], [p1, m1, a1]) = (l, r);
    let dp = p1 - p0;
    [
        p0,
        m0,
        0.5 * a0,
        10.0 * dp - 6.0 * m0 - 4.0 * m1 - 1.5 * a0 + 0.5 * a1,
        -15.0 * dp + 8.0 * m0 + 7.0 * m1 + 1.5 * a0 - a1,
        6.0 * dp - 3.0 * m0 - 3.0 * m1 - 0.5 * a0 + 0.5 * a1,
    ]
}

/// The quintic of coefficients c0..c5 at s and its first two derivatives in s, by Horner.
#[inline]
fn quintic_at([c0, c1, c2, c3, c4, c5]: [f64; 6], s: f64) -> [f64; 3] {
    [
        c0 + s * (c1 + s * (c2 + s * (c3 + s * (c4 + s * c5)))),
        c1 + s * (2.0 * c2 + s * (3.0 * c3 + s * (4.0 * c4 + s * 5.0 * c5))),
        2.0 * c2 + s * (6.0 * c3 + s * (12.0 * c4 + s * 20.0 * c5)),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quintic meets its six conditions: values, slopes and second derivatives at both
    /// ends (exact arithmetic on small integers; 1e-12 covers the rounding of the sums).
    #[test]
    fn the_quintic_meets_its_end_conditions() {
        let (l, r) = ([1.0, -2.0, 3.0], [-0.5, 4.0, -7.0]);
        let c = quintic(l, r);
        for (got, want) in [(quintic_at(c, 0.0), l), (quintic_at(c, 1.0), r)] {
            for j in 0..3 {
                assert!((got[j] - want[j]).abs() < 1e-12, "{got:?} vs {want:?}");
            }
        }
    }
}
