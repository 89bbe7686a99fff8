//! What an identification (`fit`) finds along the profile, as the per-flank summaries
//! (`flanks`) read it: the form error (its harmonics, each an estimate with its standard
//! uncertainty) and the profile points with their feet and residuals.

use crate::geometry::cos_sin_of_orders;

/// An identified value with its standard uncertainty (same unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    pub value: f64,
    pub sigma: f64,
}

/// One harmonic of the form error: w(t) ∋ cos_mm·cos(order·t) + sin_mm·sin(order·t), mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    pub order: usize,
    pub cos_mm: Estimate,
    pub sin_mm: Estimate,
}

impl Harmonic {
    /// Amplitude sqrt(a² + b²), mm.
    pub fn amplitude_mm(&self) -> f64 {
        self.cos_mm.value.hypot(self.sin_mm.value)
    }
}

/// The form error w(t) along the profile normal, mm (positive: material missing).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FormError {
    pub harmonics: Vec<Harmonic>,
}

impl FormError {
    /// The orders of a series up to `harmonics` for a disc of `teeth` teeth: 2..=harmonics
    /// without the multiples of the tooth count (see `fit`'s module comment).
    pub fn orders(harmonics: usize, teeth: usize) -> Vec<usize> {
        (2..=harmonics).filter(|k| k % teeth != 0).collect()
    }

    /// w(t), mm, the harmonics by `cos_sin_of_orders` (one sin_cos per call: the per-flank
    /// summaries evaluate it at every point).
    pub fn value_mm(&self, t: f64) -> f64 {
        let orders = self.harmonics.iter().map(|h| h.order);
        (self.harmonics.iter().zip(cos_sin_of_orders(t, orders)))
            .map(|(h, (c, s))| h.cos_mm.value * c + h.sin_mm.value * s)
            .sum()
    }
}

/// A profile point after the fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FittedPoint {
    pub t: f64,
    pub residual_mm: f64,
    pub line: usize,
}
