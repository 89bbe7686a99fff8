//! Terminal tables as text: rows of cells in aligned columns.

/// Where a cell sits in its column.
#[derive(Clone, Copy, PartialEq)]
pub enum Align {
    Left,
    Right,
}

/// Rows of cells in columns two spaces apart, each as wide as its widest cell (in characters),
/// column c's cells aligned as `align(c)` says; no line ends in spaces.
pub fn columns(rows: &[Vec<String>], align: impl Fn(usize) -> Align) -> String {
    let widths: Vec<usize> = (0..rows[0].len())
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut out = String::new();
    for r in rows {
        let cells: Vec<String> = (r.iter().zip(&widths).enumerate())
            .map(|(c, (cell, w))| match align(c) {
                Align::Right => format!("{cell:>w$}"),
                Align::Left => format!("{cell:<w$}"),
            })
            .collect();
        out += cells.join("  ").trim_end();
        out.push('\n');
    }
    out
}
