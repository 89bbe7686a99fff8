//! What every plot of the kit is made of: its colours and font, pixel coordinates as text, the
//! rough width of a label, and the standalone SVG document around a drawing.

use maud::{html, Markup};

/// Ten colours that stay apart (the "tab10" set).
pub const PALETTE: [&str; 10] = [
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
    "#bcbd22", "#17becf",
];

/// Red of limits, the smallest gap and roller forces.
pub const RED: &str = "#d62728";

pub const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";

/// A pixel coordinate with two decimals (enough for any screen, keeps files small).
pub fn px(x: f64) -> String {
    trimmed(x, 2)
}

/// `x` to `decimals` (`numeric::fixed`: no "-0"), trailing zeros of the decimals dropped.
pub fn trimmed(x: f64, decimals: usize) -> String {
    let s = crate::numeric::fixed(x, decimals);
    // Only decimals are trimmed: "10" at no decimals stays 10.
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The smallest and largest finite value.
pub(super) fn span<'a>(values: impl Iterator<Item = &'a f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |acc, &v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((v.min(lo), v.max(hi))),
        })
}

/// Estimated width of text in pixels (for layout): per character its advance in DejaVu Sans,
/// rounded up within classes (em): narrow punctuation and i, j, l 0.35, space 0.32, f, r, t
/// 0.45, digits and other lower case 0.64, m and w 0.98, upper case 0.78, anything else (µ, °,
/// −, symbols) 0.84. An overestimate keeps placed labels apart in any of the fonts of `FONT`.
pub fn text_width(text: &str, size: f64) -> f64 {
    let em: f64 = text
        .chars()
        .map(|c| match c {
            ' ' => 0.32,
            '.' | ',' | ':' | ';' | '\'' | '!' | '|' | 'i' | 'j' | 'l' | '(' | ')' => 0.35,
            'f' | 'r' | 't' | '-' => 0.45,
            'm' | 'w' => 0.98,
            '0'..='9' | 'a'..='z' => 0.64,
            'A'..='Z' => 0.78,
            _ => 0.84,
        })
        .sum();
    em * size
}

/// Rough width of the widest of `texts` at font size 12, pixels (0 for none).
pub fn widest<S: AsRef<str>>(texts: impl Iterator<Item = S>) -> f64 {
    texts
        .map(|t| text_width(t.as_ref(), 12.0))
        .fold(0.0, f64::max)
}

/// "x1,y1 x2,y2 ..." of pixel points, for `points` and paths.
pub fn points(pts: impl IntoIterator<Item = (f64, f64)>) -> String {
    pts.into_iter()
        .map(|(x, y)| format!("{},{}", px(x), px(y)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A standalone SVG document, w × h pixels on a white background, around `body`.
pub fn document(w: f64, h: f64, body: Markup) -> String {
    let doc = html! {
        svg xmlns="http://www.w3.org/2000/svg" width=(px(w)) height=(px(h))
            viewBox=(format!("0 0 {} {}", px(w), px(h))) font-family=(FONT) fill="#222" {
            rect width=(px(w)) height=(px(h)) fill="white" {}
            (body)
        }
    };
    doc.into_string() + "\n"
}

#[cfg(test)]
mod tests {
    use super::trimmed;

    /// Only the zeros after the point go: 1.50 reads 1.5 and 2.000 reads 2, but ten at no
    /// decimals stays "10" (trimming every trailing zero read it as "1"); a value that rounds
    /// to zero reads "0", not "-0".
    #[test]
    fn trimming_drops_only_trailing_decimal_zeros() {
        assert_eq!(trimmed(1.5, 2), "1.5");
        assert_eq!(trimmed(2.0, 3), "2");
        assert_eq!(trimmed(10.0, 0), "10");
        assert_eq!(trimmed(-0.001, 2), "0");
        assert_eq!(trimmed(-0.25, 2), "-0.25");
    }
}
