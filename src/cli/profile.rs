//! `cycloid profile`: export the modified profile as CSV points and a DXF polyline.

use super::output::{distinct_outputs, inputs_of, print, write_file};
use super::Outcome;
use crate::engine::commands::{self, MIN_PROFILE_TOLERANCE_MM};
use crate::error::{Error, ErrorKind, Result};
use crate::report::export;
use crate::{numeric, spec, units};
use std::io::Write;

pub(super) fn run(
    path: &str,
    csv: Option<&str>,
    dxf: Option<&str>,
    tolerance_um: f64,
    out: &mut dyn Write,
) -> Result<Outcome> {
    check_tolerance(tolerance_um)?;
    if csv.is_none() && dxf.is_none() {
        return Err(Error::new(
            ErrorKind::Usage,
            "profile writes the profile to --csv PATH, --dxf PATH or both; give at least one \
             (nothing was written)",
        ));
    }
    let spec = spec::load(path)?;
    distinct_outputs(
        &inputs_of(path, Some(&spec)),
        &[("--csv", csv), ("--dxf", dxf)],
    )?;
    let tol = units::mm_from_um(tolerance_um);
    let points = commands::profile(&spec, tol)?;
    if let Some(p) = csv {
        write_file(p, &export::csv(&spec, &points, tol))?;
    }
    if let Some(p) = dxf {
        write_file(p, &export::dxf(&spec, &points, tol))?;
    }
    print(
        out,
        &format!(
            "profile of `{}`: {} points, chordal error <= {tolerance_um} um\n",
            spec.name,
            points.len()
        ),
    )?;
    Ok(Outcome::Passed)
}

/// `--tolerance-um` is a positive number of at least 1 nm.
fn check_tolerance(tolerance_um: f64) -> Result<()> {
    let bad = |m: String| Err(Error::new(ErrorKind::InvalidValue, m));
    if !(tolerance_um.is_finite() && tolerance_um > 0.0) {
        return bad(format!(
            "--tolerance-um must be a positive number, got {}",
            numeric::input(tolerance_um)
        ));
    }
    let min_um = units::um(MIN_PROFILE_TOLERANCE_MM);
    if tolerance_um < min_um {
        return bad(format!(
            "--tolerance-um must be at least {min_um} (1 nm), got {}",
            numeric::input(tolerance_um)
        ));
    }
    Ok(())
}
