//! Small numeric helpers shared by every layer: extremes of sampled curves, and numbers
//! formatted for a person.

/// Largest entry of a \[row\]\[angle\] array: (value, row, angle index). Empty gives (0, 0, 0).
pub fn max_entry(rows: &[Vec<f64>]) -> (f64, usize, usize) {
    let mut best = (f64::NEG_INFINITY, 0, 0);
    for (i, row) in rows.iter().enumerate() {
        for (k, &v) in row.iter().enumerate() {
            if v > best.0 {
                best = (v, i, k);
            }
        }
    }
    if best.0.is_finite() {
        best
    } else {
        (0.0, 0, 0)
    }
}

/// Smallest entry of a \[row\]\[angle\] array: (value, row, angle index). Empty gives (0, 0, 0).
pub fn min_entry(rows: &[Vec<f64>]) -> (f64, usize, usize) {
    let mut best = (f64::INFINITY, 0, 0);
    for (i, row) in rows.iter().enumerate() {
        for (k, &v) in row.iter().enumerate() {
            if v < best.0 {
                best = (v, i, k);
            }
        }
    }
    if best.0.is_finite() {
        best
    } else {
        (0.0, 0, 0)
    }
}

/// (min, max) of a curve with their indices.
pub fn extremes(values: &[f64]) -> ((f64, usize), (f64, usize)) {
    let mut lo = (f64::INFINITY, 0);
    let mut hi = (f64::NEG_INFINITY, 0);
    for (k, &v) in values.iter().enumerate() {
        if v < lo.0 {
            lo = (v, k);
        }
        if v > hi.0 {
            hi = (v, k);
        }
    }
    (lo, hi)
}

/// max − min of a curve (0 when empty).
pub fn fluctuation(values: &[f64]) -> f64 {
    let ((lo, _), (hi, _)) = extremes(values);
    if values.is_empty() {
        0.0
    } else {
        hi - lo
    }
}

/// A number for a person: 4 significant figures, no exponent for ordinary magnitudes
/// (1e-3 ≤ |x| < 1e6), exponent form otherwise (never a 300-digit decimal).
pub fn number(x: f64) -> String {
    match decimals(x) {
        _ if x == 0.0 => "0".to_string(),
        Some(digits) => format!("{x:.digits$}"),
        None => format!("{x:.3e}"),
    }
}

/// The decimals `number` prints `x` with (four significant digits), or `None` where it
/// prints an exponent (|x| outside [1e-3, 1e6)).
fn decimals(x: f64) -> Option<usize> {
    let decimal = (1e-3..1e6).contains(&x.abs());
    decimal.then(|| (3 - x.abs().log10().floor() as i32).clamp(0, 6) as usize)
}

/// The change from `from` to `to`, signed, to the decimals the larger of the two is printed
/// with (`number`), so that it reads against them: a change below their last printed digit is
/// "0", not a number in exponent form far below what the values show. Where the values
/// print with an exponent, the change is `number`'s, signed.
pub fn change(from: f64, to: f64) -> String {
    let x = to - from;
    match decimals(from.abs().max(to.abs())) {
        Some(digits) => signed(x, digits).unwrap_or_else(|| "0".to_string()),
        None if x == 0.0 => "0".to_string(),
        None => format!("{x:+.3e}"),
    }
}

/// A change `x` signed, to `decimals` (`+25.000`, `-9.300`), or `None` where it rounds to zero
/// there (not `+0.000` or `-0.000`).
pub fn signed(x: f64, decimals: usize) -> Option<String> {
    let zero = format!("{:.decimals$}", x.abs())
        .trim_matches(['0', '.'])
        .is_empty();
    (!zero).then(|| format!("{x:+.decimals$}"))
}

/// A value as the user wrote it when that is short, else in exponent form: spec inputs in
/// messages (`1e300` stays readable, `0.015` stays `0.015`).
pub fn input(x: f64) -> String {
    let plain = format!("{x}");
    if plain.len() <= 12 {
        plain
    } else {
        format!("{x:e}")
    }
}

/// A probability as the reports label it, to 0.001 %: `QUANTILES` read "0.135 %", "50 %",
/// "99.865 %", `CONFIDENCE` "95 %".
pub fn percent_label(p: f64) -> String {
    let digits = format!("{:.3}", 100.0 * p);
    format!("{} %", digits.trim_end_matches('0').trim_end_matches('.'))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A change reads against the values it is between: to their printed decimals, signed,
    /// and "0" below their last digit (a difference at the round-off of two 1,234.5 N forces
    /// is not "1.418e-4"); values printed with an exponent give an exponent change.
    #[test]
    fn changes_are_printed_to_the_values_decimals() {
        assert_eq!(number(1234.5678), "1235");
        assert_eq!(change(1234.5678, 1234.5679418), "0");
        assert_eq!(change(1234.5, 1236.4), "+2");
        assert_eq!(change(0.03430, 0.03000), "-0.00430");
        assert_eq!(change(12.5, 12.5), "0");
        assert_eq!(change(2e-5, 3e-5), "+1.000e-5");
        assert_eq!(change(2e6, 2e6), "0");
    }

    /// Extremes and entries are found where they are, and empty input has defined answers.
    #[test]
    fn extremes_and_entries() {
        let rows = vec![vec![1.0, 5.0, -2.0], vec![3.0, -7.0, 4.0]];
        assert_eq!(max_entry(&rows), (5.0, 0, 1));
        assert_eq!(min_entry(&rows), (-7.0, 1, 1));
        assert_eq!(extremes(&rows[1]), ((-7.0, 1), (4.0, 2)));
        assert_eq!(fluctuation(&rows[0]), 7.0);
        assert_eq!(fluctuation(&[]), 0.0);
        assert_eq!(max_entry(&[]), (0.0, 0, 0));
    }

    /// Four significant figures for ordinary magnitudes, exponent form beyond them, and
    /// inputs keep their own short form.
    #[test]
    fn numbers_for_people() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(12.3456), "12.35");
        assert_eq!(number(-0.0123456), "-0.01235");
        assert_eq!(number(1e300), "1.000e300");
        assert_eq!(number(2.5e-7), "2.500e-7");
        assert_eq!(input(0.015), "0.015");
        assert_eq!(input(1e300), "1e300");
    }
}
