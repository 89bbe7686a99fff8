//! Terminal tables as text: rows of cells in aligned columns.

/// Rows of cells in columns two spaces apart, each as wide as its widest cell, the cells
/// aligned right (`right`) or left; no line ends in spaces.
pub fn columns(rows: &[Vec<String>], right: bool) -> String {
    let widths: Vec<usize> = (0..rows[0].len())
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut out = String::new();
    for r in rows {
        let cells: Vec<String> = r
            .iter()
            .zip(&widths)
            .map(|(cell, w)| match right {
                true => format!("{cell:>w$}"),
                false => format!("{cell:<w$}"),
            })
            .collect();
        out += cells.join("  ").trim_end();
        out.push('\n');
    }
    out
}
