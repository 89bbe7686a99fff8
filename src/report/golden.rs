//! What `cycloid bless` says it did ([`engine::golden::bless`](crate::engine::golden::bless)): per golden file, what moved, by
//! how much and where.

use crate::engine::golden::{BlessChange, Blessed, Point, Written};
use crate::model::place::{Place, Site};
use crate::numeric::{number, with_unit};
use crate::report::place;
use crate::spec::Spec;

/// The lines `cycloid bless` prints: per golden, what moved, by how much and where.
pub fn bless_report(spec: &Spec, blessed: &[Blessed]) -> String {
    let changed = blessed
        .iter()
        .filter(|b| b.written != Written::Nothing)
        .count();
    let written = match changed {
        0 => "no change beyond their tolerances: nothing written".to_string(),
        n => format!("{n} written"),
    };
    let mut out = format!(
        "cycloid bless `{}`: {} golden file(s), {written}\n",
        spec.name,
        blessed.len()
    );
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
                "max |change| {} at {} ({} → {}); {}",
                with_unit(number(c.largest.deviation), b.golden.quantity.unit),
                place::text(&c.largest.place()),
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

/// Where a golden point lies, in a row that names the golden's disc already (a check's id, the
/// review's curve: `Golden::disc_suffix`), so without it: "roller 3 at crank 12.30°".
pub fn in_row(p: &Point) -> String {
    place::text(&Place::of(Site::Golden(p.at)))
}
