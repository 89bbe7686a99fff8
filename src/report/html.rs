//! The design-review report (`--report DIR`): `index.html` plus one SVG per plot, for a
//! reviewer who opens it in a browser. No JavaScript; the page links the SVGs with `<img>`.
//!
//! Contents: verdict, spec summary, every check and golden curve with its verdict; a drawing of
//! the disc with rollers, pins and holes at a chosen crank angle (with the contact forces when a
//! scene is loaded) and a close-up of the smallest gap; per scene: clearance per roller,
//! backlash, roller forces, Hertz pressure, loaded TE, ratio, bearing force magnitude and
//! direction, pin forces; per optimisation study, the objective map with the global sample,
//! the winning local run's path, start, references and optimum, and a table of those points.

use super::svg::{
    self, esc, px, Frame, LinePlot, MapCell, MapPlot, Marker, RefLine, Series, Shape, PALETTE,
};
use crate::engine::check::{Bound, Check};
use crate::engine::golden::GoldenResult;
use crate::engine::optimise::problem::Margin;
use crate::equilibrium::sweep::{solve_angle, AngleSolution, Model};
use crate::error::{Error, Result};
use crate::geometry::clearance::{Mesh, Pose};
use crate::geometry::profile::Profile;
use crate::geometry::{rotate, Vec2};
use crate::model::results::SceneResult;
use crate::model::ContactLaw;
use crate::model::{Effect, Plan};
use crate::numeric::number;
use crate::spec::Spec;
use std::f64::consts::TAU;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// One optimisation study as the report shows it: the objective map over the study's first two
/// variables with the global sample, the winning local run's path, the start, the references
/// and the optimum; and a table of start, references and optimum. Built from a study result by
/// `report::optimisation::view`; the report only draws it.
#[derive(Debug, Clone, PartialEq)]
pub struct OptimisationView {
    /// The study's name.
    pub name: String,
    /// What it minimises, on which scene, over which bounds (a sentence).
    pub summary: String,
    /// E.g. "shift ΔRp (mm)".
    pub x_label: String,
    /// E.g. "equidistant ΔRrp (mm)".
    pub y_label: String,
    /// E.g. "ratio fluctuation κmax − κmin".
    pub objective_label: String,
    /// The objective on a grid (`MapCell::z` non-finite where a design rule fails); empty when
    /// no map was computed.
    pub map: Vec<MapCell>,
    /// How the map was made (grid, variables held fixed).
    pub map_note: String,
    /// Global-stage samples (x, y, feasible).
    pub global: Vec<(f64, f64, bool)>,
    /// The winning local run's iterates, from its start to the optimum.
    pub path: Vec<(f64, f64)>,
    /// What the path is (which run, from where).
    pub path_label: String,
    /// Evaluations of that run up to the optimum.
    pub path_evaluations: usize,
    pub start: Option<(f64, f64)>,
    pub optimum: Option<(f64, f64)>,
    /// Further labelled points (e.g. a published optimum).
    pub references: Vec<(f64, f64, String)>,
    /// Column headers of the variables in the table, with units.
    pub variables: Vec<String>,
    /// Table rows: start, references, optimum.
    pub points: Vec<StudyPoint>,
    /// Evaluations, time and why the search stopped.
    pub outcome: String,
    /// Remarks: the optimum against each reference, a point that satisfies the paper's Eq. 8
    /// but not the whole-mesh clearance.
    pub notes: Vec<String>,
}

/// One row of a study's table.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyPoint {
    /// "start", a reference's label, "optimum".
    pub label: String,
    /// Variable values in the spec's units, in `OptimisationView::variables` order.
    pub variables: Vec<f64>,
    /// None when the point could not be evaluated.
    pub objective: Option<f64>,
    /// Why the point could not be evaluated.
    pub failure: Option<String>,
    pub feasible: bool,
    /// Every constraint's value, bound and margin (≥ 0 satisfied).
    pub margins: Vec<Margin>,
}

/// Everything the report shows.
pub struct ReportInput<'a> {
    pub spec: &'a Spec,
    /// Limit and golden checks.
    pub checks: &'a [Check],
    pub results: &'a [SceneResult],
    pub goldens: &'a [GoldenResult],
    /// Crank angle of the disc drawing, degrees; default: where the smallest gap occurs.
    pub crank_deg: Option<f64>,
    /// Optimisation studies to draw and tabulate (none: no optimisation section).
    pub optimisation: &'a [OptimisationView],
    /// The accuracy ladder of a scene (`accuracy:` in the spec), when one was run.
    pub accuracy: Option<&'a crate::engine::accuracy::Ladder>,
}

/// The report's files: (file name, content), `index.html` first.
pub fn render(input: &ReportInput) -> Vec<(String, String)> {
    let mut files: Vec<(String, String)> = Vec::new();
    let mut figures = String::new();

    // The disc at the chosen crank angle.
    let phi_deg = input
        .crank_deg
        .unwrap_or_else(|| default_angle(input.results));
    let disc = disc_drawing(input.spec, input.results, phi_deg);
    files.push(("disc.svg".into(), disc.svg));
    let mut disc_figs = figure(
        "disc.svg",
        &format!("Disc, rollers and output pins at crank φ = {phi_deg:.2}°"),
        &disc.caption,
    );
    if let Some((svg, caption)) = gap_detail(input.spec, phi_deg) {
        files.push(("disc-detail.svg".into(), svg));
        disc_figs += &figure("disc-detail.svg", "Close-up of the smallest gap", &caption);
    }
    let _ = writeln!(
        figures,
        "<section><h2>The disc at crank φ = {phi_deg:.2}°</h2><div class=\"grid\">{disc_figs}</div></section>"
    );

    for (scene, r) in input.spec.scenes.iter().zip(input.results) {
        let plots = scene_plots(input.spec, r, &slug(&scene.name));
        if plots.is_empty() {
            continue;
        }
        let mut figs = String::new();
        for p in plots {
            figs += &figure(&p.file, &p.title, &p.caption);
            files.push((p.file, p.svg));
        }
        let _ = writeln!(
            figures,
            "<section><h2>Scene <code>{}</code></h2><p class=\"note\">{}</p><div class=\"grid\">{figs}</div></section>",
            esc(&scene.name),
            esc(&scene_summary(input.spec, scene))
        );
    }
    if !input.optimisation.is_empty() {
        let mut studies = String::new();
        for (k, o) in input.optimisation.iter().enumerate() {
            let file = format!("optimisation-{}-{}.svg", k + 1, slug(&o.name));
            files.push((file.clone(), optimisation_svg(o)));
            studies += &study_section(o, &file);
        }
        let _ = writeln!(
            figures,
            "<section><h2>Optimisation</h2><p class=\"note\">Every study of the spec: the \
             objective over its first two variables, where the optimiser looked and what it \
             found; the table gives the objective and every constraint at the start, the \
             references and the optimum.</p>{studies}</section>"
        );
    }
    if let Some(ladder) = input.accuracy {
        figures += &accuracy_section(ladder);
    }
    let page = page(input, &figures);
    files.insert(0, ("index.html".into(), page));
    files
}

/// Write the report into `dir` (created if missing); returns the files written.
pub fn write(dir: &Path, input: &ReportInput) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(&dir.display().to_string(), e))?;
    let mut written = Vec::new();
    for (name, text) in render(input) {
        let path = dir.join(&name);
        std::fs::write(&path, text).map_err(|e| Error::io(&path.display().to_string(), e))?;
        written.push(path);
    }
    Ok(written)
}

fn slug(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn figure(file: &str, title: &str, caption: &str) -> String {
    format!(
        "<figure><img src=\"{}\" alt=\"{}\"><figcaption><b>{}</b>. {}</figcaption></figure>\n",
        esc(file),
        esc(title),
        esc(title),
        esc(caption)
    )
}

/// Where the smallest gap of the first clearance scene occurs, else 0°.
fn default_angle(results: &[SceneResult]) -> f64 {
    results
        .iter()
        .find_map(|r| r.clearance.as_ref())
        .map_or(0.0, |c| c.min.crank_rad.to_degrees())
}

fn scene_summary(spec: &Spec, scene: &crate::model::Scene) -> String {
    let plan = Plan::for_scene(scene);
    let n = scene.crank_rad.len();
    let step = match scene.crank_rad.as_slice() {
        [a, b, ..] => (b - a).to_degrees(),
        _ => 0.0,
    };
    let effects: Vec<&str> = plan.effects.iter().map(|p| p.effect.name()).collect();
    let mut s = format!(
        "Output torque {} N·m; {n} crank angles from {:.2}° in steps of {}°; computes {}.",
        number(scene.output_torque_nmm / 1000.0),
        scene.crank_rad.first().map_or(0.0, |a| a.to_degrees()),
        number(step),
        effects.join(", ")
    );
    if plan.has(Effect::RollerContact) {
        let _ = write!(
            s,
            " Contact law {}, {} geometry, {} crank bearing.",
            match scene.contact_law {
                ContactLaw::PaperLinear => "F = (π/4)·E*·L·d (paper Eq. 9)",
                ContactLaw::HertzNonlinear => "Hertz line contact (Johnson, non-linear)",
            },
            scene.geometry,
            match scene.bearing_stiffness_n_per_mm {
                Some(k) => format!("compliant ({} N/mm)", number(k)),
                None => "rigid".into(),
            }
        );
    }
    let plan = crate::model::Plan::for_scene(scene);
    let pins = plan.has(crate::model::Effect::OutputPins);
    if !scene.spans_whole(spec.design.loaded_period_rad(pins)) {
        s += if pins {
            " The sweep does not cover whole periods of the loaded disc (mesh and output pins)."
        } else {
            " The sweep does not cover whole mesh periods."
        };
    }
    s
}

struct Plot {
    file: String,
    title: String,
    caption: String,
    svg: String,
}

fn limit_line(value: Option<f64>, label: &str, scale: f64, unit: &str) -> Vec<RefLine> {
    value
        .map(|v| RefLine {
            value: v * scale,
            label: format!("{label} {} {unit}", number(v * scale))
                .trim_end()
                .to_string(),
            color: "#d62728".into(),
        })
        .into_iter()
        .collect()
}

/// One curve per row, named `what i`; rows that are zero everywhere are left out and listed.
fn per_row(x: &[f64], rows: &[Vec<f64>], what: &str, scale: f64) -> (Vec<Series>, String) {
    let mut series = Vec::new();
    let mut idle = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        if row.iter().all(|v| *v == 0.0) {
            idle.push(i.to_string());
            continue;
        }
        series.push(Series::new(
            format!("{what} {i}"),
            x.to_vec(),
            row.iter().map(|v| v * scale).collect(),
            PALETTE[i % PALETTE.len()],
        ));
    }
    let note = if idle.is_empty() {
        String::new()
    } else {
        let mut rest = what.chars();
        let first = rest.next().map(|c| c.to_uppercase().to_string());
        format!(
            "{}{}s without load over the sweep (not drawn): {}.",
            first.unwrap_or_default(),
            rest.as_str(),
            idle.join(", ")
        )
    };
    (series, note)
}

fn mesh_step(spec: &Spec, x: &[f64]) -> Option<f64> {
    let span = (x.last()? - x.first()?) * x.len() as f64 / (x.len() as f64 - 1.0).max(1.0);
    let period = spec.design.mesh_period_rad().to_degrees();
    if span <= 1.5 * period {
        Some(period / 6.0)
    } else if span <= 4.5 * period {
        Some(period / 2.0)
    } else {
        None
    }
}

fn scene_plots(spec: &Spec, r: &SceneResult, slug: &str) -> Vec<Plot> {
    let x: Vec<f64> = r.crank_rad.iter().map(|a| a.to_degrees()).collect();
    let xl = "crank angle φ (deg)";
    let lim = &spec.limits;
    let arcsec = crate::units::ARCSEC_PER_RAD;
    let mut plots = Vec::new();
    // The whole crank range: its end is not a sample (it wraps to the start).
    let x_range = match x.as_slice() {
        [a, b, ..] => Some((*a, a + (b - a) * x.len() as f64)),
        _ => None,
    };
    let mut add = |name: &str, mut p: LinePlot, caption: String| {
        p.x_step = mesh_step(spec, &x);
        p.x_range = x_range;
        plots.push(Plot {
            file: format!("{slug}-{name}.svg"),
            title: p.title.clone(),
            caption,
            svg: p.to_svg(),
        });
    };
    if let Some(c) = &r.clearance {
        let mut p = LinePlot::new("Clearance per roller", xl, "clearance (µm)");
        (p.series, _) = per_row(&x, &c.gap_mm, "roller", 1000.0);
        p.ref_lines = limit_line(lim.get("min_clearance_mm"), "limit", 1000.0, "µm");
        p.include_zero = c.min.gap_mm < 0.0;
        p.subtitle = format!(
            "smallest {} µm: roller {} at φ = {:.2}°, tooth phase {:.3} (0 root, 0.5 tip)",
            number(c.min.gap_mm * 1000.0),
            c.min.roller,
            c.min.crank_rad.to_degrees(),
            c.min.tooth_phase
        );
        add(
            "clearance",
            p,
            "Normal gap of every roller to the modified profile at the ideal disc pose (no \
             load); negative is interference. Dashed red: the min_clearance limit."
                .into(),
        );
    }
    if let Some(b) = r.clearance.as_ref().and_then(|c| c.backlash.as_ref()) {
        let mut p = LinePlot::new("Backlash and lost motion (no load)", xl, "angle (arcsec)");
        p.series = vec![
            Series::new(
                "backlash (unloaded TE)",
                x.clone(),
                b.forward_rad.iter().map(|b| b * arcsec).collect(),
                PALETTE[0],
            ),
            Series {
                dashed: true,
                ..Series::new(
                    "reverse backlash",
                    x.clone(),
                    b.reverse_rad.iter().map(|b| b * arcsec).collect(),
                    PALETTE[1],
                )
            },
            Series::new(
                "lost motion",
                x.clone(),
                b.lost_motion_rad.iter().map(|b| b * arcsec).collect(),
                PALETTE[2],
            ),
        ];
        p.include_zero = true;
        add(
            "backlash",
            p,
            "Disc rotation needed to close the first gap in the load direction (backlash), in \
             the reverse direction, and their sum (lost motion)."
                .into(),
        );
    }
    if let Some(c) = &r.loaded.rollers {
        let mut p = LinePlot::new("Roller forces", xl, "roller force (N)");
        let note;
        (p.series, note) = per_row(&x, &c.force_n, "roller", 1.0);
        p.ref_lines = limit_line(lim.get("max_roller_force_n"), "limit", 1.0, "N");
        p.include_zero = true;
        let (fmax, i, k) = crate::numeric::max_entry(&c.force_n);
        p.subtitle = format!(
            "largest {} N on roller {i} at φ = {:.2}°",
            number(fmax),
            x.get(k).copied().unwrap_or(0.0)
        );
        add(
            "roller-forces",
            p,
            format!("Contact force of every roller on the disc. {note}"),
        );
        let mut p = LinePlot::new("Hertz peak pressure", xl, "peak contact pressure (MPa)");
        (p.series, _) = per_row(&x, &c.pressure_mpa, "roller", 1.0);
        p.ref_lines = limit_line(lim.get("max_contact_pressure_mpa"), "limit", 1.0, "MPa");
        p.include_zero = true;
        add(
            "pressure",
            p,
            "p0 = sqrt(F·E*/(π·L·R*)) with the profile's local curvature at the contact.".into(),
        );
    }
    if let Some(t) = &r.loaded.transmission {
        let te: Vec<f64> = t.te_rad.iter().map(|v| v * arcsec).collect();
        let mut p = LinePlot::new("Loaded transmission error", xl, "TE δ = β + βo (arcsec)");
        p.subtitle = format!(
            "fluctuation {} arcsec (max − min), mean {} arcsec",
            number(crate::numeric::fluctuation(&te)),
            number(te.iter().sum::<f64>() / te.len().max(1) as f64)
        );
        if let Some(pins) = &r.loaded.pins {
            let lo = pins
                .output_lag_rad
                .iter()
                .fold(f64::INFINITY, |a, &b| a.min(b));
            let hi = pins
                .output_lag_rad
                .iter()
                .fold(f64::NEG_INFINITY, |a, &b| a.max(b));
            p.subtitle += &if number(lo * arcsec) == number(hi * arcsec) {
                format!("; of which βo {} arcsec", number(lo * arcsec))
            } else {
                format!(
                    "; of which βo {}–{} arcsec",
                    number(lo * arcsec),
                    number(hi * arcsec)
                )
            };
        }
        p.series = vec![Series::new("TE", x.clone(), te, PALETTE[0])];
        add(
            "te",
            p,
            "Lag of the output behind its ideal angle φ/nc under the scene's torque: disc lag β \
             at the rollers plus output lag βo at the pins."
                .into(),
        );
        if let Some(ratio) = &t.ratio {
            let mut p = LinePlot::new("Transmission ratio", xl, "ratio κ = dφ/dφout");
            p.subtitle = format!(
                "fluctuation {} (max − min)",
                number(crate::numeric::fluctuation(ratio))
            );
            p.series = vec![Series::new("κ", x.clone(), ratio.clone(), PALETTE[0])];
            p.ref_lines = vec![RefLine {
                value: spec.design.teeth as f64,
                label: format!("nominal nc = {}", spec.design.teeth),
                color: "#7f7f7f".into(),
            }];
            add(
                "ratio",
                p,
                "κ = 1/(1/nc − dδ/dφ) by central differences; its harmonic mean over whole mesh \
                 periods is nc."
                    .into(),
            );
        }
    }
    if let Some(b) = &r.loaded.bearing {
        let mut p = LinePlot::new("Crank-bearing force", xl, "bearing force |Fb| (N)");
        p.series = vec![Series::new(
            "|Fb|",
            x.clone(),
            b.force_n.clone(),
            PALETTE[0],
        )];
        p.ref_lines = limit_line(lim.get("max_bearing_force_n"), "limit", 1.0, "N");
        p.include_zero = true;
        add(
            "bearing-force",
            p,
            "Magnitude of the force of the crank bearing on the disc, −(Σ roller + Σ pin forces)."
                .into(),
        );
        let mut p = LinePlot::new(
            "Crank-bearing force direction",
            xl,
            "bearing force angle ε (deg)",
        );
        p.series = vec![Series::new(
            "ε",
            x.clone(),
            b.angle_rad.iter().map(|a| a.to_degrees()).collect(),
            PALETTE[0],
        )];
        add(
            "bearing-angle",
            p,
            "Direction of the bearing force, counter-clockwise from the eccentric direction \
             (cos φ, sin φ)."
                .into(),
        );
    }
    if let Some(pins) = &r.loaded.pins {
        let mut p = LinePlot::new("Output-pin forces", xl, "pin force (N)");
        let note;
        (p.series, note) = per_row(&x, &pins.force_n, "pin", 1.0);
        p.ref_lines = limit_line(lim.get("max_pin_force_n"), "limit", 1.0, "N");
        p.include_zero = true;
        add(
            "pin-forces",
            p,
            format!(
                "Force of every output pin on its hole; pins whose moment arm is negative carry \
                 no load. {note}"
            ),
        );
    }
    plots
}

struct Drawing {
    svg: String,
    caption: String,
}

fn arrow(s: &mut String, f: &Frame, from: Vec2, to: Vec2, color: &str, label: &str) {
    let d = to - from;
    let len = f.len(d.norm());
    if len < 1.0 {
        return;
    }
    let u = Vec2::new(d.x, -d.y) / d.norm();
    let (hx, hy) = (f.x(to.x), f.y(to.y));
    let head = 9.0_f64.min(len * 0.5);
    let back = (hx - u.x * head, hy - u.y * head);
    let side = Vec2::new(-u.y, u.x) * head * 0.45;
    let _ = writeln!(
        s,
        r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{color}" stroke-width="2.2"/><polygon points="{},{} {},{} {},{}" fill="{color}"/>"#,
        px(f.x(from.x)),
        px(f.y(from.y)),
        px(back.0),
        px(back.1),
        px(hx),
        px(hy),
        px(back.0 + side.x),
        px(back.1 + side.y),
        px(back.0 - side.x),
        px(back.1 - side.y)
    );
    if !label.is_empty() {
        let (lx, ly) = (hx + u.x * 6.0, hy + u.y * 6.0 + 4.0);
        let anchor = if u.x < -0.3 {
            "end"
        } else if u.x > 0.3 {
            "start"
        } else {
            "middle"
        };
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" font-size="11" text-anchor="{anchor}" fill="{color}" stroke="white" stroke-width="3" paint-order="stroke">{}</text>"#,
            px(lx),
            px(ly),
            esc(label)
        );
    }
}

/// The loaded equilibrium at one crank angle, from the first scene with roller contact.
fn loaded_at(spec: &Spec, phi: f64) -> Option<(String, AngleSolution, Model)> {
    let scene = spec
        .scenes
        .iter()
        .find(|s| Plan::for_scene(s).has(Effect::RollerContact))?;
    let plan = Plan::for_scene(scene);
    let model = Model::new(&spec.design, &spec.modification, scene, &plan);
    let sol = solve_angle(&model, phi, &AngleSolution::default()).ok()?;
    Some((scene.name.clone(), sol, model))
}

/// The disc at its pose for crank φ (MODEL.md: centre e·(cos φ, sin φ), rotation −φ/nc plus
/// the loaded lag when a scene is loaded), with the rollers, the pins in their holes and the
/// contact forces.
fn disc_drawing(spec: &Spec, results: &[SceneResult], phi_deg: f64) -> Drawing {
    let d = &spec.design;
    let phi = phi_deg.to_radians();
    let loaded = loaded_at(spec, phi);
    let lag = loaded
        .as_ref()
        .and_then(|(_, s, _)| s.lag_rad)
        .unwrap_or(0.0);
    let out_lag = loaded
        .as_ref()
        .and_then(|(_, s, _)| s.output_lag_rad)
        .unwrap_or(0.0);
    let pose = Pose::lagging(phi, lag);
    let mesh = Mesh::new(&spec.design, &spec.modification);
    let centre = mesh.disc_centre(&pose);
    let psi = mesh.disc_rotation(&pose);
    let (ps, pc) = psi.sin_cos();
    let to_fixed = |p: Vec2| centre + rotate(p, pc, ps);
    let profile = Profile::new(&spec.design, &spec.modification);
    let outer = d.roller_circle_radius_mm + d.roller_radius_mm;
    let half = outer + 7.0;
    let (w, h) = (660.0, 700.0);
    let f = Frame::fit((-half, half, -half, half), (10.0, 50.0, w - 20.0, h - 60.0));
    let mut s = svg::header(w, h);
    let _ = writeln!(
        s,
        r##"<text x="14" y="24" font-size="16" font-weight="bold">Disc at crank φ = {phi_deg:.2}°</text><text x="14" y="42" font-size="12" fill="#555">fixed frame; disc centre e·(cos φ, sin φ), disc turned by ψ = −φ/nc{}</text>"##,
        if loaded.is_some() {
            " + β (loaded)"
        } else {
            ""
        }
    );
    // Pitch circles.
    let _ = writeln!(
        s,
        r##"<circle cx="{}" cy="{}" r="{}" fill="none" stroke="#aaa" stroke-dasharray="4 4"/>"##,
        px(f.x(0.0)),
        px(f.y(0.0)),
        px(f.len(d.roller_circle_radius_mm))
    );
    // Disc with its holes (even-odd fill), then the pins.
    let points = crate::report::export::polyline(&profile, 0.02 / f.scale.max(1e-9) * 10.0);
    let mut path = String::from("M");
    for (k, p) in points.iter().enumerate() {
        let q = to_fixed(p.point);
        let _ = write!(
            path,
            "{}{}",
            if k == 0 { "" } else { " L" },
            f.point(q.x, q.y)
        );
    }
    path += " Z";
    let m = d.pins.count;
    let hole = d.hole_radius_mm();
    for j in 0..m {
        let gamma = TAU * j as f64 / m as f64 + psi;
        let hc = centre + Vec2::new(gamma.cos(), gamma.sin()) * d.pins.circle_radius_mm;
        let r = f.len(hole);
        let _ = write!(
            path,
            " M{},{} a{r},{r} 0 1,0 {},0 a{r},{r} 0 1,0 {},0 Z",
            px(f.x(hc.x) - r),
            px(f.y(hc.y)),
            px(2.0 * r),
            px(-2.0 * r),
            r = px(r)
        );
    }
    let _ = writeln!(
        s,
        r##"<path d="{path}" fill="#cfe0f1" fill-rule="evenodd" stroke="#1f4e79" stroke-width="1.2"/>"##
    );
    for j in 0..m {
        let gamma = TAU * j as f64 / m as f64 + psi + out_lag;
        let q = Vec2::new(gamma.cos(), gamma.sin()) * d.pins.circle_radius_mm;
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{}" r="{}" fill="#6b6b6b" stroke="#333"/><text x="{}" y="{}" font-size="11" text-anchor="middle" fill="white">{j}</text>"##,
            px(f.x(q.x)),
            px(f.y(q.y)),
            px(f.len(d.pins.pin_radius_mm)),
            px(f.x(q.x)),
            px(f.y(q.y) + 4.0)
        );
    }
    // Rollers, with their index outside.
    let gaps: Option<Vec<f64>> = results.iter().find_map(|r| {
        let c = r.clearance.as_ref()?;
        let k = nearest(&r.crank_rad, phi)?;
        Some(c.gap_mm.iter().map(|g| g[k]).collect())
    });
    let tightest = gaps.as_ref().map(|g| {
        let (i, v) =
            g.iter().enumerate().fold(
                (0, f64::INFINITY),
                |b, (i, &v)| if v < b.1 { (i, v) } else { b },
            );
        (i, v)
    });
    for i in 0..d.rollers {
        let c = mesh.roller_centre(i);
        let hot = tightest.is_some_and(|(t, _)| t == i);
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{}" r="{}" fill="#e6e6e6" stroke="{}" stroke-width="{}"/>"##,
            px(f.x(c.x)),
            px(f.y(c.y)),
            px(f.len(d.roller_radius_mm)),
            if hot { "#d62728" } else { "#444" },
            if hot { 2.5 } else { 1.0 }
        );
        let a = d.roller_angle(i);
        let l = Vec2::new(a.cos(), a.sin()) * (outer + 3.5);
        let _ = writeln!(
            s,
            r##"<text x="{}" y="{}" font-size="13" text-anchor="middle" fill="{}">{i}</text>"##,
            px(f.x(l.x)),
            px(f.y(l.y) + 4.5),
            if hot { "#d62728" } else { "#333" }
        );
    }
    // Crank: input axis, eccentric and disc centre.
    let _ = writeln!(
        s,
        r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#d62728" stroke-width="2"/><circle cx="{}" cy="{}" r="3" fill="#333"/><circle cx="{}" cy="{}" r="3" fill="#d62728"/>"##,
        px(f.x(0.0)),
        px(f.y(0.0)),
        px(f.x(centre.x)),
        px(f.y(centre.y)),
        px(f.x(0.0)),
        px(f.y(0.0)),
        px(f.x(centre.x)),
        px(f.y(centre.y))
    );
    let mut caption = format!(
        "Blue: the modified disc ({} teeth) with its {} output-pin holes; grey circles: the {} \
         rollers (numbered) and the {} pins; red line: the crank from the input axis to the \
         disc centre (e = {} mm).",
        d.teeth,
        m,
        d.rollers,
        m,
        number(d.eccentricity_mm)
    );
    if let Some((i, g)) = tightest {
        let _ = write!(
            caption,
            " Roller {i}, ringed in red, has the smallest gap at this angle: {} µm.",
            number(g * 1000.0)
        );
    }
    if let Some((scene, sol, _)) = &loaded {
        // Forces on the disc, one scale for all: the largest is 12 mm long.
        let mut forces: Vec<(Vec2, Vec2, String, &str)> = Vec::new();
        for r in &sol.rollers {
            if r.force_n > 0.0 {
                forces.push((
                    r.point,
                    r.force_vector(),
                    format!("{} N", number(r.force_n)),
                    "#d62728",
                ));
            }
        }
        for p in &sol.pins {
            if p.force_n > 0.0 {
                forces.push((
                    p.point,
                    p.force_vector(),
                    format!("{} N", number(p.force_n)),
                    "#2ca02c",
                ));
            }
        }
        if let Some(fb) = sol.bearing_force_n {
            forces.push((centre, fb, format!("Fb {} N", number(fb.norm())), "#9467bd"));
        }
        let biggest = forces.iter().map(|f| f.1.norm()).fold(0.0, f64::max);
        if biggest > 0.0 {
            let k = 12.0 / biggest;
            for (at, force, label, color) in &forces {
                // One scale, but never shorter than 2.5 mm so that small forces stay visible.
                let force = &(force * (2.5 / (force.norm() * k)).max(1.0));
                // Roller forces end at their contact (the arrow starts in the roller); pin forces
                // start at theirs, pointing into the disc; the bearing force starts at the centre.
                let (from, to) = if color == &"#d62728" {
                    (*at - force * k, *at)
                } else {
                    (*at, *at + force * k)
                };
                arrow(&mut s, &f, from, to, color, label);
            }
            let _ = write!(
                caption,
                " Arrows: forces on the disc in scene `{scene}` at this angle, to one scale — \
                 red rollers, green output pins, purple the crank bearing (the largest is 12 mm \
                 long; none is drawn shorter than 2.5 mm)."
            );
        }
    }
    // Scale bar: 10 mm.
    let (bx, by) = (w - 30.0 - f.len(10.0), h - 20.0);
    let _ = writeln!(
        s,
        r##"<line x1="{}" y1="{by}" x2="{}" y2="{by}" stroke="#333" stroke-width="2"/><text x="{}" y="{}" font-size="12" text-anchor="middle">10 mm</text>"##,
        px(bx),
        px(bx + f.len(10.0)),
        px(bx + f.len(5.0)),
        px(by - 6.0),
        by = px(by)
    );
    s += "</svg>\n";
    Drawing { svg: s, caption }
}

fn nearest(xs: &[f64], x: f64) -> Option<usize> {
    (0..xs.len()).min_by(|&a, &b| (xs[a] - x).abs().total_cmp(&(xs[b] - x).abs()))
}

/// A close-up of the roller with the smallest gap at crank φ (ideal pose): the gap, which is
/// tens of µm against a disc of tens of mm, cannot be seen in the whole drawing.
fn gap_detail(spec: &Spec, phi_deg: f64) -> Option<(String, String)> {
    let mesh = Mesh::new(&spec.design, &spec.modification);
    let pose = Pose::ideal(phi_deg.to_radians());
    let (i, g) = (0..mesh.rollers)
        .filter_map(|i| mesh.roller_gap(i, &pose, None).ok().map(|g| (i, g)))
        .min_by(|a, b| a.1.gap_mm.total_cmp(&b.1.gap_mm))?;
    // Everything in the disc frame, turned so that the contact normal points up.
    let roller = mesh.roller_in_disc(i, &pose);
    let n = g.normal;
    let turn = n.y.atan2(n.x) - std::f64::consts::FRAC_PI_2;
    let (ts, tc) = (-turn).sin_cos();
    let local = |p: Vec2| rotate(p - g.point, tc, ts);
    let window = (g.gap_mm.abs() * 14.0).clamp(0.3, 3.0);
    let (w, h) = (560.0, 560.0);
    let f = Frame::fit(
        (-window / 2.0, window / 2.0, -window * 0.4, window * 0.6),
        (40.0, 60.0, w - 80.0, h - 110.0),
    );
    let profile = mesh.profile;
    let mut s = svg::header(w, h);
    let _ = writeln!(
        s,
        r##"<text x="14" y="24" font-size="16" font-weight="bold">Roller {i} at crank φ = {phi_deg:.2}°, close-up</text><text x="14" y="42" font-size="12" fill="#555">true scale, {} mm across; disc frame turned so the contact normal points up</text>"##,
        number(window)
    );
    let _ = writeln!(
        s,
        r#"<clipPath id="win"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath><g clip-path="url(#win)">"#,
        px(f.x(-window / 2.0)),
        px(f.y(window * 0.6)),
        px(f.len(window)),
        px(f.len(window))
    );
    // Disc material: a wedge of the profile around the contact, closed far below the window.
    let span = 0.35;
    let mut path = String::from("M");
    for k in 0..=1200 {
        let t = g.t - span + 2.0 * span * k as f64 / 1200.0;
        let p = local(profile.point(t));
        let _ = write!(
            path,
            "{}{}",
            if k == 0 { "" } else { " L" },
            f.point(p.x, p.y)
        );
    }
    let far = local(g.point - n * 50.0);
    let _ = write!(path, " L{} Z", f.point(far.x, far.y));
    let _ = writeln!(
        s,
        r##"<path d="{path}" fill="#cfe0f1" stroke="#1f4e79" stroke-width="1.5"/>"##
    );
    let c = local(roller);
    let _ = writeln!(
        s,
        r##"<circle cx="{}" cy="{}" r="{}" fill="#e6e6e6" fill-opacity="0.85" stroke="#444" stroke-width="1.5"/>"##,
        px(f.x(c.x)),
        px(f.y(c.y)),
        px(f.len(spec.design.roller_radius_mm))
    );
    s += "</g>\n";
    // The gap along the normal: from the profile (0, 0) to the roller surface (0, gap).
    let (x, y0, y1) = (f.x(0.0), f.y(0.0), f.y(g.gap_mm));
    let color = if g.gap_mm >= 0.0 {
        "#2ca02c"
    } else {
        "#d62728"
    };
    let _ = writeln!(
        s,
        r##"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="{color}" stroke-width="2"/><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{color}"/><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{color}"/>"##,
        px(y0),
        px(y1),
        px(x - 8.0),
        px(y0),
        px(x + 8.0),
        px(y0),
        px(x - 8.0),
        px(y1),
        px(x + 8.0),
        px(y1),
        x = px(x)
    );
    let what = if g.gap_mm >= 0.0 {
        "gap"
    } else {
        "interference"
    };
    let _ = writeln!(
        s,
        r##"<text x="{}" y="{}" font-size="14" font-weight="bold" fill="{color}" stroke="white" stroke-width="4" paint-order="stroke">{what} {} µm</text>"##,
        px(x + 14.0),
        px((y0 + y1) / 2.0 + 5.0),
        number(g.gap_mm * 1000.0)
    );
    let _ = writeln!(
        s,
        r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#333"/>"##,
        px(f.x(-window / 2.0)),
        px(f.y(window * 0.6)),
        px(f.len(window)),
        px(f.len(window))
    );
    let bar = svg::ticks(0.0, window / 3.0, 1, false).step;
    let (bx, by) = (f.x(window / 2.0) - f.len(bar), h - 22.0);
    let _ = writeln!(
        s,
        r##"<line x1="{}" y1="{by}" x2="{}" y2="{by}" stroke="#333" stroke-width="2"/><text x="{}" y="{}" font-size="12" text-anchor="middle">{} µm</text>"##,
        px(bx),
        px(bx + f.len(bar)),
        px(bx + f.len(bar) / 2.0),
        px(by - 6.0),
        svg::Ticks {
            decimals: 0,
            ..svg::ticks(0.0, 1.0, 1, false)
        }
        .label(bar * 1000.0),
        by = px(by)
    );
    s += "</svg>\n";
    let caption = format!(
        "Roller {i} (grey) against the disc flank (blue) at tooth phase {:.3} (0 root, 0.5 tip), \
         unloaded ideal pose, true scale. The smallest gap over the whole mesh is in the checks \
         table and the clearance plot.",
        (g.t.rem_euclid(TAU / spec.design.teeth as f64)) / (TAU / spec.design.teeth as f64)
    );
    Some((s, caption))
}

fn optimisation_svg(o: &OptimisationView) -> String {
    let mut markers = Vec::new();
    if let Some((x, y)) = o.start {
        markers.push(Marker {
            x,
            y,
            label: "start".into(),
            color: "#ff7f0e".into(),
            shape: Shape::Circle,
        });
    }
    for (x, y, label) in &o.references {
        markers.push(Marker {
            x: *x,
            y: *y,
            label: label.clone(),
            color: "#111111".into(),
            shape: Shape::Diamond,
        });
    }
    if let Some((x, y)) = o.optimum {
        markers.push(Marker {
            x,
            y,
            label: "optimum".into(),
            color: "#d62728".into(),
            shape: Shape::Star,
        });
    }
    MapPlot {
        title: format!("Study {}: objective over the modification", o.name),
        subtitle: o.map_note.clone(),
        x_label: o.x_label.clone(),
        y_label: o.y_label.clone(),
        z_label: o.objective_label.clone(),
        cells: o.map.clone(),
        samples: o.global.clone(),
        samples_label: "global sample".into(),
        path: o.path.clone(),
        path_label: o.path_label.clone(),
        markers,
        z_range: None,
        width: 700.0,
    }
    .to_svg()
}

/// The accuracy ladder as a table: one row per rung, errors against the reference, times, the
/// cheapest rung that meets every tolerance highlighted; observed orders and notes below.
fn accuracy_section(ladder: &crate::engine::accuracy::Ladder) -> String {
    use crate::engine::accuracy::{self as acc, Variation};
    let l = &ladder.layout;
    let mut head = String::from(
        "<tr><th>rung</th><th>steps per mesh period</th><th>crank angles</th><th>geometry</th>\
         <th>contact law</th><th>solver rel_tol</th><th>time</th>",
    );
    for q in &l.quantities {
        let unit = if q.unit().is_empty() {
            String::new()
        } else {
            format!(" ({})", q.unit())
        };
        let _ = write!(
            head,
            "<th>{}{}<br><span class=\"note\">tol {}</span></th>",
            esc(q.label()),
            esc(&unit),
            esc(&acc::short(q.tolerance(&l.tolerances)))
        );
    }
    head += "<th>tolerances</th></tr>";
    let mut rows = String::new();
    for (i, r) in ladder.rungs.iter().enumerate() {
        let cheapest = ladder.cheapest == Some(i);
        let (class, verdict) = r.verdict(&l.tolerances);
        let class = if cheapest { "pass cheapest" } else { class };
        let _ = write!(
            rows,
            "<tr class=\"{class}\"><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td><td>{}</td><td class=\"num\">{:e}</td><td class=\"num\">{}</td>",
            esc(&r.label),
            esc(&acc::steps_text(r.steps_per_period)),
            r.angles,
            r.geometry.name(),
            r.law.name(),
            r.rel_tol,
            esc(&if r.seconds < 1.0 {
                format!("{:.1} ms", r.seconds * 1000.0)
            } else {
                format!("{:.2} s", r.seconds)
            }),
        );
        for &q in &l.quantities {
            let cell = match r.error(q) {
                _ if r.is_reference => "—".to_string(),
                Some(e) => acc::short(e),
                None => "n/a".to_string(),
            };
            let over = !r.is_reference
                && !r.model_difference
                && r.error(q).is_some_and(|e| !q.within(e, &l.tolerances));
            let _ = write!(
                rows,
                "<td class=\"num{}\">{}</td>",
                if over { " over" } else { "" },
                esc(&cell)
            );
        }
        let _ = writeln!(
            rows,
            "<td class=\"verdict\">{}{}</td></tr>",
            esc(&verdict),
            if cheapest { " — <b>cheapest</b>" } else { "" }
        );
    }
    let missing: Vec<String> = acc::Quantity::ALL
        .into_iter()
        .filter(|q| !l.quantities.contains(q))
        .map(|q| q.description())
        .collect();
    let mut notes = format!(
        "Scene <code>{}</code> over crank {}° to {}° ({} mesh periods) on a ladder of settings. \
         The reference is the finest rung: {} steps per mesh period, {} geometry, {}, solver \
         rel_tol 1e-11. Each error is |rung − reference| in the quantity's unit; the TE curve's \
         is the largest difference between the reference and the rung's curve interpolated \
         linearly between its crank angles. Times are wall-clock measurements of the rung's run \
         (the fastest of up to {} runs for runs under {} ms).",
        esc(&l.scene),
        esc(&number(l.from_deg)),
        esc(&number(l.to_deg)),
        esc(&acc::steps_text(l.periods)),
        l.finest,
        l.geometry.name(),
        l.law.name(),
        acc::REPEATS,
        acc::REPEAT_BELOW_S * 1000.0,
    );
    if !missing.is_empty() {
        let _ = write!(
            notes,
            " Not computed by this scene (no column): {}.",
            esc(&missing.join(", "))
        );
    }
    if ladder.rungs.iter().any(|r| r.variation != Variation::Steps) {
        let _ = write!(
            notes,
            " The rungs that change one setting run at {} steps per mesh period{}.",
            ladder.settings_steps,
            if ladder.settings_steps == l.finest {
                " (the finest, so their errors are the setting's own effect)"
            } else {
                "; their errors include that resolution's, shown by its steps rung"
            }
        );
    }
    if ladder
        .rungs
        .iter()
        .any(|r| r.variation == Variation::ContactLaw)
    {
        notes += " Another contact law is another model: its difference from the reference is a \
                  model difference, not a discretisation error, and it is never the cheapest.";
    }
    let verdict = match ladder.cheapest {
        Some(i) if ladder.rungs[i].is_reference => {
            "Only the reference meets every tolerance; its own error is not measured (no finer \
             rung)."
                .to_string()
        }
        Some(i) => {
            let r = &ladder.rungs[i];
            format!(
                "Cheapest rung meeting every tolerance: <b>{}</b> ({} steps per mesh period).",
                esc(&r.label),
                esc(&acc::steps_text(r.steps_per_period))
            )
        }
        None => "No rung meets every tolerance.".to_string(),
    };
    let mut orders = String::new();
    for &q in &l.quantities {
        let o = ladder.orders(q);
        if o.is_empty() {
            continue;
        }
        let cells: String = o
            .iter()
            .map(|(_, p)| {
                format!(
                    "<td class=\"num\">{}</td>",
                    p.map_or("—".to_string(), acc::order_text)
                )
            })
            .collect();
        let fit = ladder
            .fitted_order(q)
            .map_or("—".to_string(), acc::order_text);
        let _ = writeln!(
            orders,
            "<tr><td>{}</td>{cells}<td class=\"num\"><b>{fit}</b></td></tr>",
            esc(q.label())
        );
    }
    let order_table = if orders.is_empty() {
        String::new()
    } else {
        let ns: String = ladder
            .orders(l.quantities[0])
            .iter()
            .map(|(n, _)| format!("<th>{n}→{}</th>", 2 * n))
            .collect();
        format!(
            "<p class=\"note\">Observed order of convergence log2(e(N)/e(2N)) of the steps rungs \
             (— where an error is at round-off), and the least-squares fit over N = 12 … \
             finest/4.</p><table><thead><tr><th>quantity</th>{ns}<th>fit</th></tr></thead>\
             <tbody>{orders}</tbody></table>"
        )
    };
    let skipped: String = ladder
        .skipped
        .iter()
        .map(|k| format!(" Skipped: {}.", esc(k)))
        .collect();
    format!(
        "<section id=\"accuracy\"><h2>Accuracy ladder: what accuracy costs in time</h2>\
         <p class=\"note\">{notes}{skipped}</p><p>{verdict}</p>\
         <table><thead>{head}</thead><tbody>{rows}</tbody></table>{order_table}</section>\n"
    )
}

/// A constraint's margin as the table shows it: on the bound within the checker's tolerance
/// (decimal inputs such as 0.150 − 0.135 land a few 1e-17 mm off), else signed.
fn margin_text(m: &Margin) -> String {
    if m.margin.abs() <= crate::engine::check::tolerance(m.bound) {
        "margin 0 (on the bound)".into()
    } else {
        format!(
            "margin {}{}",
            if m.margin > 0.0 { "+" } else { "" },
            number(m.margin)
        )
    }
}

/// A study's heading, table (one column per point: start, references, optimum), outcome and
/// figure.
fn study_section(o: &OptimisationView, file: &str) -> String {
    let constraints: Vec<&Margin> = o
        .points
        .iter()
        .max_by_key(|p| p.margins.len())
        .map(|p| p.margins.iter().collect())
        .unwrap_or_default();
    let optimum_class = |p: &StudyPoint| {
        if p.label == "optimum" {
            " class=\"optimum\""
        } else {
            ""
        }
    };
    let mut head = String::from("<th></th>");
    for p in &o.points {
        let _ = write!(head, "<th{}>{}</th>", optimum_class(p), esc(&p.label));
    }
    let mut rows = String::new();
    for (k, v) in o.variables.iter().enumerate() {
        let _ = write!(rows, "<tr><th>{}</th>", esc(v));
        for p in &o.points {
            let value = p
                .variables
                .get(k)
                .map_or(String::new(), |x| format!("{x:.6}").replace('-', "−"));
            let _ = write!(
                rows,
                "<td class=\"num{}\">{value}</td>",
                if p.label == "optimum" { " optimum" } else { "" }
            );
        }
        rows += "</tr>\n";
    }
    let _ = write!(rows, "<tr><th>{}</th>", esc(&o.objective_label));
    for p in &o.points {
        let cell = match (&p.objective, &p.failure) {
            (Some(z), _) => format!(
                "<td class=\"num{}\">{}</td>",
                if p.label == "optimum" { " optimum" } else { "" },
                esc(&number(*z).replace('-', "−"))
            ),
            (None, why) => format!(
                "<td class=\"violated\">not evaluated: {}</td>",
                esc(why.as_deref().unwrap_or("no value"))
            ),
        };
        rows += &cell;
    }
    rows += "</tr>\n";
    for c in &constraints {
        let (name, qualifier) = match c.name.split_once(" (") {
            Some((n, q)) => (n.to_string(), format!(" ({q}")),
            None => (c.name.clone(), String::new()),
        };
        // A lower bound has margin value − bound, an upper one bound − value.
        let op = if (c.margin - (c.value - c.bound)).abs() <= (c.margin - (c.bound - c.value)).abs()
        {
            "≥"
        } else {
            "≤"
        };
        let _ = write!(
            rows,
            "<tr><th>{}<br><small>{op} {}{}</small></th>",
            esc(&name),
            esc(&number(c.bound)),
            esc(&qualifier)
        );
        for p in &o.points {
            match p.margins.iter().find(|m| m.name == c.name) {
                Some(m) => {
                    let _ = write!(
                        rows,
                        "<td class=\"num{}\">{}<br><small>{}</small></td>",
                        if m.satisfied() { "" } else { " violated" },
                        esc(&number(m.value).replace('-', "−")),
                        esc(&margin_text(m).replace('-', "−"))
                    );
                }
                None => rows += "<td class=\"num\">—</td>",
            }
        }
        rows += "</tr>\n";
    }
    rows += "<tr><th>verdict</th>";
    for p in &o.points {
        let _ = write!(
            rows,
            "<td class=\"verdict {}\">{}</td>",
            if p.feasible { "pass" } else { "fail" },
            if p.feasible { "feasible" } else { "INFEASIBLE" }
        );
    }
    rows += "</tr>\n";
    let notes: String = o
        .notes
        .iter()
        .map(|n| format!("<li>{}</li>", esc(n)))
        .collect();
    let notes = if notes.is_empty() {
        String::new()
    } else {
        format!("<ul class=\"note\">{notes}</ul>")
    };
    let path = if o.path.len() > 1 {
        format!(
            "Red: the iterates of {} up to the optimum ({} evaluations; COBYLA probes around \
             its trust region, so the path zig-zags).",
            o.path_label, o.path_evaluations
        )
    } else {
        "No path: the optimum is a point of the global stage.".to_string()
    };
    let references = if o.references.is_empty() {
        ""
    } else {
        " black diamonds: the references;"
    };
    let caption = format!(
        "Colour: {} on the grid ({}); hatched cells violate a constraint, and the colour range \
         is that of the feasible cells. White dots and crosses: the feasible and infeasible \
         points of the global stage. {path} Orange circle: the start;{references} red star: the \
         optimum, the best feasible point evaluated anywhere.",
        o.objective_label,
        if o.map.is_empty() {
            "no map computed"
        } else {
            o.map_note.as_str()
        },
    );
    format!(
        "<h3>Study <code>{name}</code></h3><p class=\"note\">{summary}</p><div class=\"grid\">{figure}<div>\
         <table class=\"study\"><thead><tr>{head}</tr></thead><tbody>\n{rows}</tbody></table>\
         <p class=\"note\">{outcome}</p>{notes}</div></div>\n",
        name = esc(&o.name),
        summary = esc(&o.summary),
        figure = figure(file, &format!("Study {}: objective map and search", o.name), &caption),
        outcome = esc(&o.outcome),
    )
}

fn check_rows(checks: &[Check]) -> String {
    let mut rows = String::new();
    for c in crate::report::table::ordered(checks) {
        let op = match c.bound {
            Bound::Max => "≤",
            Bound::Min => "≥",
        };
        let unit = if c.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", c.unit)
        };
        let _ = writeln!(
            rows,
            "<tr class=\"{}\"><td><code>{}</code></td><td class=\"num\">{}{unit}</td><td class=\"num\">{op} {}{unit}</td><td class=\"verdict\">{}</td><td>{}</td></tr>",
            if c.passed { "pass" } else { "fail" },
            esc(&c.id),
            esc(&number(c.value)),
            esc(&number(c.limit)),
            if c.passed { "pass" } else { "FAIL" },
            esc(&c.at)
        );
    }
    rows
}

fn page(input: &ReportInput, figures: &str) -> String {
    let spec = input.spec;
    let d = &spec.design;
    let m = &spec.modification;
    let failed = input.checks.iter().filter(|c| !c.passed).count();
    let verdict = if failed == 0 {
        format!(
            "<p class=\"banner pass\">PASSED: all {} checks pass</p>",
            input.checks.len()
        )
    } else {
        format!(
            "<p class=\"banner fail\">FAILED: {failed} of {} checks fail</p>",
            input.checks.len()
        )
    };
    let row = |k: &str, v: String| format!("<tr><th>{}</th><td>{}</td></tr>", esc(k), esc(&v));
    let mut design = String::new();
    for (k, v) in [
        (
            "teeth nc / rollers np",
            format!("{} / {}", d.teeth, d.rollers),
        ),
        (
            "eccentricity e",
            format!("{} mm", number(d.eccentricity_mm)),
        ),
        (
            "roller circle Rp / roller radius Rrp",
            format!(
                "{} mm / {} mm",
                number(d.roller_circle_radius_mm),
                number(d.roller_radius_mm)
            ),
        ),
        ("face width B", format!("{} mm", number(d.face_width_mm))),
        (
            "output pins",
            format!(
                "{} on rw {} mm, pin radius {} mm, hole radius {} mm",
                d.pins.count,
                number(d.pins.circle_radius_mm),
                number(d.pins.pin_radius_mm),
                number(d.hole_radius_mm())
            ),
        ),
        (
            "material",
            format!(
                "E {} GPa, ν {} (rollers and pins: E {} GPa, ν {}); E* {} GPa",
                number(d.disc_material.youngs_modulus_mpa / 1000.0),
                number(d.disc_material.poisson_ratio),
                number(d.roller_material.youngs_modulus_mpa / 1000.0),
                number(d.roller_material.poisson_ratio),
                number(d.contact_modulus_mpa() / 1000.0)
            ),
        ),
        ("K1 = e·np/Rp", number(d.k1())),
    ] {
        design += &row(k, v);
    }
    let mut modification = String::new();
    for (k, v) in [
        ("shift ΔRp", format!("{} mm", number(m.shift_mm))),
        (
            "equidistant ΔRrp",
            format!("{} mm", number(m.equidistant_mm)),
        ),
        (
            "rotation Δδ",
            format!("{} deg", number(m.rotation_rad.to_degrees())),
        ),
        (
            "tip clearance ΔRrp − ΔRp",
            format!("{} µm", number(m.tip_clearance_mm() * 1000.0)),
        ),
    ] {
        modification += &row(k, v);
    }
    let mut goldens = String::new();
    for g in input.goldens {
        let w = &g.comparison.worst;
        let unit = g.unit;
        let _ = writeln!(
            goldens,
            "<tr class=\"{}\"><td><code>{}</code></td><td><code>{}</code></td><td class=\"num\">{} {unit}</td><td class=\"num\">{} {unit}</td><td>{}</td><td class=\"num\">{}</td><td class=\"verdict\">{}</td></tr>",
            if g.comparison.passed { "pass" } else { "fail" },
            esc(&format!("{}/{}", g.golden.scene, g.golden.quantity)),
            esc(&g.golden.path.display().to_string()),
            esc(&number(w.deviation)),
            esc(&number(w.band)),
            esc(&w.place()),
            g.comparison.points,
            if g.comparison.passed { "pass" } else { "FAIL" },
        );
    }
    let golden_section = if goldens.is_empty() {
        String::new()
    } else {
        format!(
            "<section><h2>Golden curves</h2><p class=\"note\">Each curve compared point by point with its reviewed reference; the worst point is the one furthest outside (or least inside) its band abs + rel·|golden|.</p>\
             <table><thead><tr><th>curve</th><th>golden file</th><th>worst |deviation|</th><th>band there</th><th>where</th><th>points</th><th>verdict</th></tr></thead><tbody>{goldens}</tbody></table></section>"
        )
    };
    format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>Design review: {name}</title>
<style>
body {{ font-family: {font}; color: #222; margin: 24px auto; max-width: 1360px; padding: 0 16px; line-height: 1.4; }}
h1 {{ font-size: 26px; margin: 0 0 6px; }}
h2 {{ font-size: 20px; margin: 28px 0 10px; border-bottom: 1px solid #ddd; padding-bottom: 4px; }}
.meta {{ color: #555; font-size: 13px; }}
.meta code {{ font-size: 12px; }}
.banner {{ font-size: 18px; font-weight: bold; padding: 10px 14px; border-radius: 4px; margin: 12px 0; }}
.banner.pass {{ background: #e3f4e1; color: #1d6b1a; border: 1px solid #9fd39a; }}
.banner.fail {{ background: #fde2e2; color: #a11212; border: 1px solid #f0a1a1; }}
table {{ border-collapse: collapse; font-size: 14px; margin: 6px 0; }}
th, td {{ text-align: left; padding: 4px 10px; border-bottom: 1px solid #eee; vertical-align: top; }}
thead th {{ background: #f3f3f3; }}
td.num {{ text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }}
tr.fail td.verdict {{ color: #b00; font-weight: bold; }}
tr.pass td.verdict {{ color: #1d6b1a; }}
tr.fail {{ background: #fff3f3; }}
tr.cheapest {{ background: #e3f4e1; font-weight: bold; }}
tr.reference {{ background: #f3f3f3; }}
td.over {{ color: #b00; }}
table.study th {{ font-weight: normal; }}
table.study thead th {{ font-weight: bold; text-align: right; }}
table.study .optimum {{ font-weight: bold; }}
table.study small {{ font-weight: normal; color: #666; }}
td.verdict.pass {{ color: #1d6b1a; }}
td.verdict.fail, td.violated {{ color: #b00; font-weight: bold; }}
h3 {{ font-size: 17px; margin: 22px 0 4px; }}
.cols {{ display: flex; gap: 40px; flex-wrap: wrap; }}
.grid {{ display: grid; grid-template-columns: repeat(auto-fill, minmax(660px, 1fr)); gap: 18px; }}
figure {{ margin: 0; }}
figure img {{ max-width: 100%; border: 1px solid #ddd; }}
figcaption {{ font-size: 13px; color: #444; max-width: 660px; }}
.note {{ color: #555; font-size: 14px; }}
pre {{ background: #f7f7f7; padding: 10px; font-size: 12px; overflow-x: auto; }}
</style></head>
<body>
<h1>Design review: {name}</h1>
<p class="meta">spec <code>{path}</code> · SHA-256 <code>{sha}</code> · cycloid {version} · generated {date}</p>
{verdict}
<section><h2>Design</h2><div class="cols">
<table><thead><tr><th colspan="2">reducer</th></tr></thead><tbody>{design}</tbody></table>
<table><thead><tr><th colspan="2">tooth-profile modification</th></tr></thead><tbody>{modification}</tbody></table>
</div></section>
<section><h2>Checks</h2><p class="note">Failures first, the furthest outside its limit first.</p>
<table><thead><tr><th>check</th><th>value</th><th>limit</th><th>verdict</th><th>where</th></tr></thead><tbody>
{checks}</tbody></table></section>
{golden_section}
{figures}
<details><summary>Spec source</summary><pre>{source}</pre></details>
</body></html>
"#,
        name = esc(&spec.name),
        font = svg::FONT,
        path = esc(&spec.path),
        sha = crate::engine::golden::sha256_hex(&spec.source),
        version = env!("CARGO_PKG_VERSION"),
        date = crate::engine::golden::today(),
        checks = check_rows(input.checks),
        source = esc(&spec.source),
    )
}
