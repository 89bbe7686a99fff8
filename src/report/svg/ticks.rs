//! Axis ticks at round values: 1, 2, 2.5 or 5 × 10^k on a linear axis, decades (then 1-2-5,
//! then every digit) on a logarithmic one.

/// Ticks covering [lo, hi] and how to label them.
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    pub lo: f64,
    pub hi: f64,
    pub step: f64,
    pub values: Vec<f64>,
    pub decimals: usize,
}

/// Nice ticks for the range [lo, hi], about `target` of them. With `expand` the range grows
/// to the outer ticks; otherwise it stays and only inner ticks are kept.
pub fn ticks(mut lo: f64, mut hi: f64, target: usize, expand: bool) -> Ticks {
    if !(lo.is_finite() && hi.is_finite()) {
        (lo, hi) = (0.0, 1.0);
    }
    if hi - lo <= f64::EPSILON * lo.abs().max(hi.abs()).max(1e-300) * 16.0 {
        // A flat curve: open a band around it.
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.05 };
        lo -= pad;
        hi += pad;
    }
    let raw = (hi - lo) / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let (a, b) = (lo / step, hi / step);
    let (first, last) = if expand {
        (a.floor() * step, b.ceil() * step)
    } else {
        ((a - 1e-9).ceil() * step, (b + 1e-9).floor() * step)
    };
    let (lo, hi) = if expand { (first, last) } else { (lo, hi) };
    stepped(lo, hi, step, first, last)
}

/// Ticks of [lo, hi] at first, first + step, ... up to last (a value within 1e-9 steps of
/// zero is zero), labelled with the decimals the step needs.
fn stepped(lo: f64, hi: f64, step: f64, first: f64, last: f64) -> Ticks {
    let n = ((last - first) / step + 1e-9).floor() as i64;
    let values = (0..=n.max(0))
        .map(|k| first + k as f64 * step)
        .map(|v| if v.abs() < step * 1e-9 { 0.0 } else { v })
        .collect();
    Ticks {
        lo,
        hi,
        step,
        values,
        decimals: decimals(step),
    }
}

/// Decimals that show every multiple of `step` exactly (2.5 needs one more than 2).
fn decimals(step: f64) -> usize {
    let d = (-step.log10().floor()).max(0.0) as usize;
    let scaled = step * 10f64.powi(d as i32);
    d + usize::from((scaled - scaled.round()).abs() > 1e-6)
}

/// Ticks every `step` (e.g. 6° over a 36° mesh period) inside [lo, hi].
pub fn every(lo: f64, hi: f64, step: f64) -> Ticks {
    stepped(lo, hi, step, (lo / step - 1e-9).ceil() * step, hi)
}

impl Ticks {
    /// A tick's label: its decimals, a true minus sign, never "−0".
    pub fn label(&self, v: f64) -> String {
        crate::numeric::fixed(v, self.decimals).replace('-', "−")
    }

    /// Grow the range by one step at an end that `v` (a limit) would sit on, so that a line
    /// at v never hides under the plot's frame.
    pub fn clear_of(&mut self, v: f64) {
        let tolerance = 0.01 * (self.hi - self.lo);
        if (v - self.hi).abs() <= tolerance {
            self.hi += self.step;
            self.values.push(self.hi);
        }
        if (v - self.lo).abs() <= tolerance {
            self.lo -= self.step;
            self.values.insert(0, self.lo);
        }
    }
}

/// Ticks of a logarithmic axis over [lo, hi] (0 < lo < hi): 1·10^k, else 1, 2, 5·10^k, else
/// every digit, whichever first gives at least four.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let mut out = Vec::new();
    for mults in [
        &[1.0][..],
        &[1.0, 2.0, 5.0][..],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0][..],
    ] {
        out = (k0..=k1)
            .flat_map(|k| mults.iter().map(move |m| m * 10f64.powi(k)))
            .filter(|v| *v >= lo * (1.0 - 1e-9) && *v <= hi * (1.0 + 1e-9))
            .collect();
        if out.len() >= 4 {
            break;
        }
    }
    out
}

/// A tick value of a log axis with as many decimals as it needs (0.05, 2, 300).
pub fn log_label(v: f64) -> String {
    let decimals = (-(v.log10() + 1e-9).floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}
