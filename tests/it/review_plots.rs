//! The review's plots as a reviewer sees them, checked on the SVG files `check --report`
//! writes (parsed with quick-xml, measured here with DejaVu Sans's own glyph widths): labels
//! clear of each other, of the drawing (profile, holes, pins, rollers, crank, force arrows,
//! the close-up's flank and roller, a map's path and markers) and inside their frame; a map's
//! global samples small against its cells; the output lag βo drawn at a scale that shows its
//! ripple as the small thing it is; the torsion curves one per locked angle with the slope
//! beyond the dead band visible and the band labelled; few samples drawn as marks, with their
//! count in the title.

use crate::common::{cycloid as run, Scratch};
use cycloid::progress::Silent;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;
use std::collections::HashMap;

/// One element of an SVG: its name, attributes, the text directly inside it and the classes
/// of the elements around it.
#[derive(Debug, Clone)]
struct El {
    name: String,
    attrs: HashMap<String, String>,
    text: String,
    within: Vec<String>,
}

impl El {
    fn num(&self, key: &str) -> f64 {
        let v = self
            .attrs
            .get(key)
            .unwrap_or_else(|| panic!("{key} of {self:?}"));
        v.parse()
            .unwrap_or_else(|_| panic!("{key}={v} of {self:?}"))
    }

    fn attr(&self, key: &str) -> &str {
        self.attrs.get(key).map_or("", String::as_str)
    }

    fn class(&self) -> &str {
        self.attr("class")
    }

    fn inside(&self, class: &str) -> bool {
        self.within.iter().any(|c| c == class)
    }
}

fn element(e: &BytesStart, within: &[String]) -> El {
    let attrs = e
        .attributes()
        .map(|a| {
            let a = a.unwrap();
            let key = String::from_utf8(a.key.as_ref().to_vec()).unwrap();
            (key, a.unescape_value().unwrap().into_owned())
        })
        .collect();
    El {
        name: String::from_utf8(e.name().as_ref().to_vec()).unwrap(),
        attrs,
        text: String::new(),
        within: within.to_vec(),
    }
}

/// Every element of the document in order.
fn elements(svg: &str) -> Vec<El> {
    let mut reader = Reader::from_str(svg);
    let (mut out, mut open, mut classes) = (Vec::<El>::new(), Vec::new(), Vec::new());
    loop {
        match reader.read_event().unwrap() {
            Event::Start(e) => {
                let el = element(&e, &classes);
                classes.push(el.class().to_string());
                open.push(out.len());
                out.push(el);
            }
            Event::Empty(e) => out.push(element(&e, &classes)),
            Event::Text(t) => {
                if let Some(&k) = open.last() {
                    out[k].text += &t.unescape().unwrap();
                }
            }
            Event::End(_) => {
                open.pop();
                classes.pop();
            }
            Event::Eof => break,
            _ => {}
        }
    }
    out
}

/// A pixel box (x0, y0, x1, y1).
type Box4 = (f64, f64, f64, f64);

/// A segment between two pixel points.
type Segment = ((f64, f64), (f64, f64));

/// A circle: centre and radius, pixels.
type Circle = ((f64, f64), f64);

/// Advance width of a character in DejaVu Sans, the first font the SVGs ask for, em (its
/// hmtx widths over 2048 units per em), for the characters the labels use; 0.84 em for any
/// other, wider than every glyph of the font except M, W and m, which are listed.
fn advance(c: char) -> f64 {
    match c {
        '0'..='9' | 'b' | 'd' | 'g' | 'h' | 'n' | 'p' | 'q' | 'u' | 'µ' => 0.636,
        ' ' | '.' | ',' | ':' => 651.0 / 2048.0,
        'i' | 'j' | 'l' => 0.278,
        'f' => 0.352,
        't' => 0.392,
        'r' => 0.411,
        's' => 0.521,
        'c' => 0.550,
        'k' => 0.579,
        'v' | 'x' | 'y' => 0.592,
        'o' => 0.612,
        'a' => 0.613,
        'e' => 0.615,
        'w' => 0.818,
        'm' => 0.974,
        'F' => 0.575,
        'N' => 0.748,
        'M' => 0.863,
        'W' => 0.989,
        _ => 0.84,
    }
}

/// The box of a text element's glyphs: its width from the advances, from the cap height
/// above the baseline to the descenders below it (DejaVu Sans: 0.73 and 0.24 em).
fn text_box(t: &El) -> Box4 {
    let size = t.num("font-size");
    let w: f64 = t.text.chars().map(advance).sum::<f64>() * size;
    let (x, y) = (t.num("x"), t.num("y"));
    let x0 = match t.attr("text-anchor") {
        "middle" => x - w / 2.0,
        "end" => x - w,
        _ => x,
    };
    (x0, y - 0.73 * size, x0 + w, y + 0.24 * size)
}

fn overlap(a: &Box4, b: &Box4) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Whether a segment passes through a box: points along it every 0.25 px, one strictly inside
/// (a line 0.25 px from a corner may be missed: far under the stroke widths drawn).
fn crosses(b: &Box4, p: (f64, f64), q: (f64, f64)) -> bool {
    let n = ((q.0 - p.0).hypot(q.1 - p.1) / 0.25).ceil().max(1.0) as usize;
    (0..=n).any(|k| {
        let t = k as f64 / n as f64;
        let (x, y) = (p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1));
        x > b.0 && x < b.2 && y > b.1 && y < b.3
    })
}

/// Distances from c to the box's nearest and farthest points.
fn distances(b: &Box4, c: (f64, f64)) -> (f64, f64) {
    let near = (c.0.clamp(b.0, b.2) - c.0).hypot(c.1.clamp(b.1, b.3) - c.1);
    let far = (c.0 - b.0)
        .abs()
        .max((c.0 - b.2).abs())
        .hypot((c.1 - b.1).abs().max((c.1 - b.3).abs()));
    (near, far)
}

/// "x,y x,y ..." as points.
fn point_list(text: &str) -> Vec<(f64, f64)> {
    text.split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// A path "M x,y x,y ... Z" (its first subpath) as its segments, closed; and the circles of
/// the further subpaths "M x,y a r,r 0 1,0 2r,0 ..." (holes: the circle's left point, then
/// arcs), as (centre, radius).
fn path_parts(d: &str) -> (Vec<Segment>, Vec<Circle>) {
    let mut subpaths = d.split('M').filter(|s| !s.trim().is_empty());
    let outline = point_list(subpaths.next().unwrap().trim().trim_end_matches('Z'));
    let mut segments: Vec<_> = outline.windows(2).map(|w| (w[0], w[1])).collect();
    segments.push((outline[outline.len() - 1], outline[0]));
    let circles = subpaths
        .map(|s| {
            let mut tokens = s.split_whitespace();
            let (x, y) = point_list(tokens.next().unwrap())[0];
            let r: f64 = tokens.next().unwrap()[1..]
                .split(',')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            ((x + r, y), r)
        })
        .collect();
    (segments, circles)
}

/// What labels must keep clear of.
#[derive(Default)]
struct Drawing {
    segments: Vec<Segment>,
    /// Filled discs: no label may cover any of them.
    discs: Vec<Circle>,
    /// Outlines: no label may lie across them.
    rings: Vec<Circle>,
}

/// The labels of an SVG (text of class `label`) pairwise apart, clear of `drawing` and inside
/// `frame`; panics naming the first that is not.
fn labels_clear(name: &str, els: &[El], drawing: &Drawing, frame: Box4) -> usize {
    let labels: Vec<(&str, Box4)> = els
        .iter()
        .filter(|e| e.name == "text" && e.class() == "label")
        .map(|e| (e.text.as_str(), text_box(e)))
        .collect();
    for (k, (text, b)) in labels.iter().enumerate() {
        let inside = b.0 >= frame.0 && b.1 >= frame.1 && b.2 <= frame.2 && b.3 <= frame.3;
        assert!(
            inside,
            "{name}: label {text:?} {b:?} outside the frame {frame:?}"
        );
        for (other, o) in &labels[k + 1..] {
            assert!(
                !overlap(b, o),
                "{name}: labels {text:?} and {other:?} overlap"
            );
        }
        for &(p, q) in &drawing.segments {
            assert!(
                !crosses(b, p, q),
                "{name}: label {text:?} {b:?} crosses {p:?}–{q:?}"
            );
        }
        for &(c, r) in &drawing.discs {
            let near = distances(b, c).0;
            assert!(
                near >= r,
                "{name}: label {text:?} {b:?} covers the disc at {c:?} r {r}"
            );
        }
        for &(c, r) in &drawing.rings {
            let (near, far) = distances(b, c);
            assert!(
                near > r || far < r,
                "{name}: label {text:?} {b:?} lies across the circle at {c:?} r {r}"
            );
        }
    }
    labels.len()
}

fn svg_frame(els: &[El]) -> Box4 {
    let svg = els.iter().find(|e| e.name == "svg").unwrap();
    (0.0, 0.0, svg.num("width"), svg.num("height"))
}

/// The disc drawing: roller numbers and force labels clear of the profile, the holes, pins,
/// rollers, crank and arrows, and of each other. Returns how many labels it has.
fn disc_labels(name: &str, svg: &str) -> usize {
    let els = elements(svg);
    let mut d = Drawing::default();
    let profile = els.iter().find(|e| e.class() == "profile").unwrap();
    let (segments, holes) = path_parts(profile.attr("d"));
    d.segments = segments;
    d.rings = holes;
    for e in &els {
        match (e.name.as_str(), e.class()) {
            ("circle", "roller" | "pin") => d.discs.push(((e.num("cx"), e.num("cy")), e.num("r"))),
            ("line", "crank") => d
                .segments
                .push(((e.num("x1"), e.num("y1")), (e.num("x2"), e.num("y2")))),
            ("line", _) if e.inside("arrows") => d
                .segments
                .push(((e.num("x1"), e.num("y1")), (e.num("x2"), e.num("y2")))),
            ("polygon", _) if e.inside("arrows") => {
                let p = point_list(e.attr("points"));
                d.segments
                    .extend((0..p.len()).map(|k| (p[k], p[(k + 1) % p.len()])));
            }
            _ => {}
        }
    }
    assert!(
        !d.discs.is_empty() && !d.segments.is_empty(),
        "{name}: nothing drawn?"
    );
    labels_clear(name, &els, &d, svg_frame(&els))
}

/// The close-up: the gap's label clear of the flank and across neither the roller's outline
/// nor the gap's marks, inside the window.
fn detail_label(name: &str, svg: &str) {
    let els = elements(svg);
    let mut d = Drawing::default();
    let flank = els.iter().find(|e| e.class() == "profile").unwrap();
    d.segments = path_parts(flank.attr("d")).0;
    let roller = els.iter().find(|e| e.name == "circle").unwrap();
    d.rings
        .push(((roller.num("cx"), roller.num("cy")), roller.num("r")));
    let window = els
        .iter()
        .find(|e| e.name == "rect" && e.attr("fill") == "none")
        .unwrap();
    let (x, y) = (window.num("x"), window.num("y"));
    let frame = (x, y, x + window.num("width"), y + window.num("height"));
    let n = labels_clear(name, &els, &d, frame);
    assert_eq!(n, 1, "{name}: the gap's label");
}

/// An optimisation map: marker labels apart, clear of the path and the markers, inside the
/// axes; the global samples' marks (each counted as its whole extent, stroke included, an
/// upper bound of its ink) cover under 10 % of the axes, so that nine tenths of the map show
/// the cells' colour (the paper's ~830 samples on 225 cells of ~30 × 30 px; the marks drawn
/// before this bar, 7 px crosses with a 3 px stroke and 5.6 px dots, covered 22–26 %).
fn map_labels_and_samples(name: &str, svg: &str) {
    let els = elements(svg);
    let area = els
        .iter()
        .find(|e| e.name == "rect" && e.attr("fill") == "#f4f4f4")
        .unwrap();
    let (x, y, w, h) = (
        area.num("x"),
        area.num("y"),
        area.num("width"),
        area.num("height"),
    );
    let mut d = Drawing::default();
    for e in &els {
        match (e.name.as_str(), e.class()) {
            ("polyline", "path") => {
                let p = point_list(e.attr("points"));
                d.segments.extend(p.windows(2).map(|w| (w[0], w[1])));
            }
            ("circle", "marker") => d.discs.push(((e.num("cx"), e.num("cy")), e.num("r"))),
            ("polygon", "marker") => {
                let p = point_list(e.attr("points"));
                let c = p.iter().fold((0.0, 0.0), |a, q| (a.0 + q.0, a.1 + q.1));
                let c = (c.0 / p.len() as f64, c.1 / p.len() as f64);
                // The star's tips, 10 px from its centre.
                d.discs.push((c, 10.0));
            }
            ("path", "marker") => {
                // "M cx,cy-8 l8,8 ...": the diamond's top, 8 px above its centre.
                let top = point_list(e.attr("d")[1..].split(' ').next().unwrap())[0];
                d.discs.push(((top.0, top.1 + 8.0), 8.0));
            }
            _ => {}
        }
    }
    // Markers in the legend, outside the axes, are not on the map.
    d.discs.retain(|(c, _)| c.1 <= y + h + 12.0);
    let n = labels_clear(name, &els, &d, (x, y, x + w, y + h));
    assert!(n >= 2, "{name}: {n} marker labels");
    // Each sample's spot once (a mark is drawn twice, dark under light), with the area of its
    // mark and its widest stroke.
    let mut spots: HashMap<(i64, i64), f64> = HashMap::new();
    for e in els.iter().filter(|e| e.inside("samples")) {
        let (key, area) = match e.name.as_str() {
            "circle" => {
                let r = e.num("r") + e.num("stroke-width") / 2.0;
                ((e.num("cx"), e.num("cy")), std::f64::consts::PI * r * r)
            }
            "path" => {
                let p: Vec<(f64, f64)> = e
                    .attr("d")
                    .split(['M', 'L'])
                    .filter(|s| !s.trim().is_empty())
                    .flat_map(|s| point_list(s.trim()))
                    .collect();
                let (x0, x1) = p
                    .iter()
                    .fold((f64::MAX, f64::MIN), |a, q| (a.0.min(q.0), a.1.max(q.0)));
                let (y0, y1) = p
                    .iter()
                    .fold((f64::MAX, f64::MIN), |a, q| (a.0.min(q.1), a.1.max(q.1)));
                let s = e.num("stroke-width");
                (
                    ((x0 + x1) / 2.0, (y0 + y1) / 2.0),
                    (x1 - x0 + s) * (y1 - y0 + s),
                )
            }
            _ => continue,
        };
        let spot = ((key.0 * 10.0).round() as i64, (key.1 * 10.0).round() as i64);
        let seen = spots.entry(spot).or_insert(0.0);
        *seen = seen.max(area);
    }
    assert!(spots.len() > 50, "{name}: {} samples", spots.len());
    let covered: f64 = spots.values().sum::<f64>() / (w * h);
    assert!(
        covered < 0.10,
        "{name}: samples cover {:.1} % of the map",
        100.0 * covered
    );
}

/// The first outlined rectangle: a line plot's area (x, y, width, height).
fn plot_area(els: &[El]) -> (f64, f64, f64, f64) {
    let r = els
        .iter()
        .find(|e| e.name == "rect" && e.attr("fill") == "none" && e.attr("stroke") == "#333")
        .unwrap();
    (r.num("x"), r.num("y"), r.num("width"), r.num("height"))
}

fn title(els: &[El]) -> &str {
    let t = els
        .iter()
        .find(|e| e.name == "text" && e.attr("font-size") == "16");
    &t.unwrap().text
}

/// The paper's βo is 5.967 arcsec with a ripple of ~5e-4 arcsec (under 1 % of the mean): the
/// axis starts at zero, so that the curve spans under 1 % of the plot's height (ripple < 1 %
/// of the mean, and the axis at least as tall as the mean), and the title gives the ripple.
/// Zoomed to the ripple, as before, the curve spanned over 80 % of the height.
fn output_lag_at_scale(svg: &str) {
    let els = elements(svg);
    let (_, top, _, height) = plot_area(&els);
    let ticks: Vec<f64> = els
        .iter()
        .filter(|e| e.name == "text" && e.attr("text-anchor") == "end")
        .map(|e| e.text.replace('−', "-").parse().unwrap())
        .collect();
    let lowest = ticks.iter().copied().fold(f64::MAX, f64::min);
    assert!(lowest <= 0.0, "the axis starts at {lowest}: {ticks:?}");
    let curve = els.iter().find(|e| e.name == "polyline").unwrap();
    let ys: Vec<f64> = point_list(curve.attr("points"))
        .iter()
        .map(|p| p.1)
        .collect();
    let span =
        ys.iter().copied().fold(f64::MIN, f64::max) - ys.iter().copied().fold(f64::MAX, f64::min);
    assert!(span < 0.01 * height, "βo spans {span} px of {height}");
    assert!(ys.iter().all(|&y| y > top), "βo inside the plot");
    assert!(title(&els).contains("(ripple "), "{}", title(&els));
}

/// `specs/paper.yaml` (one run: it optimises four studies): its disc at the smallest gap with
/// the bearing force near the crank line, the close-up, the four optimisation maps and the
/// output lag.
#[test]
fn the_paper_review_keeps_labels_clear_samples_small_and_the_output_lag_to_scale() {
    let dir = Scratch::new("review-plots-paper");
    let spec = format!("{}/specs/paper.yaml", env!("CARGO_MANIFEST_DIR"));
    let out = run(&dir.path, &["check", &spec, "--report", "r"]);
    assert_eq!(out.code, Some(0), "{out:?}");
    let n = disc_labels("paper disc.svg", &dir.read("r/disc.svg"));
    // 10 roller numbers and at least the bearing's force.
    assert!(n > 10, "{n} labels");
    detail_label("paper disc-detail.svg", &dir.read("r/disc-detail.svg"));
    let maps: Vec<String> = std::fs::read_dir(dir.join("r"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|f| f.starts_with("optimisation-"))
        .collect();
    assert_eq!(maps.len(), 4, "{maps:?}");
    for m in &maps {
        map_labels_and_samples(m, &dir.read(&format!("r/{m}")));
    }
    output_lag_at_scale(&dir.read("r/scene-2-rated-output-lag.svg"));
}

/// The disc drawings of the other shipped specs: unloaded (`reducer`, roller numbers only),
/// two discs, and the loaded negative start whose forces (a 17298 N roller force beside its
/// roller, the 4667 N bearing force on the crank line) crowded their labels onto rings and
/// lines.
#[test]
fn disc_labels_clear_the_drawing_on_the_shipped_specs() {
    for (spec, labels) in [
        ("reducer", 10),
        ("reducer-two-discs", 10),
        ("paper-negative-start", 10 + 1),
    ] {
        let dir = Scratch::new("review-plots-disc");
        let path = format!("{}/specs/{spec}.yaml", env!("CARGO_MANIFEST_DIR"));
        let out = run(&dir.path, &["check", &path, "--report", "r"]);
        assert!(matches!(out.code, Some(0 | 1)), "{spec}: {out:?}");
        let n = disc_labels(spec, &dir.read("r/disc.svg"));
        assert!(n >= labels, "{spec}: {n} labels");
        detail_label(spec, &dir.read("r/disc-detail.svg"));
    }
}

/// `specs/reducer-torsion.yaml` locks 4 crank angles: 4 curves named by their angle, the
/// title says so; its dead band (~25 arcmin) dwarfs the twist beyond it (~0.4 arcmin each
/// way), so the axis is cut across the band and the cut says "dead band … arcmin"; beyond the
/// band the twist from +3 % to +100 % of rated spans a visible part of the plot (over 15 % of
/// its height: a panel is under half of it and the branch spans most of its panel; on one
/// axis with the band it spanned ~1 %).
#[test]
fn torsion_draws_a_curve_per_angle_and_cuts_its_axis_across_the_dead_band() {
    let dir = Scratch::new("review-plots-torsion");
    let spec = format!("{}/specs/reducer-torsion.yaml", env!("CARGO_MANIFEST_DIR"));
    let out = run(&dir.path, &["check", &spec, "--report", "r"]);
    assert_eq!(out.code, Some(0), "{out:?}");
    let els = elements(&dir.read("r/scene-1-torsion-torsion.svg"));
    let curves: Vec<&El> = els
        .iter()
        .filter(|e| e.class() == "series" && e.attr("aria-label").starts_with("crank "))
        .collect();
    let names: Vec<&str> = curves.iter().map(|e| e.attr("aria-label")).collect();
    assert_eq!(
        names,
        ["crank 0.00°", "crank 9.00°", "crank 18.00°", "crank 27.00°"]
    );
    assert!(
        title(&els).contains("at 4 locked crank angles"),
        "{}",
        title(&els)
    );
    let cut = els
        .iter()
        .find(|e| e.class() == "cut-label")
        .expect("a cut");
    assert!(
        cut.text.starts_with("dead band ") && cut.text.ends_with(" arcmin"),
        "{}",
        cut.text
    );
    let (_, _, _, height) = plot_area(&els);
    // The first curve: its points right of T = 0, the step's top to +rated.
    let curve = els
        .iter()
        .find(|e| e.name == "polyline" && e.inside("series"))
        .unwrap();
    let p = point_list(curve.attr("points"));
    let x0 = p[p.len() / 2].0;
    let right: Vec<f64> = p.iter().filter(|q| q.0 > x0 + 1.0).map(|q| q.1).collect();
    let span = right.iter().copied().fold(f64::MIN, f64::max)
        - right.iter().copied().fold(f64::MAX, f64::min);
    assert!(
        span > 0.15 * height,
        "the twist beyond the band spans {span} px of {height}"
    );
}

/// Few samples are marks, not a line: the torsion loop at 2 steps per quarter (5 torques) is
/// a dot per torque, and the 4 locked angles' backlash plot a dot per angle, both titles
/// stating the count.
#[test]
fn sparse_samples_are_marks_and_their_titles_count_them() {
    let dir = Scratch::new("review-plots-sparse");
    let text = std::fs::read_to_string(format!(
        "{}/specs/reducer-torsion.yaml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let edited = text.replace("steps: 40 }", "steps: 2 }");
    assert_ne!(edited, text);
    dir.write("spec.yaml", edited);
    let out = run(&dir.path, &["check", "spec.yaml", "--report", "r"]);
    assert!(matches!(out.code, Some(0 | 1)), "{out:?}");
    for (file, count) in [
        ("r/scene-1-torsion-torsion.svg", "5 torques"),
        ("r/scene-1-torsion-backlash.svg", "at 4 crank angles"),
    ] {
        let els = elements(&dir.read(file));
        assert!(title(&els).contains(count), "{file}: {}", title(&els));
        let series: Vec<&El> = els.iter().filter(|e| e.class() == "series").collect();
        assert!(!series.is_empty(), "{file}");
        let lines = els
            .iter()
            .filter(|e| e.name == "polyline" && e.inside("series"));
        assert_eq!(lines.count(), 0, "{file}: a line through few samples");
        let marks = els
            .iter()
            .filter(|e| e.class() == "mark" && e.inside("series"));
        assert!(marks.count() >= 4, "{file}: marks");
    }
}

/// `cycloid design`'s front plot names its axes as a reader says them, with their units
/// ("mass (kg)"), not by the YAML keys (`mass_kg`): the small search of `design_search.rs`
/// minimises mass and contact pressure, so the x axis is the mass in kg and the y axis the
/// contact pressure in MPa (the units README gives these objectives), and no text of the plot
/// is a key with underscores.
#[test]
fn the_front_plot_names_its_axes_in_words_with_units() {
    let dir = Scratch::new("front-axes");
    dir.write("small.yaml", crate::design_search::SMALL);
    let out = run(&dir.path, &["design", "small.yaml", "--out", "front"]);
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    let els = elements(&dir.read("front/front-1.svg"));
    let texts: Vec<&str> = els
        .iter()
        .filter(|e| e.name == "text")
        .map(|e| e.text.as_str())
        .collect();
    assert!(texts.contains(&"mass (kg)"), "x axis: {texts:?}");
    assert!(
        texts.contains(&"max contact pressure (MPa)"),
        "y axis: {texts:?}"
    );
    assert!(!texts.iter().any(|t| t.contains('_')), "a key: {texts:?}");
}

/// `cycloid check specs/reducer-misaligned.yaml --report review` in a scratch directory named
/// after `tag`: the directory and the run (exit 0 asserted).
fn misaligned_review(tag: &str) -> (Scratch, crate::common::Run) {
    let dir = Scratch::new(tag);
    let spec = format!(
        "{}/specs/reducer-misaligned.yaml",
        env!("CARGO_MANIFEST_DIR")
    );
    let out = run(&dir.path, &["check", &spec, "--report", "review"]);
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    (dir, out)
}

/// The face-width plot's legend gives the tilt as the spec writes it: `reducer-misaligned.yaml`
/// tilts by 0.3 mrad about x and y, which reads "0.3 mrad", not "0.3000 mrad" (four
/// significant figures claim a precision the input never had).
#[test]
fn the_face_plot_legend_gives_the_tilt_as_the_spec_writes_it() {
    let (dir, _) = misaligned_review("face-legend");
    let els = elements(&dir.read("review/face-2-misaligned.svg"));
    let legend: Vec<&str> = els
        .iter()
        .filter(|e| e.name == "text" && e.text.starts_with("tilted"))
        .map(|e| e.text.as_str())
        .collect();
    assert_eq!(legend, ["tilted θx 0.3 mrad, θy 0.3 mrad"]);
}

/// The face-width plot is drawn at the worst face load factor's crank angle, whose peak need
/// not be the scene's max line load: on `reducer-misaligned.yaml` the plotted peak is well
/// under the check's max line load. The plot says where that max is, with the same value and
/// place the terminal's check table prints (one number, the same in every output).
#[test]
fn the_face_plot_names_the_scenes_max_line_load_as_the_table_does() {
    let (dir, out) = misaligned_review("face-max");
    let row = out
        .stdout
        .lines()
        .find(|l| l.starts_with("misaligned/max_line_load_n_per_mm"))
        .unwrap();
    let cells: Vec<&str> = row.split("  ").filter(|c| !c.trim().is_empty()).collect();
    let (value, place) = (cells[1].trim(), cells[4].trim());
    let svg = dir.read("review/face-2-misaligned.svg");
    let text: String = elements(&svg)
        .iter()
        .filter(|e| e.name == "text")
        .map(|e| e.text.clone())
        .collect::<Vec<_>>()
        .join(" ");
    let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let want = format!("the scene's max line load, {value}, is at {place}");
    assert!(text.contains(&want), "{want:?} not in {text:?}");
}

/// The face-width plot draws the whole face (review of the outputs, item 3): on
/// `reducer-misaligned.yaml` (B = 8 mm, 20 slices) the x axis spans −B/2…B/2 with round ticks
/// every 2 mm (−4, −2, 0, 2, 4), and each curve is a step per slice: its 20 line loads (each the
/// mean over its slice) held over their slices' widths, B/20 each, from the face's one end to
/// the other. Points are written to 0.01 px: 0.02 px covers the rounding of both ends.
#[test]
fn the_face_plot_spans_the_face_with_a_step_per_slice() {
    let (dir, _) = misaligned_review("face-steps");
    let els = elements(&dir.read("review/face-2-misaligned.svg"));
    let (left, top, width, height) = plot_area(&els);
    let bottom = top + height;
    let ticks: Vec<&str> = els
        .iter()
        .filter(|e| {
            e.name == "text"
                && e.attr("text-anchor") == "middle"
                && e.attr("font-size") == "12"
                && e.num("y") > bottom
                && e.num("y") < bottom + 25.0
        })
        .map(|e| e.text.as_str())
        .collect();
    assert_eq!(ticks, ["−4", "−2", "0", "2", "4"]);
    let curves: Vec<Vec<(f64, f64)>> = els
        .iter()
        .filter(|e| e.name == "polyline" && e.inside("series"))
        .map(|e| point_list(e.attr("points")))
        .collect();
    assert_eq!(curves.len(), 2, "tilted and designed");
    let slice = width / 20.0;
    for c in &curves {
        assert_eq!(c.len(), 40, "two points per slice");
        assert!((c[0].0 - left).abs() <= 0.02, "{:?} from {left}", c[0]);
        assert!((c[39].0 - (left + width)).abs() <= 0.02, "{:?}", c[39]);
        for s in 0..20 {
            let (a, b) = (c[2 * s], c[2 * s + 1]);
            assert_eq!(a.1, b.1, "slice {s}: one line load across it");
            assert!((b.0 - a.0 - slice).abs() <= 0.02, "slice {s}: {a:?} {b:?}");
            assert!((a.0 - (left + s as f64 * slice)).abs() <= 0.02, "slice {s}");
        }
    }
}

/// `cycloid design`'s front plot has a title naming what it plots, in words with units, and
/// a line saying what its points are and which way each objective is better (review of the
/// outputs, item 4): the small search of `design_search.rs` minimises mass and contact
/// pressure over 11 designs.
#[test]
fn the_front_plot_has_a_title() {
    let dir = Scratch::new("front-title");
    dir.write("small.yaml", crate::design_search::SMALL);
    let out = run(&dir.path, &["design", "small.yaml", "--out", "front"]);
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    let els = elements(&dir.read("front/front-1.svg"));
    assert_eq!(
        title(&els),
        "Pareto front: max contact pressure (MPa) against mass (kg)"
    );
    let n = out
        .stdout
        .lines()
        .find_map(|l| l.strip_prefix("Pareto front, "))
        .and_then(|l| l.split(' ').next())
        .expect("the front's count");
    let subtitle = format!(
        "{n} designs, numbered as in the table; mass minimised, max contact pressure minimised"
    );
    assert!(
        els.iter().any(|e| e.name == "text" && e.text == subtitle),
        "{subtitle}"
    );
}

/// The y pixel of `value` on a line plot's y axis, read from its tick labels (right-aligned
/// text left of the plot area, each 4 px under its tick's line): the axis is linear, so the
/// two outer ticks fix it.
fn y_of(els: &[El], value: f64) -> f64 {
    let (left, ..) = plot_area(els);
    let ticks: Vec<(f64, f64)> = els
        .iter()
        .filter(|e| e.name == "text" && e.attr("text-anchor") == "end" && e.num("x") < left)
        .map(|e| (e.text.replace('−', "-").parse().unwrap(), e.num("y") - 4.0))
        .collect();
    let (a, b) = (ticks[0], ticks[ticks.len() - 1]);
    a.1 + (value - a.0) * (b.1 - a.1) / (b.0 - a.0)
}

/// The dashed reference lines drawn across a line plot's area (not the legend's swatches,
/// which start right of it): (colour, y pixel).
fn reference_lines(els: &[El]) -> Vec<(String, f64)> {
    let (left, ..) = plot_area(els);
    els.iter()
        .filter(|e| e.name == "line" && e.attr("stroke-dasharray") == "7 4")
        .filter(|e| (e.num("x1") - left).abs() < 0.01)
        .map(|e| (e.attr("stroke").to_string(), e.num("y1")))
        .collect()
}

/// Dashed red is a limit everywhere in the review, the efficiency plot included (issue 44,
/// item 6): on `reducer-efficiency.yaml` driven backwards (−20 N·m) the one red dashed line is
/// `min_mean_efficiency: 0.85`, at 0.85 on the axis (0.02 px: two decimals of each pixel
/// written), and the scene's own point is a mark, not red, whose legend keeps the torque's
/// sign: "the scene: −20.00 N·m". Before, a red dashed line sat at the scene's own efficiency
/// and the torque read "20.00 N·m".
#[test]
fn the_efficiency_plot_draws_its_limit_and_the_scene_with_its_signed_torque() {
    let dir = Scratch::new("review-efficiency-limit");
    let text = std::fs::read_to_string(format!(
        "{}/specs/reducer-efficiency.yaml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let edited = text.replace("output_torque_nm: 20.0 ", "output_torque_nm: -20.0 ");
    assert_ne!(edited, text);
    assert!(text.contains("min_mean_efficiency: 0.85"));
    dir.write("spec.yaml", edited);
    let out = run(&dir.path, &["check", "spec.yaml", "--report", "r"]);
    assert!(matches!(out.code, Some(0 | 1)), "{out:?}");
    let els = elements(&dir.read("r/efficiency-1.svg"));
    let lines = reference_lines(&els);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert_eq!(lines[0].0, "#d62728");
    let at = y_of(&els, 0.85);
    assert!((lines[0].1 - at).abs() <= 0.02, "{lines:?}: 0.85 at {at}");
    let scene = els
        .iter()
        .find(|e| e.class() == "series" && e.attr("aria-label").starts_with("the scene: "))
        .expect("the scene's point");
    assert!(
        scene
            .attr("aria-label")
            .starts_with("the scene: −20.00 N·m, "),
        "{}",
        scene.attr("aria-label")
    );
    let marks: Vec<&El> = els
        .iter()
        .filter(|e| e.class() == "mark" && e.within.iter().any(|c| c == "series"))
        .collect();
    assert_eq!(marks.len(), 1, "one mark, the scene's");
    assert!(
        !marks[0].attrs.values().any(|v| v == "#d62728"),
        "{:?}",
        marks[0]
    );
}

/// The face load factor against the crank angle (issue 44, item 8): `reducer-misaligned.yaml`'s
/// tilted scene draws one curve over its 10800 crank angles (0–1080° at 0.1°: whole periods of
/// the tilted reducer as run, which the spec gives) whose largest value is the check
/// table's `max_face_load_factor` (to the table's 4 digits and 0.02 px of drawing), with the
/// spec's limit 3.5 dashed red and the uniform face's 1 dashed grey.
#[test]
fn the_face_load_factor_is_plotted_against_the_crank_angle() {
    let (dir, out) = misaligned_review("face-factor");
    let row = out
        .stdout
        .lines()
        .find(|l| l.starts_with("misaligned/max_face_load_factor"))
        .unwrap();
    let cells: Vec<&str> = row.split("  ").filter(|c| !c.trim().is_empty()).collect();
    let table: f64 = cells[1].trim().parse().unwrap();
    let els = elements(&dir.read("review/scene-2-misaligned-face-load-factor.svg"));
    assert!(
        title(&els).starts_with("Face load factor"),
        "{}",
        title(&els)
    );
    let curve = els
        .iter()
        .find(|e| e.name == "polyline" && e.inside("series"))
        .unwrap();
    let points = point_list(curve.attr("points"));
    assert_eq!(points.len(), 10800);
    let top = points.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    // The table rounds to 4 digits (±5e-4 at 3.0); a pixel is written to 0.01.
    let slack = (y_of(&els, table + 5e-4) - y_of(&els, table)).abs() + 0.02;
    assert!(
        (top - y_of(&els, table)).abs() <= slack,
        "{top} against {table}"
    );
    let lines = reference_lines(&els);
    let red: Vec<f64> = lines
        .iter()
        .filter(|l| l.0 == "#d62728")
        .map(|l| l.1)
        .collect();
    let grey: Vec<f64> = lines
        .iter()
        .filter(|l| l.0 != "#d62728")
        .map(|l| l.1)
        .collect();
    assert_eq!(red.len(), 1, "{lines:?}");
    assert!((red[0] - y_of(&els, 3.5)).abs() <= 0.02, "{lines:?}");
    assert_eq!(grey.len(), 1, "{lines:?}");
    assert!((grey[0] - y_of(&els, 1.0)).abs() <= 0.02, "{lines:?}");
}

/// A crowned, aligned scene gets its face plot too, at the angle of its largest line load,
/// and each face plot names its angle and why, first thing under its title (issue 44, item 8): `reducer-misaligned.yaml`'s
/// `designed` scene (crowned, aligned) draws one curve whose peak is the check table's
/// `max_line_load_n_per_mm` of that scene, at the roller and angle the table names; the tilted
/// scene's title names the largest face load factor.
#[test]
fn a_crowned_aligned_scene_draws_its_face_at_its_largest_line_load() {
    let (dir, out) = misaligned_review("face-crowned");
    let row = out
        .stdout
        .lines()
        .find(|l| l.starts_with("designed/max_line_load_n_per_mm"))
        .unwrap();
    let cells: Vec<&str> = row.split("  ").filter(|c| !c.trim().is_empty()).collect();
    let (value, place) = (cells[1].trim(), cells[4].trim());
    let value: f64 = value.trim_end_matches(" N/mm").parse().unwrap();
    // "roller 3 at crank 12.30°, slice …": the roller and the angle.
    let (roller, rest) = place.split_once(" at ").unwrap();
    let crank = rest.split(',').next().unwrap();
    let els = elements(&dir.read("review/face-1-designed.svg"));
    let subtitle = |els: &[El]| -> String {
        let lines = els
            .iter()
            .filter(|e| e.name == "text" && e.attr("fill") == "#555");
        lines.map(|e| e.text.clone()).collect::<Vec<_>>().join(" ")
    };
    let want = format!("at {crank}, the scene's largest line load: {roller}; ");
    assert!(
        subtitle(&els).starts_with(&want),
        "{want:?} / {:?}",
        subtitle(&els)
    );
    let curves: Vec<Vec<(f64, f64)>> = els
        .iter()
        .filter(|e| e.name == "polyline" && e.inside("series"))
        .map(|e| point_list(e.attr("points")))
        .collect();
    assert_eq!(curves.len(), 1, "aligned: no designed curve beside it");
    let top = curves[0].iter().map(|p| p.1).fold(f64::MAX, f64::min);
    // The table rounds to 4 digits; a pixel is written to 0.01.
    let slack = (y_of(&els, value * (1.0 + 5e-4)) - y_of(&els, value)).abs() + 0.02;
    assert!(
        (top - y_of(&els, value)).abs() <= slack,
        "{top} against {value}"
    );
    let tilted = elements(&dir.read("review/face-2-misaligned.svg"));
    let names = subtitle(&tilted);
    // The angle the check table gives the tilted scene's largest factor at.
    let factor = out
        .stdout
        .lines()
        .find(|l| l.starts_with("misaligned/max_face_load_factor"))
        .unwrap();
    let at = factor
        .split("  ")
        .filter(|c| !c.trim().is_empty())
        .nth(4)
        .unwrap();
    let want = format!(
        "at {}, the scene's largest face load factor: roller ",
        at.trim()
    );
    assert!(names.starts_with(&want), "{want:?} / {names:?}");
}

/// The duty cycle's pictures (issue 44, item 7) on `reducer-duty-cycle.yaml` (30 N·m at
/// 1000 rpm 20 %, 15 N·m at 2000 rpm 40 %, −20 N·m at 1000 rpm 20 %, 8 N·m standing 20 %):
/// the load spectrum's bars are as wide as the time shares (0.2, 0.4, 0.2, 0.2 of the axis),
/// as tall as the torques (30 : 15 : 20 : 8, the braking bin below the zero line) and speeds
/// (1 : 2 : 1 : 0); the shares' bars are the time shares, the revolution shares sᵢ·nᵢ/Σ sⱼ·nⱼ
/// (0.2·1000/1200, 0.4·2000/1200, …) and the bearing damage shares by Miner's rule
/// sᵢ·nᵢ·Pᵢ^p/Σ sⱼ·nⱼ·Pⱼ^p, computed here from each bin's own equivalent load Pᵢ (its run's
/// ordinary bearing life) with p = 10/3. Pixels are written to 0.01: 0.03 px covers a bar's
/// two rounded ends.
#[test]
fn the_duty_cycle_is_drawn_as_its_spectrum_and_each_bins_shares() {
    let dir = Scratch::new("review-duty");
    let path = format!(
        "{}/specs/reducer-duty-cycle.yaml",
        env!("CARGO_MANIFEST_DIR")
    );
    let out = run(&dir.path, &["check", &path, "--report", "r"]);
    assert_eq!(out.code, Some(0), "{out:?}");
    let bins = [
        (30.0, 1000.0, 0.2),
        (15.0, 2000.0, 0.4),
        (-20.0, 1000.0, 0.2),
        (8.0, 0.0, 0.2),
    ];
    let spectrum = elements(&dir.read("r/duty-1-robot-joint-spectrum.svg"));
    let (left, _, width, _) = plot_area(&spectrum);
    let bars = |els: &[El], class: &str| -> Vec<(f64, f64, f64, f64)> {
        els.iter()
            .filter(|e| e.name == "rect" && e.class() == class)
            .map(|e| (e.num("x"), e.num("y"), e.num("width"), e.num("height")))
            .collect()
    };
    let torque = bars(&spectrum, "torque");
    let speed = bars(&spectrum, "speed");
    assert_eq!((torque.len(), speed.len()), (4, 4));
    let mut start = 0.0;
    for (i, &(t, n, share)) in bins.iter().enumerate() {
        for b in [torque[i], speed[i]] {
            assert!(
                (b.0 - (left + start * width)).abs() <= 0.03,
                "bin {i}: {b:?}"
            );
            assert!((b.2 - share * width).abs() <= 0.03, "bin {i}: {b:?}");
        }
        start += share;
        // Heights in proportion to |T| and n, against the first bin's.
        let (h0, s0) = (torque[0].3, speed[0].3);
        assert!(
            (torque[i].3 - h0 * f64::abs(t) / 30.0).abs() <= 0.03,
            "bin {i}"
        );
        assert!((speed[i].3 - s0 * n / 1000.0).abs() <= 0.03, "bin {i}");
    }
    // The braking bin hangs from the zero line, where the others stand.
    let zero = torque[0].1 + torque[0].3;
    assert!((torque[2].1 - zero).abs() <= 0.03, "{torque:?}");

    let spec = cycloid::spec::load(&path).unwrap();
    let result = cycloid::check(&spec, &cycloid::CheckOptions::default(), &Silent).unwrap();
    let duty = result.results[0].duty.as_ref().unwrap();
    let p = 10.0 / 3.0;
    let loads: Vec<f64> = (duty.bins.iter())
        .map(|b| b.result.discs[0].bearing_life.unwrap().equivalent_load_n)
        .collect();
    let damage: Vec<f64> = (bins.iter().zip(&loads))
        .map(|(&(_, n, s), &l)| s * n * l.powf(p))
        .collect();
    let total: f64 = damage.iter().sum();
    let revolutions: f64 = bins.iter().map(|b| b.2 * b.1).sum();
    let shares = elements(&dir.read("r/duty-1-robot-joint-shares.svg"));
    let (_, top, _, height) = plot_area(&shares);
    let zero = y_of(&shares, 0.0);
    assert!((zero - (top + height)).abs() <= 0.03, "shares start at 0 %");
    let per_percent = (zero - y_of(&shares, 100.0)) / 100.0;
    for (class, want) in [
        ("time-share", bins.map(|b| b.2).to_vec()),
        (
            "revolution-share",
            bins.map(|b| b.2 * b.1 / revolutions).to_vec(),
        ),
        ("damage-share", damage.iter().map(|d| d / total).collect()),
    ] {
        let got = bars(&shares, class);
        assert_eq!(got.len(), 4, "{class}");
        for (i, (b, w)) in got.iter().zip(&want).enumerate() {
            assert!(
                (b.3 - 100.0 * w * per_percent).abs() <= 0.03,
                "{class} bin {i}: {b:?} {w}"
            );
        }
    }
}

/// Each front design has its own review page (issue 44, item 5): `DIR/design-01/index.html`
/// and its figures are, byte for byte, what `cycloid check design-01.yaml --report DIR` writes
/// beside the spec (the same function; the date pinned), and the front's table links it from
/// the design's row with a small drawing of its disc: the profile with its holes, the 10
/// rollers and the 6 pins of the small search's designs. The table scrolls sideways (the
/// objective columns were off a 1280 px window with no way to reach them) and no raw Markdown
/// backtick shows.
#[test]
fn each_front_design_has_its_own_review_linked_from_its_row() {
    let dir = Scratch::new("front-reviews");
    dir.write("small.yaml", crate::design_search::SMALL);
    let out = run(&dir.path, &["design", "small.yaml", "--out", "front"]);
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    let page = dir.read("front/index.html");
    assert!(!page.contains('`'), "a raw backtick on the page");
    assert!(
        page.contains("<div class=\"scroll\"><table>"),
        "the table scrolls"
    );
    assert!(
        page.contains(".scroll{overflow-x:auto"),
        "the table scrolls"
    );
    let designs = dir.read("front/front.csv").lines().count() - 1;
    assert!(designs >= 2);
    for k in [1, designs] {
        let name = format!("design-{k:02}");
        let row = format!("<a href=\"{name}/index.html\"><img src=\"{name}/disc-small.svg\"");
        assert!(page.contains(&row), "{row}");
        let check = run(
            &dir.join("front"),
            &["check", &format!("{name}.yaml"), "--report", "alone"],
        );
        assert_eq!(check.code, Some(0), "{check:?}");
        let mut written = crate::common::files(&dir.join(&format!("front/{name}")));
        let thumbnail = written.remove("disc-small.svg").expect("a small disc");
        assert_eq!(
            written,
            crate::common::files(&dir.join("front/alone")),
            "{name}"
        );
        std::fs::remove_dir_all(dir.join("front/alone")).unwrap();
        let els = elements(std::str::from_utf8(&thumbnail).unwrap());
        assert_eq!(els.iter().filter(|e| e.class() == "profile").count(), 1);
        let circles = els.iter().filter(|e| e.name == "circle").count();
        assert_eq!(circles, 10 + 6, "{name}: rollers and pins");
    }
}

/// The solid beside the disc drawing (issue 43, item 6), read back from `disc-solid.svg`: the
/// paper's disc with a 16 mm bore, seen isometrically from the +x, −y side above (the caption's
/// view), every polygon a facet facing the viewer and inside the disc's bounding cylinder, the
/// top face a whole triangulation of a face with 7 holes.
#[test]
fn the_solid_picture_draws_the_facets_facing_the_viewer_inside_the_discs_cylinder() {
    use crate::common::PaperSpec;
    let dir = Scratch::new("review-solid");
    let bore =
        "reducer:\n  crank_bearing: {dynamic_load_rating_n: 12000.0, outer_diameter_mm: 16.0}\n";
    dir.write(
        "disc.yaml",
        PaperSpec::new().edit("reducer:\n", bore).text(),
    );
    let out = run(&dir.path, &["check", "disc.yaml", "--report", "r"]);
    assert_eq!(out.code, Some(0), "{out:?}");
    let html = dir.read("r/index.html");
    assert!(html.contains("src=\"disc-solid.svg\""));
    for named in [
        "Isometric view",
        "Face width B = 8.000 mm",
        "bore ⌀ 16.00 mm",
    ] {
        assert!(html.contains(named), "the caption lacks `{named}`");
    }
    let svg = dir.read("r/disc-solid.svg");
    assert!(svg.len() < 1_000_000, "{} bytes", svg.len());
    let els = elements(&svg);
    let group = els.iter().find(|e| e.class() == "solid").unwrap();
    assert!(group.attr("transform").starts_with("translate("));
    // Isometric from v = (1, −1, 1)/√3: screen right r = ẑ × v = (1, 1, 0)/√2, up u = v × r =
    // (−1, 1, 2)/√6; a point (x, y, z) is drawn at X = p·r, Y = −p·u (mm, y down). Inverted at
    // height z: x = a + z, y = b − z with a, b below.
    let (s2, s6) = (2f64.sqrt(), 6f64.sqrt());
    let (b_mm, bore_mm) = (8.0, 8.0);
    // The modified profile's largest radius, at the tooth tip where its normal is radial:
    // (Rp + ΔRp) + e − (Rrp + ΔRrp) (MODEL.md's profile with the paper's optimum).
    let tip_mm = 30.0 + 0.125 + 2.0 - (3.0 + 0.1593);
    // The nearest a point drawn at (X, Y) comes to the axis over z in [0, B], and at z = B.
    let radius_at = |(x, y): (f64, f64), z: f64| {
        let (a, b) = ((s2 * x + s6 * y) / 2.0, (s2 * x - s6 * y) / 2.0);
        ((a + z).powi(2) + (b - z).powi(2)).sqrt()
    };
    let nearest = |p: (f64, f64)| radius_at(p, (-s6 * p.1 / 2.0).clamp(0.0, b_mm));
    // Coordinates are written to 1 µm (0.5 µm rounding each): 2 µm covers a point's error.
    let rounding = 2e-3;
    let (mut faces, mut walls, mut widest) = (Vec::new(), 0, 0.0f64);
    for p in els
        .iter()
        .filter(|e| e.name == "polygon" && e.inside("solid"))
    {
        let pts = point_list(p.attr("points"));
        assert_eq!(pts.len(), 3);
        for &q in &pts {
            let r = nearest(q);
            assert!(r <= tip_mm + rounding, "{q:?} is {r} mm from the axis");
            widest = widest.max(r);
        }
        // Shoelace area with y down: a facet counter-clockwise seen from outside (its normal
        // toward the viewer) is clockwise on the screen, negative. The rounding moves a wall
        // strip's (B = 8 mm tall) area by at most 8 mm · 2 µm.
        let area = 0.5
            * (0..3)
                .map(|i| {
                    let (p, q) = (pts[i], pts[(i + 1) % 3]);
                    p.0 * q.1 - q.0 * p.1
                })
                .sum::<f64>();
        assert!(area < b_mm * rounding, "a back-facing facet drawn: {pts:?}");
        match p.class() {
            "face" => {
                // On the top face z = B, and outside the bore.
                for &q in &pts {
                    let r = radius_at(q, b_mm);
                    assert!(r <= tip_mm + rounding && r >= bore_mm - 0.1, "{q:?}: {r}");
                }
                faces.push(pts);
            }
            "wall" => walls += 1,
            c => panic!("polygon of class {c}"),
        }
    }
    // The silhouette reaches the tips (within a chord's sag and the rounding).
    assert!(widest > tip_mm - 0.05, "widest {widest} mm");
    // The top face is whole: a triangulated face of V vertices and H = 6 + 1 holes has
    // V + 2H − 2 triangles (Euler's formula).
    let vertices: std::collections::HashSet<String> = (faces.iter().flatten())
        .map(|(x, y)| format!("{x},{y}"))
        .collect();
    assert_eq!(faces.len(), vertices.len() + 2 * 7 - 2);
    // Walls facing the viewer: about half of the outline's and the holes' facets, and some.
    assert!(walls > 100, "{walls} walls");
}
