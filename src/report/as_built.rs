//! The design review's section on the disc as built (`measured_profile:`): what was
//! identified, the measured points' deviation and the fitted form error along the profile
//! (micrometres: the scale is stated, the profile itself is tens of millimetres), and each
//! scene's headline results as designed beside as built.

use super::html::{data_table, figure, section, Section};
use super::svg::{LinePlot, Series, PALETTE};
use super::table::{count_or_number, with_unit};
use crate::engine::summary::{summarise, SceneSummary};
use crate::geometry::profile::Profile;
use crate::measure::fit::Identification;
use crate::model::results::SceneResult;
use crate::model::Modification;
use crate::numeric::number;
use crate::spec::Spec;
use crate::units;
use maud::html;

/// What the section shows: the identification and the results of the spec as designed (the
/// report's own results are those as built).
pub struct AsBuiltView<'a> {
    pub identification: &'a Identification,
    /// The spec's own modification, as designed.
    pub designed_modification: Modification,
    pub designed: &'a [SceneResult],
}

/// The section, its figure added to `files`.
pub(super) fn section_of(
    spec: &Spec,
    view: &AsBuiltView,
    built: &[SceneResult],
    files: &mut Vec<(String, String)>,
) -> Section {
    let id = view.identification;
    let (designed, as_built) = (summarise(view.designed), summarise(built));
    let file = "as-built-deviation.svg";
    let from_design = design_deviation_um(spec, &view.designed_modification, id);
    files.push((file.into(), deviation_plot(id, &from_design).to_svg()));
    let um = |mm: f64| format!("{} µm", number(mm * 1e3));
    let m = (&view.designed_modification, &id.modification);
    let body = html! {
        p.note { "Every scene ran on the disc identified from "
            code { (spec.measured.as_ref().map_or("", |m| m.path.as_str())) }
            ": its modification and form error, exact geometry. Beside each result, the same \
             scene on the disc as designed." }
        (data_table(
            html! { th { "" } th { "designed" } th { "as built" } th { "change" } },
            html! {
                tr { th { "shift ΔRp" } td.num { (number(m.0.shift_mm)) " mm" }
                    td.num { (number(m.1.shift_mm)) " mm" }
                    td.num { (um(m.1.shift_mm - m.0.shift_mm)) } }
                tr { th { "equidistant ΔRrp" } td.num { (number(m.0.equidistant_mm)) " mm" }
                    td.num { (number(m.1.equidistant_mm)) " mm" }
                    td.num { (um(m.1.equidistant_mm - m.0.equidistant_mm)) } }
                tr { th { "form error" } td { "none" }
                    td { (id.form.harmonics.len()) " harmonics, |w| ≤ "
                        (um(id.form.harmonics.iter().map(|h| h.amplitude_mm()).sum())) }
                    td { "residual RMS " (um(id.residual_rms_mm)) } }
                @for (d, b) in designed.iter().zip(&as_built) { (rows(d, b)) }
            },
        ))
        (figure(file, "Measured deviation from the profile",
            "Along the profile (locus parameter t over the whole disc), in µm normal to it, \
             positive where material is missing: the measured points against the design \
             profile (vs design: the spec's modification), the same points against the \
             identified profile (vs identified: its modification; the fitted form error plus \
             each point's residual), \
             and the fitted form error w(t). The disc is tens of millimetres across; these \
             are micrometres."))
    };
    section("as-built", html! { "Disc as built" }, body)
}

/// A scene's headline results as designed and as built.
fn rows(designed: &SceneSummary, built: &SceneSummary) -> maud::Markup {
    html! {
        @for (k, (d, b)) in designed.headlines.iter().zip(&built.headlines).enumerate() {
            tr {
                th { @if k == 0 { code { (designed.scene) } " " } (d.quantity.label) }
                td.num { (with_unit(count_or_number(d.value, d.quantity.unit), d.quantity.unit)) }
                td.num { (with_unit(count_or_number(b.value, b.quantity.unit), b.quantity.unit)) }
                td.num { (with_unit(number(b.value - d.value), d.quantity.unit)) }
            }
        }
    }
}

/// Each measured point's deviation from the design profile, µm (positive: material missing),
/// sorted by t: the point, placed in the disc frame as the fit left it (on the identified
/// profile, moved inward by its deviation from it, w(t) plus its residual), measured by its
/// signed distance to the profile of the spec's modification (exact closest point).
fn design_deviation_um(
    spec: &Spec,
    designed: &Modification,
    id: &Identification,
) -> Vec<(f64, f64)> {
    let identified = Profile::new(&spec.design, &id.modification);
    let design = Profile::new(&spec.design, designed);
    let mut out: Vec<(f64, f64)> = id
        .profile
        .iter()
        .filter_map(|p| {
            let inward = id.form.value_mm(p.t) + p.residual_mm;
            let q = identified.point(p.t) - identified.normal(p.t) * inward;
            let foot = design.closest_point(q, p.t).ok()?;
            Some((p.t, -foot.signed_distance_mm * 1e3))
        })
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// The points' deviations and the form error, µm against t in degrees.
fn deviation_plot(id: &Identification, from_design: &[(f64, f64)]) -> LinePlot {
    let mut points: Vec<(f64, f64)> = id
        .profile
        .iter()
        .map(|p| (p.t, id.form.value_mm(p.t) + p.residual_mm))
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let degrees = |t: f64| units::deg(t.rem_euclid(std::f64::consts::TAU));
    let curve: Vec<f64> = (0..=720)
        .map(|k| std::f64::consts::TAU * k as f64 / 720.0)
        .collect();
    let mut plot = LinePlot::new(
        "Measured deviation from the profile",
        "locus parameter t (deg)",
        "normal deviation (µm)",
    );
    plot.series.push(Series::new(
        "vs design",
        from_design.iter().map(|p| degrees(p.0)).collect(),
        from_design.iter().map(|p| p.1).collect(),
        PALETTE[3],
    ));
    plot.series.push(Series::new(
        "vs identified",
        points.iter().map(|p| degrees(p.0)).collect(),
        points.iter().map(|p| p.1 * 1e3).collect(),
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
