//! What `cycloid bless` says it did ([`engine::golden::bless`](crate::engine::golden::bless)): per golden file, what moved, by
//! how much and where.

use crate::engine::golden::{BlessChange, Blessed, Written};
use crate::numeric::number;
use crate::spec::Spec;

/// The lines `cycloid bless` prints: per golden, what moved, by how much and where.
pub fn bless_report(spec: &Spec, blessed: &[Blessed]) -> String {
    let changed = blessed
        .iter()
        .filter(|b| b.written != Written::Nothing)
        .count();
    let mut out = if changed == 0 {
        format!(
            "cycloid bless `{}`: {} golden file(s), no change beyond their tolerances: nothing \
             written\n",
            spec.name,
            blessed.len()
        )
    } else {
        format!(
            "cycloid bless `{}`: {} golden file(s), {changed} written\n",
            spec.name,
            blessed.len()
        )
    };
    for b in blessed {
        let file = b.golden.path.display();
        let cols = match b.golden.quantity.shape.per() {
            Some(what) => format!("{what} columns"),
            None => "1 column".into(),
        };
        let what = match &b.change {
            BlessChange::New => format!("new: {} crank angles, {cols}", b.rows),
            BlessChange::Replaced(why) => format!("replaced ({why})"),
            BlessChange::Compared(c) if c.largest.deviation == 0.0 => "unchanged".into(),
            BlessChange::Compared(c) => format!(
                "max |change| {}{} at {} ({} → {}); {}",
                number(c.largest.deviation),
                if b.unit.is_empty() {
                    String::new()
                } else {
                    format!(" {}", b.unit)
                },
                place(&c.largest),
                number(c.largest.golden),
                number(c.largest.value),
                if c.passed {
                    "within its tolerance"
                } else {
                    "OUTSIDE the old tolerance: the review is reset, review it again"
                }
            ),
        };
        let what = match b.written {
            Written::Curve => what,
            Written::Metadata => {
                format!("{what}: the curve kept, its metadata brought up to date (spec hash, path or tolerance)")
            }
            Written::Nothing => format!("{what}: kept as it was"),
        };
        out += &format!(
            "  {file}  {}/{}: {what}\n",
            b.golden.scene, b.golden.quantity
        );
    }
    out
}

/// Where a golden point lies: "roller 3 at crank 12.30°" (or "crank 12.30°" for a single
/// curve).
pub fn place(p: &crate::engine::golden::Point) -> String {
    match p.column.rsplit_once('_') {
        Some((what, i)) if i.parse::<usize>().is_ok() => {
            format!("{what} {i} at crank {:.2}°", p.crank_deg)
        }
        _ => format!("crank {:.2}°", p.crank_deg),
    }
}
