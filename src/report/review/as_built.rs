//! The design review's section on the disc as built (`measured_profile:`): what was
//! identified, the measured points' deviation and the fitted form error along the profile
//! (micrometres: the scale is stated, the profile itself is tens of millimetres), and each
//! scene's headline results as designed beside as built.

use super::common::{data_table, figure, Section};
use super::disc::hole_cutouts;
use crate::engine::summary::{summarise, SceneSummary};
use crate::geometry::profile::Profile;
use crate::geometry::{polyline, Vec2};
use crate::measure::fit::{coverage_bin_rad, Identification};
use crate::model::quantity::TE;
use crate::model::results::SceneResult;
use crate::model::Modification;
use crate::numeric::{fixed, fixed_change};
use crate::numeric::{number, with_unit};
use crate::report::fit::flank_length_mm;
use crate::report::svg::frame::{titles, wrap, Frame};
use crate::report::svg::ticks::log_label;
use crate::report::svg::{self, document, px, LinePlot, Series, PALETTE, RED};
use crate::report::table::figure_change;
use crate::spec::Spec;
use crate::units;
use maud::html;
use std::f64::consts::TAU;

/// What the section shows: the identification and the results of the spec as designed (the
/// report's own results are those as built).
pub struct AsBuiltView<'a> {
    pub identification: &'a Identification,
    /// The spec's own modification, as designed.
    pub designed_modification: Modification,
    pub designed: &'a [SceneResult],
}

/// The section, its figure added to `files`.
pub(super) fn section(
    spec: &Spec,
    view: &AsBuiltView,
    built: &[SceneResult],
    files: &mut Vec<(String, String)>,
) -> Section {
    let id = view.identification;
    let (designed, as_built) = (summarise(view.designed), summarise(built));
    let file = "as-built-deviation.svg";
    let from_design = against_design(spec, &view.designed_modification, id);
    files.push((
        file.into(),
        deviation_plot(id, &from_design, spec.design.teeth).to_svg(),
    ));
    let mut comparisons = Vec::new();
    for (name, plot, caption) in comparison_plots(view.designed, built) {
        files.push((name.clone(), plot.to_svg()));
        comparisons.push((name, plot.title, caption));
    }
    let drawing_file = "as-built-disc.svg";
    let (drawing, times) = disc_drawing(spec, &view.designed_modification, &from_design);
    files.push((drawing_file.into(), drawing));
    let times = log_label(times);
    // Micrometres to the nanometre, as `cycloid fit` prints them: a change at the round-off
    // of the fit reads 0.000 µm (not 6.134e-12 µm, nor −0.000).
    let um = |mm: f64| format!("{} µm", fixed(units::um(mm), 3));
    // A change is signed, as the results' changes below are (`numeric::change`).
    let um_change = |mm: f64| format!("{} µm", fixed_change(units::um(mm), 3));
    let m = (&view.designed_modification, &id.modification);
    let body = html! {
        p.note { "Every scene ran on the disc identified from "
            code { (spec.measured.as_ref().map_or("", |m| m.path.as_str())) }
            ": its modification and form error, exact geometry. Beside each result, the same \
             scene on the disc as designed." }
        @if let Some(t) = id.thinning {
            p { "Thinned: every " (crate::report::fit::ordinal(t.every)) " of " (t.of) " profile points (" (t.used)
                " used, hole points all kept): the scan is denser than the fit holds; the \
                 residuals and plots are those of the points used." }
        }
        (data_table(
            html! { th { "" } th { "designed" } th { "as built" } th { "change" } },
            html! {
                tr { th { "shift ΔRp" } td.num { (number(m.0.shift_mm)) " mm" }
                    td.num { (number(m.1.shift_mm)) " mm" }
                    td.num { (um_change(m.1.shift_mm - m.0.shift_mm)) } }
                tr { th { "equidistant ΔRrp" } td.num { (number(m.0.equidistant_mm)) " mm" }
                    td.num { (number(m.1.equidistant_mm)) " mm" }
                    td.num { (um_change(m.1.equidistant_mm - m.0.equidistant_mm)) } }
                tr { th { "form error" } td { "none" }
                    td { (id.form.harmonics.len()) " harmonics, |w| ≤ "
                        (um(id.form.harmonics.iter().map(|h| h.amplitude_mm()).sum())) }
                    td { "residual RMS " (um(id.residual_rms_mm)) } }
                @for (d, b) in designed.iter().zip(&as_built) { (rows(d, b)) }
            },
        ))
        @for (file, title, caption) in &comparisons {
            (figure(file, title, caption))
        }
        (figure(file, "Measured deviation from the profile",
            "Along the profile (locus parameter t over the whole disc), in µm normal to it, \
             positive where material is missing: the measured points against the design \
             profile (vs design: the spec's modification), the same points against the \
             identified profile (vs identified: its modification; the fitted form error plus \
             each point's residual), \
             and the fitted form error w(t). The disc is tens of millimetres across; these \
             are micrometres."))
        (figure(drawing_file, &format!("The disc as built against the design, deviation ×{times}"),
            &format!("The disc in its own frame, true scale: blue, the design profile (the \
             spec's modification) with its pin holes, the zero-deviation reference; red, each \
             measured point where the fit placed it, moved along the design profile's normal \
             to {times} times its distance from it (deviation magnified ×{times}; at ×1 the \
             points would sit on the outline), inside the outline where material is missing. \
             The red bar at the bottom left is a deviation at that magnification, the black \
             one 10 mm at true scale. The deviations are those of the vs design series above.")))
        (flank_table(spec, id))
    };
    Section::new("as-built", html! { "Disc as built" }, body)
}

/// Each scene's smallest gap over the rollers and its TE over the crank, as designed (dashed)
/// against as built: (file, plot, caption) of each scene that computes them.
fn comparison_plots(
    designed: &[SceneResult],
    built: &[SceneResult],
) -> Vec<(String, LinePlot, &'static str)> {
    let mut out = Vec::new();
    for (k, (d, b)) in designed.iter().zip(built).enumerate() {
        let x: Vec<f64> = b.crank_rad.iter().map(|&c| units::deg(c)).collect();
        let file = |what: &str| format!("as-built-{}-{what}.svg", k + 1);
        if let (Some(dg), Some(bg)) = (smallest_gap_um(d), smallest_gap_um(b)) {
            let title = format!("{}: smallest gap, designed and as built", b.name);
            let plot = pair_plot(&title, "smallest gap over the rollers (µm)", &x, dg, bg);
            out.push((file("clearance"), plot, CLEARANCE_CAPTION));
        }
        // The registry's TE curve (arcsec): one row.
        let te = |r: &SceneResult| TE.rows(r)?.into_owned().pop();
        if let (Some(dt), Some(bt)) = (te(d), te(b)) {
            let title = format!("{}: TE, designed and as built", b.name);
            let plot = pair_plot(&title, "transmission error (arcsec)", &x, dt, bt);
            out.push((file("te"), plot, TE_CAPTION));
        }
    }
    out
}

const CLEARANCE_CAPTION: &str = "At each of the scene's crank angles the smallest gap of any \
    roller to the disc, µm (negative: interference): the spec's disc dashed, the disc as \
    identified solid. A form error makes the gaps repeat only after several mesh periods: the \
    min clearance in the table above is sought over that whole period, so it can lie outside \
    a scene that covers less.";
const TE_CAPTION: &str = "The loaded transmission error over the crank, arcsec: the spec's \
    disc dashed, the disc as identified solid.";

/// The smallest gap over the rollers at each angle, µm (disc 0's with several discs).
fn smallest_gap_um(r: &SceneResult) -> Option<Vec<f64>> {
    let c = r.discs.first()?.clearance.as_ref()?;
    let smallest = |i: usize| c.gap_mm.iter().map(|g| g[i]).fold(f64::INFINITY, f64::min);
    Some(
        (0..r.crank_rad.len())
            .map(|i| units::um(smallest(i)))
            .collect(),
    )
}

/// One quantity over the crank (degrees), designed dashed against as built.
fn pair_plot(
    title: &str,
    y_label: &str,
    x: &[f64],
    designed: Vec<f64>,
    built: Vec<f64>,
) -> LinePlot {
    let mut plot = LinePlot::new(title, "crank angle (deg)", y_label);
    let mut d = Series::new("designed", x.to_vec(), designed, PALETTE[0]);
    d.dashed = true;
    plot.series.push(d);
    plot.series
        .push(Series::new("as built", x.to_vec(), built, PALETTE[3]));
    plot
}

/// A scene's headline results as designed and as built.
fn rows(designed: &SceneSummary, built: &SceneSummary) -> maud::Markup {
    html! {
        @for (k, (d, b)) in designed.headlines.iter().zip(&built.headlines).enumerate() {
            tr {
                th { @if k == 0 { code { (designed.scene) } " " } (d.quantity.label) }
                td.num { (crate::report::table::headline_value(d)) }
                td.num { (crate::report::table::headline_value(b)) }
                td.num { (with_unit(figure_change(d.quantity, d.value, b.value), d.quantity.unit)) }
            }
        }
    }
}

/// A measured point against the design profile (disc frame, mm): the point where the fit left
/// it (on the identified profile at its foot t, moved inward by its deviation from it, w(t)
/// plus its residual), its foot on the profile of the spec's modification (exact closest
/// point) with the outward normal there, and its deviation from it, positive where material
/// is missing (minus the signed distance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AgainstDesign {
    /// The point's locus parameter on the identified profile, rad.
    pub t: f64,
    pub point: Vec2,
    pub foot: Vec2,
    pub normal: Vec2,
    pub deviation_mm: f64,
}

impl AgainstDesign {
    /// Where a drawing magnifying deviations `m` times puts the point: foot − m·d·N, on the
    /// design profile's normal through the point, m times as far from the outline, on the
    /// same side (inside where material is missing); m = 1 is the point itself.
    pub fn magnified(&self, m: f64) -> Vec2 {
        self.foot - self.normal * (m * self.deviation_mm)
    }
}

/// Every measured profile point against the design profile, sorted by t (a point whose
/// closest-point search fails is left out).
pub fn against_design(
    spec: &Spec,
    designed: &Modification,
    id: &Identification,
) -> Vec<AgainstDesign> {
    let identified = Profile::new(&spec.design, &id.modification);
    let design = Profile::new(&spec.design, designed);
    let mut out: Vec<AgainstDesign> = id
        .profile
        .iter()
        .filter_map(|p| {
            let inward = id.form.value_mm(p.t) + p.residual_mm;
            let q = identified.point(p.t) - identified.normal(p.t) * inward;
            let foot = design.closest_point(q, p.t).ok()?;
            Some(AgainstDesign {
                t: p.t,
                point: q,
                foot: foot.point,
                normal: foot.normal,
                deviation_mm: -foot.signed_distance_mm,
            })
        })
        .collect();
    out.sort_by(|a, b| a.t.total_cmp(&b.t));
    out
}

/// The points' deviations and the form error, µm against t in degrees.
fn deviation_plot(id: &Identification, from_design: &[AgainstDesign], teeth: usize) -> LinePlot {
    // A stretch longer than a coverage bin without a point is unmeasured: the curves break.
    let gap = coverage_bin_rad(teeth);
    let (design_x, design_y) = with_breaks(
        from_design.iter().map(|p| (p.t, units::um(p.deviation_mm))),
        gap,
    );
    let (identified_x, identified_y) = with_breaks(
        (id.profile.iter()).map(|p| (p.t, units::um(id.form.value_mm(p.t) + p.residual_mm))),
        gap,
    );
    let curve: Vec<f64> = (0..=720).map(|k| TAU * k as f64 / 720.0).collect();
    let mut plot = LinePlot::new(
        "Measured deviation from the profile",
        "locus parameter t (deg)",
        "normal deviation (µm)",
    );
    plot.series
        .push(Series::new("vs design", design_x, design_y, PALETTE[3]));
    plot.series.push(Series::new(
        "vs identified",
        identified_x,
        identified_y,
        PALETTE[7],
    ));
    let mut form = Series::new(
        "form error w(t)",
        curve.iter().map(|&t| units::deg(t)).collect(),
        curve.iter().map(|&t| id.form.value_mm(t) * 1e3).collect(),
        PALETTE[0],
    );
    // Dashed, so that the points beneath it show where they leave it.
    form.dashed = true;
    plot.series.push(form);
    plot.include_zero = true;
    plot
}

/// (t in degrees, value) of `points` sorted by t over [0, 2π), with a break (a NaN, which
/// the plot does not join across) wherever consecutive points are more than `gap` rad apart:
/// an unmeasured stretch is not drawn as a line across it.
fn with_breaks(points: impl Iterator<Item = (f64, f64)>, gap: f64) -> (Vec<f64>, Vec<f64>) {
    let mut sorted: Vec<(f64, f64)> = points.map(|(t, v)| (t.rem_euclid(TAU), v)).collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for run in sorted.chunk_by(|a, b| b.0 - a.0 <= gap) {
        if !x.is_empty() {
            x.push(units::deg(run[0].0));
            y.push(f64::NAN);
        }
        x.extend(run.iter().map(|p| units::deg(p.0)));
        y.extend(run.iter().map(|p| p.1));
    }
    (x, y)
}

/// The largest magnified deviation drawn, as a share of the tooth height 2e.
const MAGNIFIED_SHARE_OF_TOOTH: f64 = 0.5;

/// The magnification of the drawing of the disc as built: the largest 1, 2 or 5 × 10^k that
/// draws the largest |deviation| at most `MAGNIFIED_SHARE_OF_TOOTH` of the tooth height (so
/// that magnified points stay on their tooth); 1 when no point deviates (nothing to magnify).
pub fn magnification(largest_mm: f64, tooth_height_mm: f64) -> f64 {
    let raw = MAGNIFIED_SHARE_OF_TOOTH * tooth_height_mm / largest_mm;
    if raw.is_finite() && raw > 1.0 {
        round_down_125(raw)
    } else {
        1.0
    }
}

/// The largest 1, 2 or 5 × 10^k at most `x` (> 0).
fn round_down_125(x: f64) -> f64 {
    let decade = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&m| m <= x * (1.0 + 1e-12))
        .unwrap_or(decade)
}

/// The disc in its own frame at true scale: the design profile (the zero-deviation outline)
/// with its pin holes, and the measured points each on the design profile's normal, their
/// deviation magnified M times (`AgainstDesign::magnified`): (SVG, M). Runs of points closer
/// than 1/16 tooth pitch in t are joined by a line; a dot marks every point (every k-th of more
/// than `MOST_DOTS`).
pub fn disc_drawing(
    spec: &Spec,
    designed: &Modification,
    points: &[AgainstDesign],
) -> (String, f64) {
    const MOST_DOTS: usize = 4000;
    let d = &spec.design;
    let largest = points
        .iter()
        .map(|p| p.deviation_mm.abs())
        .fold(0.0, f64::max);
    let m = magnification(largest, 2.0 * d.eccentricity_mm);
    let design = Profile::new(d, designed);
    // The outline is the zero of the magnified deviations: its chords stay within
    // (Rp + Rrp)/20000 of the curve (0.02 px on this drawing), ten times closer than the disc
    // drawing's, so that they add no visible deviation of their own.
    let outline: Vec<Vec2> = polyline::polyline(
        &design,
        (d.roller_circle_radius_mm + d.roller_radius_mm) / 20000.0,
    )
    .iter()
    .map(|p| p.point)
    .collect();
    let half = outline.iter().map(|p| p.norm()).fold(0.0, f64::max) * 1.06;
    let (w, h) = (660.0, 720.0);
    let f = Frame::fit(
        (-half, half, -half, half),
        (10.0, 70.0, w - 20.0, h - 110.0),
    );
    let holes: Vec<Vec2> = (0..d.pins.count)
        .map(|j| Vec2::from(d.pins.centre_mm(j)))
        .collect();
    let gap = coverage_bin_rad(d.teeth);
    let runs = points.chunk_by(|a, b| b.t - a.t <= gap);
    let stride = points.len().div_ceil(MOST_DOTS).max(1);
    let times = log_label(m);
    let bar_um = round_down_125(units::um(largest.max(1e-6)));
    let title = format!("Disc as built against the design: deviation ×{times}");
    let subtitle = if largest > 0.0 {
        format!(
            "disc frame, true scale. Blue: the design profile, zero deviation; red: each \
             measured point on the design profile's normal, {times} × its deviation away from \
             it, inside where material is missing (largest deviation {} µm)",
            number(units::um(largest))
        )
    } else {
        "disc frame, true scale; the measured points lie on the design outline".to_string()
    };
    let lines = wrap(&subtitle, w - 28.0);
    let body = html! {
        (titles(14.0, &title, &lines))
        path d=(f.path(&outline) + &hole_cutouts(&f, &holes, d.hole_radius_mm())) fill="#cfe0f1"
            fill-rule="evenodd" stroke="#1f4e79" stroke-width="1.2" {}
        @for run in runs.filter(|r| r.len() > 1) {
            polyline points=(svg::points(run.iter().map(|p| f.at(p.magnified(m))))) fill="none"
                stroke=(RED) stroke-width="1.2" {}
        }
        @for p in points.iter().step_by(stride) {
            @let (x, y) = f.at(p.magnified(m));
            circle.measured cx=(px(x)) cy=(px(y)) r="1.6" fill=(RED) {}
        }
        (f.scale_bar(w - 30.0, h - 20.0, 10.0, "10 mm"))
        (deviation_bar(&f, (20.0, h - 20.0), m * bar_um * 1e-3,
            &format!("{} µm deviation, drawn ×{times}", log_label(bar_um))))
    };
    (document(w, h, body), m)
}

/// A bar of `length_mm` (world) from `left` (pixels), its label to its right.
fn deviation_bar(f: &Frame, (left, y): (f64, f64), length_mm: f64, label: &str) -> maud::Markup {
    let right = left + f.len(length_mm);
    html! {
        line x1=(px(left)) y1=(px(y)) x2=(px(right)) y2=(px(y)) stroke=(RED) stroke-width="2" {}
        line x1=(px(left)) y1=(px(y - 4.0)) x2=(px(left)) y2=(px(y + 4.0)) stroke=(RED) {}
        line x1=(px(right)) y1=(px(y - 4.0)) x2=(px(right)) y2=(px(y + 4.0)) stroke=(RED) {}
        text x=(px(right + 8.0)) y=(px(y + 4.0)) font-size="12" { (label) }
    }
}

/// The per-flank summaries of the measured points ([`measure::flanks`](crate::measure::flanks)), as on an inspection
/// sheet: arc length in mm, deviations in µm.
fn flank_table(spec: &Spec, id: &Identification) -> maud::Markup {
    // Fixed decimals as `cycloid fit` prints them: mm to the µm, µm to the nm.
    let (mm, um) = (|v: f64| fixed(v, 3), |v: f64| fixed(units::um(v), 3));
    html! {
        p.note { "Per flank, as on a gear inspection sheet (ISO 1328-1 total F, form f_f and \
            slope f_H deviation) over the arc length s along the profile from the flank's root \
            (each flank " (mm(flank_length_mm(spec, id))) " mm root to tip): \
            the deviation of the measured points from the identified profile (form error plus \
            residual), over each flank's measured extent; f_H > 0: more material missing \
            towards the tip. Flank a runs root to tip with increasing t, b tip to root." }
        (data_table(
            html! { th { "tooth" } th { "flank" } th { "points" } th { "s from (mm)" }
                th { "s to (mm)" } th { "F (µm)" } th { "f_f (µm)" } th { "f_H (µm)" } },
            html! {
                @for f in &id.flanks {
                    tr { td.num { (f.tooth) } td { (f.side) } td.num { (f.points) }
                        @if let Some(s) = f.summary {
                            td.num { (mm(s.from_mm)) } td.num { (mm(s.to_mm)) }
                            td.num { (um(s.total_mm)) } td.num { (um(s.form_mm)) }
                            td.num { (um(s.slope_mm)) }
                        } @else {
                            td colspan="5" { "fewer than 3 points" }
                        }
                    }
                }
            },
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::results::{ClearanceSweep, DiscResult, MinClearance, MinCoverage};

    /// Points more than the gap apart are not joined: a NaN between them; the points come
    /// sorted over [0, 2π) whatever their order and turn (2π + 0.05 is 0.05, first).
    #[test]
    fn an_unmeasured_stretch_breaks_the_curve() {
        let tau = TAU;
        let points = [(1.1, 4.0), (0.2, 2.0), (tau + 0.05, 1.0), (1.0, 3.0)];
        let (x, y) = with_breaks(points.into_iter(), 0.5);
        let deg = |t: f64| units::deg(t);
        assert_eq!(x.len(), 5);
        assert!(y[2].is_nan(), "{y:?}");
        let kept: Vec<(f64, f64)> = x
            .iter()
            .zip(&y)
            .filter(|p| !p.1.is_nan())
            .map(|(a, b)| (*a, *b))
            .collect();
        let expected = [
            (deg(0.05), 1.0),
            (deg(0.2), 2.0),
            (deg(1.0), 3.0),
            (deg(1.1), 4.0),
        ];
        for (k, e) in kept.iter().zip(expected) {
            assert!((k.0 - e.0).abs() < 1e-9 && k.1 == e.1, "{kept:?}");
        }
    }

    /// The smallest gap at each angle is the least over the rollers ([roller][angle]), in µm:
    /// roller 1 is nearest at the first angle, roller 0 at the second.
    #[test]
    fn the_smallest_gap_is_the_least_over_the_rollers_at_each_angle() {
        let disc = DiscResult {
            efficiency: None,
            clearance: Some(ClearanceSweep {
                gap_mm: vec![vec![0.003, 0.001], vec![0.002, 0.005]],
                min: MinClearance {
                    gap_mm: 0.001,
                    roller: 0,
                    crank_rad: 0.1,
                    tooth_phase: 0.0,
                },
                coverage: MinCoverage::Angles(2),
                backlash: None,
            }),
            loaded: Default::default(),
            bearing_life: None,
        };
        let r = SceneResult {
            name: "s".into(),
            crank_rad: vec![0.0, 0.1],
            reducer: Default::default(),
            discs: vec![disc],
            duty: None,
        };
        let got = smallest_gap_um(&r).unwrap();
        assert!(
            (got[0] - 2.0).abs() < 1e-12 && (got[1] - 1.0).abs() < 1e-12,
            "{got:?}"
        );
    }
}
