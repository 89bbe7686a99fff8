//! The terminal table of checks: check, value, limit, verdict, where.

use crate::check::{Bound, Check};

/// Format a number for a person: 4 significant figures, no exponent for ordinary magnitudes.
pub fn number(x: f64) -> String {
    if x == 0.0 || (1e-3..1e6).contains(&x.abs()) {
        let digits = (3 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.3e}")
    }
}

/// The table, one check a row, failures first.
pub fn render(checks: &[Check]) -> String {
    let mut rows: Vec<&Check> = checks.iter().collect();
    rows.sort_by_key(|c| c.passed);
    let header = ["check", "value", "limit", "verdict", "where"];
    let cells: Vec<[String; 5]> = rows
        .iter()
        .map(|c| {
            let op = match c.bound {
                Bound::Max => "≤",
                Bound::Min => "≥",
            };
            [
                c.id.clone(),
                number(c.value),
                format!("{op} {}", number(c.limit)),
                if c.passed { "pass" } else { "FAIL" }.to_string(),
                c.at.clone(),
            ]
        })
        .collect();
    let mut widths = header.map(|h| h.chars().count());
    for row in &cells {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |row: [&str; 5]| {
        let mut s = String::new();
        for (k, (cell, w)) in row.iter().zip(widths).enumerate() {
            if k + 1 == row.len() {
                s += cell;
            } else {
                s += &format!("{cell}{}  ", " ".repeat(w - cell.chars().count()));
            }
        }
        s.trim_end().to_string() + "\n"
    };
    let mut out = line(header);
    for row in &cells {
        out += &line([&row[0], &row[1], &row[2], &row[3], &row[4]]);
    }
    let failed = checks.iter().filter(|c| !c.passed).count();
    out += &format!(
        "{} checks: {} passed, {} failed\n",
        checks.len(),
        checks.len() - failed,
        failed
    );
    out
}
