//! `cycloid profile`: export the modified profile as CSV points and a DXF polyline, and the
//! disc as a STEP solid and an STL mesh.

use super::output::{distinct_outputs, inputs_of, print, write_file};
use super::{Outcome, ProfileArgs};
use crate::engine::commands::{self, MIN_PROFILE_TOLERANCE_MM};
use crate::error::{Error, ErrorKind, Result};
use crate::report::{export, step, stl};
use crate::{numeric, spec, units};
use std::io::Write;

pub(super) fn run(args: &ProfileArgs, out: &mut dyn Write) -> Result<Outcome> {
    let (path, tolerance_um) = (args.spec.as_str(), args.tolerance_um);
    check_tolerance(tolerance_um)?;
    let paths = [&args.csv, &args.dxf, &args.step, &args.stl].map(Option::as_deref);
    let [csv, dxf, step_path, stl_path] = paths;
    if paths.iter().all(Option::is_none) {
        return Err(Error::new(
            ErrorKind::Usage,
            "profile writes the profile to --csv PATH, --dxf PATH, --step PATH, --stl PATH or \
             several; give at least one (nothing was written)",
        ));
    }
    let spec = spec::load(path)?;
    let outputs: Vec<_> = ["--csv", "--dxf", "--step", "--stl"]
        .into_iter()
        .zip(paths)
        .collect();
    distinct_outputs(&inputs_of(path, Some(&spec)), &outputs)?;
    let tol = units::mm_from_um(tolerance_um);
    let points = commands::profile(&spec, tol)?;
    // The solids are built before any file is written: a refused disc writes nothing.
    let disc = match (step_path, stl_path) {
        (None, None) => None,
        _ => Some(commands::disc(&spec)?),
    };
    let solid = match (&disc, step_path) {
        (Some(d), Some(_)) => Some(d.solids(tol)?),
        _ => None,
    };
    let mesh = match (&disc, stl_path) {
        (Some(d), Some(_)) => Some(d.placed_mesh(tol)?),
        _ => None,
    };
    if let Some(p) = csv {
        write_file(p, export::csv(&spec, &points, tol))?;
    }
    if let Some(p) = dxf {
        write_file(p, export::dxf(&spec, &points, tol))?;
    }
    if let (Some(p), Some(s)) = (step_path, &solid) {
        write_file(p, step::step(&spec, s))?;
    }
    if let (Some(p), Some(m)) = (stl_path, &mesh) {
        write_file(p, stl::stl(&spec, m))?;
    }
    print(
        out,
        &format!(
            "profile of `{}`: {} points, chordal error <= {tolerance_um} um\n",
            spec.name,
            points.len()
        ),
    )?;
    if let Some(d) = &disc {
        let pieces = solid.as_ref().map(|s| s[0].0.piece_count());
        let triangles = mesh.as_ref().map(|m| m.triangles.len());
        print(
            out,
            &export::solid_lines(d, pieces, triangles, tolerance_um),
        )?;
    }
    Ok(Outcome::Passed)
}

/// `--tolerance-um` is a positive number of at least 1 nm.
fn check_tolerance(tolerance_um: f64) -> Result<()> {
    if !(tolerance_um.is_finite() && tolerance_um > 0.0) {
        return Err(Error::invalid_value(format!(
            "--tolerance-um must be a positive number, got {}",
            numeric::input(tolerance_um)
        )));
    }
    let min_um = units::um(MIN_PROFILE_TOLERANCE_MM);
    if tolerance_um < min_um {
        return Err(Error::invalid_value(format!(
            "--tolerance-um must be at least {min_um} (1 nm), got {}",
            numeric::input(tolerance_um)
        )));
    }
    Ok(())
}
