//! The frame of a review page: its style, its head (the spec's identity), the banner, a table of
//! contents of its sections and the spec's source; and the writing of a page with its figures
//! as one batch.

use super::common::Section;
use crate::engine::golden::{sha256_hex, today};
use crate::error::{Error, Result};
use crate::files::Batch;
use crate::report::svg::FONT;
use crate::spec::Spec;
use maud::{html, Markup, PreEscaped, DOCTYPE};
use std::path::Path;

/// `files` (name, text) into `dir` (created if missing) as one batch, in their order: every
/// file is staged, then all are renamed into place, the page that links the others last, so a
/// reader never sees a page that links figures of another run. A name in a folder
/// (`design-01/index.html`, a design search's review of each design) has its folder created.
pub fn write_files(dir: &Path, files: &[(String, String)]) -> Result<()> {
    let mut batch = Batch::default();
    let mkdir =
        |d: &Path| std::fs::create_dir_all(d).map_err(|e| Error::io(&d.display().to_string(), e));
    mkdir(dir)?;
    for (name, text) in files {
        let path = dir.join(name);
        if let Some(folder) = path.parent().filter(|p| *p != dir) {
            mkdir(folder)?;
        }
        batch.add(&path, text.as_bytes())?;
    }
    batch.commit()
}

pub(super) const STYLE: &str = r#"
body { font-family: FONT; color: #222; margin: 24px auto; max-width: 1360px; padding: 0 16px; line-height: 1.4; }
h1 { font-size: 26px; margin: 0 0 6px; }
h2 { font-size: 20px; margin: 28px 0 10px; border-bottom: 1px solid #ddd; padding-bottom: 4px; }
h3 { font-size: 17px; margin: 22px 0 4px; }
.meta { color: #555; font-size: 13px; overflow-wrap: anywhere; }
.meta code { font-size: 12px; }
.banner { font-size: 18px; font-weight: bold; padding: 10px 14px; border-radius: 4px; margin: 12px 0; }
.banner.pass { background: #e3f4e1; color: #1d6b1a; border: 1px solid #9fd39a; }
.banner.fail { background: #fde2e2; color: #a11212; border: 1px solid #f0a1a1; }
.banner.warn { background: #fff4d6; color: #6b4a00; border: 1px solid #e8c768; font-size: 15px; }
.banner.warn p { margin: 2px 0; }
nav.toc { font-size: 14px; background: #f7f7f7; border: 1px solid #e3e3e3; border-radius: 4px; padding: 6px 14px; }
nav.toc ol { margin: 4px 0; padding-left: 22px; columns: 2 260px; }
.scroll { overflow-x: auto; max-width: 100%; }
table { border-collapse: collapse; font-size: 14px; margin: 6px 0; }
th, td { text-align: left; padding: 4px 10px; border-bottom: 1px solid #eee; vertical-align: top; }
thead th { background: #f3f3f3; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.fail td.verdict { color: #b00; font-weight: bold; }
tr.pass td.verdict { color: #1d6b1a; }
tr.fail { background: #fff3f3; }
tr.cheapest { background: #e3f4e1; font-weight: bold; }
tr.implausible td { background: #fdecc8; }
tr.implausible td[rowspan] { background: none; }
tr.reference { background: #f3f3f3; }
td.over { color: #b00; }
table.study th { font-weight: normal; }
table.study thead th { font-weight: bold; text-align: right; }
table.study .optimum { font-weight: bold; }
table.study small { font-weight: normal; color: #666; }
td.verdict.pass { color: #1d6b1a; }
td.verdict.fail, td.violated { color: #b00; font-weight: bold; }
.cols { display: flex; gap: 40px; flex-wrap: wrap; }
.grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(min(660px, 100%), 1fr)); gap: 18px; }
figure { margin: 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 13px; color: #444; max-width: 660px; }
.note { color: #555; font-size: 14px; }
pre { background: #f7f7f7; padding: 10px; font-size: 12px; overflow-x: auto; }
"#;

/// A page of the report's look: `title` of the spec, its identity, the `banner`, a table of
/// contents of `sections`, the sections and the spec's source.
pub(super) fn shell(spec: &Spec, title: &str, banner: Markup, sections: &[Section]) -> String {
    let page = html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                meta name="viewport" content="width=device-width, initial-scale=1";
                title { (title) ": " (spec.name) }
                style { (PreEscaped(STYLE.replace("FONT", FONT))) }
            }
            body {
                h1 { (title) ": " (spec.name) }
                p.meta {
                    "spec " code { (spec.path) } " · SHA-256 " code { (sha256_hex(&spec.source)) }
                    " · cycloid " (env!("CARGO_PKG_VERSION")) " · generated " (today())
                }
                (banner)
                nav.toc {
                    b { "Contents" }
                    ol { @for s in sections { li { a href=(format!("#{}", s.id)) { (s.heading) } } } }
                }
                @for s in sections {
                    section id=(s.id) { h2 { (s.heading) } (s.body) }
                }
                section #source {
                    details { summary { "Spec source" } pre { (spec.source) } }
                }
            }
        }
    };
    page.into_string()
}
