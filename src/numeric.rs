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

/// The smallest and largest of `values` (∞ and −∞ for none; `min`/`max` pass over a NaN).
pub fn extent(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    let start = (f64::INFINITY, f64::NEG_INFINITY);
    (values.into_iter()).fold(start, |(lo, hi), v| (lo.min(v), hi.max(v)))
}

/// The step between the first two of evenly spaced samples `values` (0 with fewer than two).
pub fn step(values: &[f64]) -> f64 {
    match values {
        [a, b, ..] => b - a,
        _ => 0.0,
    }
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
    match decimals(x, 1e-3) {
        _ if x == 0.0 => "0".to_string(),
        Some(digits) => format!("{x:.digits$}"),
        None => format!("{x:.3e}"),
    }
}

/// A value followed by its unit, if any ("2.000 mm", "3").
pub fn with_unit(x: String, unit: &str) -> String {
    if unit.is_empty() {
        x
    } else {
        format!("{x} {unit}")
    }
}

/// The decimals that give `x` four significant digits where it rounds into [`smallest`, 1e6),
/// else `None` (an exponent): `number` prints decimals from 1e-3, a column from 1e-4 (one
/// decade further down: a column may need it).
fn decimals(x: f64, smallest: f64) -> Option<usize> {
    // The magnitude after rounding to four significant digits: 9.99996 prints as 10.00 (four
    // digits), not 10.000, and 999999.7 as 1.000e6.
    let a = x.abs();
    let unit = 10f64.powi(a.log10().floor() as i32 - 3);
    let rounded = (a / unit).round() * unit;
    (smallest..1e6)
        .contains(&rounded)
        .then(|| (3 - (rounded.log10() + 1e-12).floor() as i32).max(0) as usize)
}

/// The cells of one column of numbers, by one rule for the whole column: whole numbers (a
/// column of counts, |x| < 1e6) as integers; otherwise every cell to four significant digits
/// (as `number`), all in decimals where every non-zero value rounds into [1e-4, 1e6)
/// (`-0.0005314` beside `-0.002242`), else all with an exponent (`-5.314e-4`, `1.200e1`), so
/// that no column switches between the two forms. Zero is "0".
pub fn column(values: &[f64]) -> Vec<String> {
    let counts = values.iter().all(|x| x.fract() == 0.0 && x.abs() < 1e6);
    let decimal = values
        .iter()
        .filter(|&&x| x != 0.0)
        .all(|&x| decimals(x, 1e-4).is_some());
    values
        .iter()
        .map(|&x| match decimals(x, 1e-4) {
            _ if x == 0.0 => "0".to_string(),
            _ if counts => format!("{x:.0}"),
            Some(digits) if decimal => format!("{x:.digits$}"),
            _ => format!("{x:.3e}"),
        })
        .collect()
}

/// The change from `from` to `to`, signed, to the decimals the larger of the two is printed
/// with (`number`), so that it reads against them: a change below their last printed digit is
/// "0", not a number in exponent form far below what the values show. Where the values
/// print with an exponent, the change is `number`'s, signed.
pub fn change(from: f64, to: f64) -> String {
    let x = to - from;
    match decimals(from.abs().max(to.abs()), 1e-3) {
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

/// `x` with `decimals`, without the sign of a value that rounds to zero (`-0.000` → `0.000`).
pub fn fixed(x: f64, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

/// A change `x` with `decimals`, signed as [`change`] signs one ([`signed`]: `+25.000`,
/// `-9.300`), and unsigned where it rounds to zero (`0.000`).
pub fn fixed_change(x: f64, decimals: usize) -> String {
    signed(x, decimals).unwrap_or_else(|| fixed(0.0, decimals))
}

/// A value as the user wrote it when that is short, else in exponent form: spec inputs in
/// messages (`1e300` stays readable, `0.015` stays `0.015`).
pub fn input(x: f64) -> String {
    let plain = format!("{x}");
    if plain.len() <= 12 {
        return plain;
    }
    // A long value (360/5.5 = 65.454545…): ten significant digits, trailing zeros dropped,
    // plain where that reads (65.45454545), an exponent beyond (1.234567891e-9).
    let exponent = x.abs().log10().floor();
    if (-3.0..9.0).contains(&exponent) {
        // At least one decimal (exponent ≤ 8), so the zeros trimmed are decimals.
        let digits = (9 - exponent as i32) as usize;
        let s = format!("{x:.digits$}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        let s = format!("{x:.9e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
    }
}

/// A tooth phase in [0, 1) to three decimals: a phase that rounds to 1.000 is the next tooth's
/// root, 0.000 (the phase wraps).
pub fn phase(p: f64) -> String {
    let s = format!("{:.3}", p.rem_euclid(1.0));
    if s == "1.000" {
        "0.000".to_string()
    } else {
        s
    }
}

/// A fraction as a percentage for people, to `number`'s digits: 0.0027 is "0.2700 %".
pub fn percent(x: f64) -> String {
    format!("{} %", number(100.0 * x))
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

    /// Signed like the headline changes beside it, and a change at the round-off of a fit
    /// (1e-12 either way) reads as no change at all.
    #[test]
    fn a_change_is_signed_and_round_off_reads_zero() {
        assert_eq!(fixed_change(25.0, 3), "+25.000");
        assert_eq!(fixed_change(-9.3, 3), "-9.300");
        assert_eq!(fixed_change(1e-12, 3), "0.000");
        assert_eq!(fixed_change(-1e-12, 3), "0.000");
        assert_eq!(fixed_change(0.0005, 3), "+0.001");
    }

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

    /// A column reads by one rule (`column`): the review's example, -5.314e-4 beside
    /// -0.002242, reads in decimals, four significant digits each; a whole value beside
    /// fractions reads to four digits too ("3.000", not "3"); counts as integers; a column
    /// spanning more decades than decimals can show (1e-6 beside 2) wholly with exponents.
    #[test]
    fn a_column_reads_by_one_rule() {
        assert_eq!(column(&[-5.314e-4, -0.002242]), ["-0.0005314", "-0.002242"]);
        assert_eq!(column(&[3.0, 2.942]), ["3.000", "2.942"]);
        assert_eq!(column(&[29.0, 31.0]), ["29", "31"]);
        assert_eq!(column(&[1e-6, 2.0, 0.0]), ["1.000e-6", "2.000e0", "0"]);
        assert_eq!(column(&[942.7, 1002.25]), ["942.7", "1002"]);
        assert_eq!(column(&[0.99996, 0.5]), ["1.000", "0.5000"]);
    }

    /// Four significant digits after rounding: a value that rounds up into the next decade
    /// prints as that decade does (10.00, not 10.000: "golden 10.00, now 10.000" read as two
    /// precisions of one number).
    #[test]
    fn numbers_round_into_the_next_decade_with_its_digits() {
        assert_eq!(number(9.99996), "10.00");
        assert_eq!(number(10.0), "10.00");
        assert_eq!(number(9.9994), "9.999");
        assert_eq!(number(0.99996), "1.000");
        assert_eq!(number(999.96), "1000");
        assert_eq!(number(999_999.7), "1.000e6");
        assert_eq!(number(0.0009999), "9.999e-4");
        assert_eq!(number(0.00099996), number(0.001));
    }

    /// A phase wraps: 0.9996 is the next root, not "1.000".
    #[test]
    fn phases_wrap_at_one() {
        assert_eq!(phase(0.9996), "0.000");
        assert_eq!(phase(0.9994), "0.999");
        assert_eq!(phase(1.25), "0.250");
        assert_eq!(phase(-0.25), "0.750");
        assert_eq!(phase(0.5), "0.500");
    }

    /// Inputs are shown as written when short, else to ten significant digits: 360°/5.5 is
    /// 65.45454545, not 6.545454545454545e1.
    #[test]
    fn long_inputs_are_cut_to_ten_significant_digits() {
        assert_eq!(input(0.015), "0.015");
        assert_eq!(input(1e300), "1e300");
        assert_eq!(input(360.0 / 5.5), "65.45454545");
        assert_eq!(input(-1.0 / 3.0), "-0.3333333333");
        assert_eq!(input(1.0 / 3.0 * 1e-9), "3.333333333e-10");
        assert_eq!(input(123456789.123456), "123456789.1");
    }

    /// Extremes and entries are found where they are, and empty input has defined answers.
    #[test]
    fn extremes_and_entries() {
        let rows = vec![vec![1.0, 5.0, -2.0], vec![3.0, -7.0, 4.0]];
        assert_eq!(max_entry(&rows), (5.0, 0, 1));
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
