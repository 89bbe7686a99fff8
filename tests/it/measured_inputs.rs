//! Measured-disc inputs of issue 26 ("no data lost, no false pass, no crash"), one test per
//! case: points in another unit, a disc the design rules refuse, standard CSV quoting, a DXF
//! with whitespace after EOF or in Windows-1252, a spline of 120,000 control points and the
//! bounds on every count, a form-error order of 10⁹, and `tolerance --write-sample` of a spec
//! with a measured profile. The measured files are made here from `cycloid profile` of the
//! paper's drawing (ΔRp 0.125 mm, ΔRrp 0.1593 mm), whose points lie on that profile: a fit of
//! them gives back the drawing's modification, printed to 1e-6 mm.

use crate::common::{cycloid, PaperSpec, Scratch};
use cycloid::measure::points::{parse_csv_at_most, parse_dxf_at_most, MAX_FILE_BYTES, MAX_POINTS};

/// The drawing's modification lines as `fit` prints them (6 decimals, zero uncertainty: the
/// points are on the profile).
const DRAWN: [&str; 2] = [
    "\n  shift_mm                0.125000 mm   ± 0.000 µm\n",
    "\n  equidistant_mm          0.159300 mm   ± 0.000 µm\n",
];

/// `made.yaml` (the paper's drawing) and its exports `disc.csv` and `disc.dxf` in `dir`.
fn export(dir: &Scratch) {
    dir.write(
        "made.yaml",
        PaperSpec::new().modification(0.125, 0.1593).text(),
    );
    let run = cycloid(
        &dir.path,
        &[
            "profile",
            "made.yaml",
            "--csv",
            "disc.csv",
            "--dxf",
            "disc.dxf",
        ],
    );
    assert_eq!(run.code(), 0, "{}", run.stderr);
}

/// The paper's spec with another nominal modification (the fit's start) identifying `file`.
fn fitting(file: &str, format: &str) -> PaperSpec {
    PaperSpec::new().modification(0.1, 0.13).with(&format!(
        "measured_profile: {{file: {file}, format: {format}, harmonics: 0, fit: [shift_mm, \
         equidistant_mm]}}\n"
    ))
}

/// `fit fit.yaml` in `dir` of a spec identifying `file`.
fn fit(dir: &Scratch, file: &str, format: &str) -> crate::common::Run {
    dir.write("fit.yaml", fitting(file, format).text());
    cycloid(&dir.path, &["fit", "fit.yaml"])
}

/// The 1-based line and column of the key `file:` in the flow mapping of `measured_profile:`.
fn measured_file_at(text: &str) -> (usize, usize) {
    let i = text
        .lines()
        .position(|l| l.starts_with("measured_profile:"))
        .unwrap();
    let column = text.lines().nth(i).unwrap().find("{file:").unwrap() + 2;
    (i + 1, column)
}

/// The export with `$INSUNITS` set to `code`.
fn with_units(dxf: &str, code: u32) -> String {
    let from = "$INSUNITS\n70\n4\n";
    assert_eq!(dxf.matches(from).count(), 1, "the export says mm");
    dxf.replacen(from, &format!("$INSUNITS\n70\n{code}\n"), 1)
}

/// Case 1, DXF: a drawing in inches (`$INSUNITS 1`) was read as mm and fitted. Every unit
/// other than mm is refused at the line of its value, naming it (the AutoCAD DXF reference's
/// codes: 1 inches, 6 metres, 13 microns); unitless (0) leaves the numbers without a unit and
/// they are read as mm, so the drawing's own numbers give back its modification.
#[test]
fn a_dxf_in_another_unit_is_refused_naming_it() {
    let dir = Scratch::new("measured-units");
    export(&dir);
    let dxf = dir.read("disc.dxf");
    let value_line = dxf.lines().position(|l| l == "$INSUNITS").unwrap() + 3;
    for (code, unit) in [(1, "inches"), (6, "metres"), (13, "microns")] {
        dir.write("other.dxf", with_units(&dxf, code));
        let run = fit(&dir, "other.dxf", "dxf");
        assert_eq!(
            (run.code(), run.stderr.as_str()),
            (
                2,
                format!(
                    "other.dxf:{value_line}:1: invalid value: the drawing is in {unit} \
                     ($INSUNITS {code}): measured points are read in millimetres ($INSUNITS 4, \
                     or 0 for unitless numbers read as mm); export the drawing in mm\n"
                )
                .as_str()
            )
        );
    }
    dir.write("unitless.dxf", with_units(&dxf, 0));
    let run = fit(&dir, "unitless.dxf", "dxf");
    assert_eq!(run.code(), 0, "{}", run.stderr);
    assert!(
        DRAWN.iter().all(|l| run.stdout.contains(l)),
        "{}",
        run.stdout
    );
}

/// Case 1, CSV: the drawing's points divided by 25.4 (a CMM set to inches) fitted with a small
/// RMS to an impossible disc, exit 0. The identified disc is now held to the bound of a part
/// as built: its profile must lie less than e = 2 mm from the drawing's. Independently of the
/// fit: the scaled points lie within (Rp + ΔRp + e − Rrp − ΔRrp)/25.4 = 28.97/25.4 = 1.14 mm of
/// their centre while the drawing's root is at 24.97 mm, so any disc through them lies at
/// least 23.8 mm from the drawing somewhere. `fit` and `check` refuse it at the key naming the
/// file; the message's distance is the sum of the changes it lists.
#[test]
fn a_csv_in_inches_is_no_disc_of_this_design() {
    let dir = Scratch::new("measured-inches");
    export(&dir);
    let scaled: String = dir
        .read("disc.csv")
        .lines()
        .map(|l| match l.split(',').collect::<Vec<_>>()[..] {
            [x, y, ..] if !l.starts_with(['#', 'x']) => {
                let (x, y): (f64, f64) = (x.parse().unwrap(), y.parse().unwrap());
                format!("{:.9},{:.9}\n", x / 25.4, y / 25.4)
            }
            _ => format!("{l}\n"),
        })
        .collect();
    dir.write("inches.csv", scaled);
    let text = fitting("inches.csv", "csv").text().to_string();
    let (line, column) = measured_file_at(&text);
    dir.write("fit.yaml", &text);
    for command in ["fit", "check"] {
        let run = cycloid(&dir.path, &[command, "fit.yaml"]);
        assert_eq!(run.code(), 2, "{command}: {}", run.stderr);
        let head = format!(
            "fit.yaml:{line}:{column}: invalid value: measured_profile.file: the disc \
             identified from `inches.csv` lies up to "
        );
        let rest = run
            .stderr
            .strip_prefix(&head)
            .unwrap_or_else(|| panic!("{}", run.stderr));
        let numbers: Vec<f64> = rest
            .split([' ', '('])
            .filter_map(|w| w.parse().ok())
            .collect();
        // lies up to D mm (shift_mm S mm and equidistant_mm Q mm ..., form error up to W mm)
        let [moved, shift, equidistant, form, e] = numbers[..5] else {
            panic!("{rest}")
        };
        assert!(moved >= 23.8, "{rest}");
        assert_eq!(e, 2.0, "{rest}");
        // 4 significant digits each: their sum within the rounding of the five.
        let sum = shift.abs() + equidistant.abs() + form;
        assert!((moved - sum).abs() <= 1e-3 * moved, "{rest}");
        assert!(
            rest.ends_with(
                "not less than the eccentricity e = 2 mm that a part as built may move (the \
                 teeth are 2e deep): the points are not a disc of this design, or not in mm\n"
            ),
            "{rest}"
        );
    }
}

/// Case 1, design rules: a disc 20 µm thinner than drawn (ΔRrp 0.1793 mm), well within the
/// bound of a part as built, on a design whose pin holes clear the tooth root by 10 µm
/// (rw = 19.9557 mm, hole radius 3 + e = 5 mm). Its root radius Rp + ΔRp − e − (Rrp + ΔRrp)
/// = 30.125 − 2 − 3.1793 = 24.9457 mm is below rw + hole = 24.9557 mm: the holes cut the
/// root. `fit` reported it (exit 0); it is refused with the rule and these closed-form numbers.
#[test]
fn a_disc_that_breaks_a_design_rule_is_refused_with_the_rule() {
    let dir = Scratch::new("measured-rule");
    let made = PaperSpec::new().modification(0.125, 0.1793);
    dir.write("made.yaml", made.text());
    let run = cycloid(&dir.path, &["profile", "made.yaml", "--csv", "thin.csv"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
    let spec = PaperSpec::new()
        .modification(0.125, 0.1593)
        .edit("circle_radius_mm: 18.0 ", "circle_radius_mm: 19.9557 ")
        .with(
            "measured_profile: {file: thin.csv, format: csv, harmonics: 0, fit: [shift_mm, \
             equidistant_mm]}\n",
        );
    dir.write("fit.yaml", spec.text());
    let run = cycloid(&dir.path, &["fit", "fit.yaml"]);
    assert_eq!(run.code(), 2, "{}", run.stderr);
    let (line, column) = measured_file_at(spec.text());
    assert!(
        run.stderr.starts_with(&format!(
            "fit.yaml:{line}:{column}: invalid value: measured_profile.file: the disc \
             identified from `thin.csv` (shift_mm 0.1250, equidistant_mm 0.1793) breaks a \
             design rule, the points are not a disc of this design, or not in mm: output-pin \
             holes cut into the tooth root: pin circle radius + hole radius = 19.9557 + 5.0000 \
             = 24.9557 mm reaches the root radius of the profile, Rp + ΔRp − e − (Rrp + ΔRrp) \
             = 24.9457 mm"
        )),
        "{}",
        run.stderr
    );
}

/// Case 2: a header written with standard CSV quoting (`"x_mm","y_mm"`, as spreadsheets and
/// many CMM programs write it) was refused. Quoted names and cells, and a quoted note holding a
/// comma, read as their text: the drawing's modification comes back.
#[test]
fn a_quoted_csv_reads_as_its_text() {
    let dir = Scratch::new("measured-quoted");
    export(&dir);
    let quoted: String = dir
        .read("disc.csv")
        .lines()
        .map(|l| match l.split(',').collect::<Vec<_>>()[..] {
            _ if l.starts_with('#') => format!("{l}\n"),
            [x, y, ..] if l.starts_with('x') => format!("\"{x}\",\"{y}\",\"note\"\n"),
            [x, y, ..] => format!("\"{x}\",\"{y}\",\"tooth, flank\"\n"),
            _ => panic!("{l}"),
        })
        .collect();
    assert!(quoted.contains("\n\"x_mm\",\"y_mm\",\"note\"\n"));
    dir.write("quoted.csv", quoted);
    let run = fit(&dir, "quoted.csv", "csv");
    assert_eq!(run.code(), 0, "{}", run.stderr);
    assert!(
        DRAWN.iter().all(|l| run.stdout.contains(l)),
        "{}",
        run.stdout
    );
}

/// Case 3: a blank line after `EOF` (an editor's) made the file unreadable ("`` is not a DXF
/// group code"). Whitespace after EOF is read past; anything else there (a second drawing
/// appended) is refused at its line, not dropped unseen.
#[test]
fn a_dxf_reads_past_whitespace_after_eof_only() {
    let dir = Scratch::new("measured-eof");
    export(&dir);
    let dxf = dir.read("disc.dxf");
    assert!(dxf.ends_with("0\nEOF\n"));
    for tail in ["\n", "\r\n  \r\n\t\n"] {
        dir.write("tail.dxf", format!("{dxf}{tail}"));
        let run = fit(&dir, "tail.dxf", "dxf");
        assert_eq!(run.code(), 0, "{tail:?}: {}", run.stderr);
        assert!(
            DRAWN.iter().all(|l| run.stdout.contains(l)),
            "{}",
            run.stdout
        );
    }
    dir.write("twice.dxf", format!("{dxf}\n{dxf}"));
    let run = fit(&dir, "twice.dxf", "dxf");
    let eof = dxf.lines().count();
    assert_eq!(
        (run.code(), run.stderr.as_str()),
        (
            2,
            format!(
                "twice.dxf:{}:1: invalid value: `999` after the end of the drawing (`EOF` at \
                 line {}): a DXF file ends at EOF; remove what follows, or split a second \
                 drawing into its own file\n",
                eof + 2,
                eof
            )
            .as_str()
        )
    );
}

/// The export with an R12 header naming the code page ANSI_1252 and a TEXT entity
/// `<label>` (bytes) before the end of its ENTITIES section.
fn ansi_1252(dxf: &str, label: &[u8]) -> Vec<u8> {
    let header = "$INSUNITS\n70\n4\n";
    let dxf = dxf.replacen(
        header,
        &format!("$ACADVER\n1\nAC1009\n9\n$DWGCODEPAGE\n3\nANSI_1252\n9\n{header}"),
        1,
    );
    let end = dxf.rfind("0\nENDSEC\n").unwrap();
    let mut bytes = dxf.as_bytes()[..end].to_vec();
    bytes.extend_from_slice(b"0\nTEXT\n8\nNOTES\n10\n0.0\n20\n-40.0\n40\n2.5\n1\n");
    bytes.extend_from_slice(label);
    bytes.extend_from_slice(b"\n");
    bytes.extend_from_slice(&dxf.as_bytes()[end..]);
    bytes
}

/// Case 4: an R12 drawing in ANSI_1252 with `Ø 18 H7` (Ø is the byte 0xD8) in a TEXT was
/// refused as "not UTF-8 text". It is decoded as Windows-1252 and fits as the clean drawing.
/// A code-page byte inside a number is no number: refused at its line, decoded (0xB5 is µ in
/// Windows-1252), never read as another value.
#[test]
fn an_ansi_1252_drawing_reads_and_its_numbers_stay_exact() {
    let dir = Scratch::new("measured-ansi");
    export(&dir);
    let dxf = dir.read("disc.dxf");
    let bytes = ansi_1252(&dxf, b"\xD8 18 H7");
    assert!(std::str::from_utf8(&bytes).is_err(), "the file is no UTF-8");
    dir.write("ansi.dxf", &bytes);
    let run = fit(&dir, "ansi.dxf", "dxf");
    assert_eq!(run.code(), 0, "{}", run.stderr);
    assert!(
        DRAWN.iter().all(|l| run.stdout.contains(l)),
        "{}",
        run.stdout
    );
    // The first vertex's x (lines VERTEX, 8, PROFILE, 10, x) with a µ appended; the header
    // gained 8 lines above it ($ACADVER and $DWGCODEPAGE with their values and codes).
    let x_index = dxf.lines().position(|l| l == "VERTEX").unwrap() + 4;
    let x = dxf.lines().nth(x_index).unwrap().to_string();
    let mut broken = ansi_1252(&dxf, b"\xD8 18 H7");
    let vertex = format!("VERTEX\n8\nPROFILE\n10\n{x}\n");
    broken.insert(find(&broken, vertex.as_bytes()) + vertex.len() - 1, 0xB5);
    dir.write("broken.dxf", &broken);
    let run = fit(&dir, "broken.dxf", "dxf");
    assert_eq!(
        (run.code(), run.stderr.as_str()),
        (
            2,
            format!(
                "broken.dxf:{}:1: invalid value: `{x}µ` is not a finite number\n",
                x_index + 1 + 8
            )
            .as_str()
        )
    );
}

/// The offset of the first `needle` in `hay`.
fn find(hay: &[u8], needle: &[u8]) -> usize {
    hay.windows(needle.len()).position(|w| w == needle).unwrap()
}

/// Case 5: a closed SPLINE of 120,000 control points never returned: every one of its 32·n
/// points searched its knot span from the first knot, n/2 steps on average (2.3e11 in all).
/// The span is now found by bisection, and a spline is read at 32 points per control point up
/// to 65,536 points, at one per control point beyond. The spline here is of degree 1 through
/// 120,000 points spaced along the export's polygon (120,001 with the closing one), so its
/// curve is that polygon, within the export's 0.5 µm chordal tolerance of the profile: the
/// modification comes back within 0.5 µm (as from the polygon itself, `measure_cli`).
#[test]
fn a_spline_of_120000_control_points_is_read() {
    let dir = Scratch::new("measured-spline");
    export(&dir);
    let vertices: Vec<(f64, f64)> = dir
        .read("disc.csv")
        .lines()
        .filter(|l| !l.starts_with(['#', 'x']))
        .map(|l| {
            let mut c = l.split(',').map(|v| v.parse::<f64>().unwrap());
            (c.next().unwrap(), c.next().unwrap())
        })
        .collect();
    let (n, count) = (vertices.len(), 120_000);
    let mut control: Vec<(f64, f64)> = (0..count)
        .map(|k| {
            let u = (k * n) as f64 / count as f64;
            let (i, f) = (u.floor() as usize, u.fract());
            let (a, b) = (vertices[i], vertices[(i + 1) % n]);
            (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1))
        })
        .collect();
    control.push(control[0]);
    let m = control.len();
    let mut dxf = String::from("0\nSECTION\n2\nENTITIES\n0\nSPLINE\n8\nPROFILE\n70\n8\n71\n1\n");
    for k in std::iter::once(0).chain(0..m).chain(std::iter::once(m - 1)) {
        dxf += &format!("40\n{k}\n");
    }
    for (x, y) in &control {
        dxf += &format!("10\n{x:.9}\n20\n{y:.9}\n");
    }
    dxf += "0\nENDSEC\n0\nEOF\n";
    dir.write("spline.dxf", dxf);
    let run = fit(&dir, "spline.dxf", "dxf");
    assert_eq!(run.code(), 0, "{}", run.stderr);
    assert!(
        run.stdout
            .starts_with("cycloid fit `paper-table-1`: 120001 profile points, 0 hole points"),
        "{}",
        run.stdout
    );
    let value = |name: &str| -> f64 {
        let line = run
            .stdout
            .lines()
            .find(|l| l.trim_start().starts_with(name))
            .unwrap();
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
    };
    assert!((value("shift_mm") - 0.125).abs() < 5e-4, "{}", run.stdout);
    assert!(
        (value("equidistant_mm") - 0.1593).abs() < 5e-4,
        "{}",
        run.stdout
    );
}

/// Case 5, every other count: a CSV of more than the reader's bound and a polyline of more
/// vertices are refused at the line that goes past it, naming it; exactly the bound is read.
/// The bound is a parameter (`parse_*_at_most`) so that this runs on 1,000 rows, not 10^7
/// (issue 39 §5: a scan of 10^7 points is read); `points::read` uses `MAX_POINTS`.
#[test]
fn every_count_of_the_reader_is_bounded() {
    const MAX: usize = 1_000;
    let rows = |n: usize| String::from("x_mm,y_mm\n") + &"1.5,2\n".repeat(n);
    assert_eq!(
        parse_csv_at_most("p.csv", &rows(MAX), MAX).unwrap().len(),
        MAX
    );
    let message = |line: usize, file: &str| {
        format!(
            "{file}:{line}:1: invalid value: more than {MAX} measured points: a file gives at \
             most {MAX} (a CMM scan of a disc holds thousands to tens of thousands, an optical \
             scan millions; the fit thins a denser profile itself); thin the points, e.g. \
             every k-th"
        )
    };
    let e = parse_csv_at_most("p.csv", &rows(MAX + 1), MAX).unwrap_err();
    // The header is line 1, point k is line k + 1.
    assert_eq!(e.to_string(), message(MAX + 2, "p.csv"));
    let mut dxf = String::from("0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\nPROFILE\n70\n1\n");
    dxf += &"10\n1.5\n20\n2\n".repeat(MAX + 1);
    dxf += "0\nENDSEC\n0\nEOF\n";
    let e = parse_dxf_at_most("p.dxf", &dxf, MAX).unwrap_err();
    assert_eq!(e.to_string(), message(5, "p.dxf"));
    // The shipped bound is issue 39's 10^7, and the byte cap holds 10^7 CMM rows of two
    // coordinates to the nm on a disc up to a metre across, with a `hole:J` feature cell.
    assert_eq!(MAX_POINTS, 10_000_000);
    let row = "-999.123456789,-999.123456789,hole:99\n";
    assert!((MAX_POINTS * row.len()) as u64 <= MAX_FILE_BYTES);
}

/// Issue 39 §5: a scan of 2^20 + 5 points (more than the old reader's 2^20) on the paper's
/// drawing (ΔRp 0.125 mm, ΔRrp 0.1593 mm), fitted with 12 form-error harmonics: 25 unknowns
/// (centre 2, orientation, 2 modifications, 2 × 10 orders: 2..=12 without 9) hold
/// 2^24 / 25 = 671,088 points, so every 2nd point is used, ⌈(2^20 + 5)/2⌉ = 524,291 of them,
/// and the report says so. The drawing's modification comes back: the points lie on its
/// profile to their 9 printed decimals, so the fit is exact to far below the 1e-6 mm printed.
#[test]
fn a_scan_denser_than_the_fit_is_read_thinned_and_fitted() {
    use cycloid::geometry::profile::Profile;
    let dir = Scratch::new("measured-scan");
    let made = PaperSpec::new().modification(0.125, 0.1593);
    let spec = made.parse("made.yaml");
    let profile = Profile::new(&spec.design, &spec.modification);
    let n = (1 << 20) + 5;
    let mut csv = String::from("x_mm,y_mm\n");
    for i in 0..n {
        let p = profile.point(std::f64::consts::TAU * i as f64 / n as f64);
        csv += &format!("{:.9},{:.9}\n", p.x, p.y);
    }
    dir.write("scan.csv", &csv);
    dir.write(
        "fit.yaml",
        PaperSpec::new()
            .modification(0.1, 0.13)
            .with(
                "measured_profile: {file: scan.csv, format: csv, harmonics: 12, fit: [shift_mm, \
                 equidistant_mm]}\n",
            )
            .text(),
    );
    let run = cycloid(&dir.path, &["fit", "fit.yaml"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
    assert!(
        run.stdout.contains(&format!(
            "\nthinned: every 2nd of {n} profile points (524291 used; hole points all kept;"
        )),
        "{}",
        run.stdout
    );
    assert!(
        run.stdout.starts_with(
            "cycloid fit `paper-table-1`: 524291 profile points, 0 hole points, 25 unknowns"
        ),
        "{}",
        run.stdout
    );
    for line in DRAWN {
        assert!(run.stdout.contains(line), "{}", run.stdout);
    }
}

/// Case 5, the fit: points × unknowns beyond `MAX_JACOBIAN_ENTRIES` (2^24) are refused before
/// anything is allocated when thinning the profile cannot bring them within it (hole points are
/// all kept): 400 profile and 50,000 hole points with 200 harmonics on the paper's 9-tooth disc
/// are 6 + 2·177 = 360 unknowns (the hole radius; orders 2..=200 without the 22 multiples of
/// 9), 18,144,000 entries, the holes' alone 18,000,000.
#[test]
fn a_fit_beyond_its_jacobian_bound_is_refused() {
    use cycloid::measure::{fit, Feature, MeasuredPoint};
    let spec = PaperSpec::new().parse("p.yaml");
    let points: Vec<MeasuredPoint> = (0..50_400)
        .map(|k| {
            let a = k as f64 * 1e-4;
            MeasuredPoint {
                point: cycloid::geometry::Vec2::new(25.0 * a.cos(), 25.0 * a.sin()),
                feature: if k < 400 {
                    Feature::Profile
                } else {
                    Feature::Hole(0)
                },
                line: k + 2,
            }
        })
        .collect();
    let request = fit::Request {
        design: &spec.design,
        nominal: spec.modification,
        fit: cycloid::model::measured::Fitted {
            shift: true,
            equidistant: true,
            rotation: false,
        },
        harmonics: 200,
    };
    let e = fit::identify(&request, &points).unwrap_err();
    assert_eq!(
        e.message,
        format!(
            "50400 points × 360 unknowns = 18144000 Jacobian entries, more than the {} \
             (128 MiB) a fit holds: thin the points (every k-th) or ask for fewer harmonics",
            fit::MAX_JACOBIAN_ENTRIES
        )
    );
    assert_eq!(fit::MAX_JACOBIAN_ENTRIES, 1 << 24);
}

/// Case 6: a form-error order of 10⁹ never returned (a series summed to order 10⁹ at every
/// sample). Orders above 1,000 are refused at their key, with the bound and its reason; order
/// 1,000 itself (a 0.1 µm wave, 0.19 mm long) checks.
#[test]
fn a_form_order_beyond_the_bound_is_refused_at_its_key() {
    let dir = Scratch::new("measured-order");
    let spec = |order: u64| {
        PaperSpec::new().edit(
            "  output_pins:\n",
            &format!(
                "  deviations:\n    form:\n      - {{order: {order}, cos_mm: 0.0001, sin_mm: 0.0}}\n  \
                 output_pins:\n"
            ),
        )
    };
    let text = spec(1_000_000_000).text().to_string();
    let line = text.lines().position(|l| l.contains("order:")).unwrap() + 1;
    let column = text.lines().nth(line - 1).unwrap().find("order:").unwrap() + 1;
    dir.write("s.yaml", &text);
    let run = cycloid(&dir.path, &["check", "s.yaml"]);
    assert_eq!(
        (run.code(), run.stderr.as_str()),
        (
            2,
            format!(
                "s.yaml:{line}:{column}: invalid value: reducer.deviations.form[0].order: order \
                 1000000000 is above 1000, the highest a form error may have: a wave of order k \
                 is about 2π·Rp/k long along the disc (1.885e-7 mm here, 0.1885 mm at order \
                 1000), and a wave shorter than a loaded roller's contact (~0.1 mm wide) is \
                 flattened by it: the model, one contact point per roller, does not resolve it \
                 (a fit identifies orders up to 200)\n"
            )
            .as_str()
        )
    );
    dir.write("s.yaml", spec(1000).text());
    let run = cycloid(&dir.path, &["check", "s.yaml"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
}

/// The terminal's as-built line of a disc fitted without form error read "form error of 0
/// harmonics (|w| ≤ -0.000 µm)": an empty sum of f64 is −0.0. The bound of no harmonic is 0.
#[test]
fn no_form_error_is_bounded_by_zero_not_minus_zero() {
    let dir = Scratch::new("measured-zero");
    export(&dir);
    dir.write("fit.yaml", fitting("disc.csv", "csv").text());
    let run = cycloid(&dir.path, &["check", "fit.yaml"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
    assert!(
        run.stdout
            .contains("form error of 0 harmonics (|w| ≤ 0.000 µm)"),
        "{}",
        run.stdout
    );
}

/// Case 7: `tolerance --write-sample K` of a spec with `measured_profile` wrote a spec that
/// `check` ran on the measured disc (34.30 µm of root clearance, ΔRp/ΔRrp 0.125/0.1593 mm)
/// plus the sample's draw, where the sample was drawn from the drawing (30 µm, 0.1/0.13 mm):
/// a failing sample checked as a pass (sample 12 below: 13.61 µm against the limit of 15,
/// replayed as 17.91 µm). The written spec leaves the measured profile out, and every failing
/// sample's value is its replay's `check --json` value bit for bit, and fails there too.
#[test]
fn a_written_sample_of_a_measured_spec_replays_its_value() {
    let dir = Scratch::new("measured-sample");
    export(&dir);
    let spec = fitting("disc.csv", "csv").with(
        "tolerances:\n  scene: rated\n  max_failure_rate: 0.5\n  equidistant_mm: 0.06\n  \
         samples: 20\n  seed: 5\n",
    );
    dir.write("t.yaml", spec.text());
    let run = cycloid(
        &dir.path,
        &["tolerance", "t.yaml", "--samples-csv", "s.csv"],
    );
    assert_eq!(run.code(), 0, "{}", run.stderr);
    let csv = dir.read("s.csv");
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == "min_clearance_mm")
        .unwrap();
    let failing: Vec<(usize, f64)> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .map(|r| (r[0].parse().unwrap(), r[col].parse().unwrap()))
        .filter(|(_, v)| *v < 0.015)
        .collect();
    assert!(failing.len() >= 2, "the seed draws failing samples: {csv}");
    for (k, recorded) in failing {
        let out = format!("sample{k}.yaml");
        let w = cycloid(
            &dir.path,
            &[
                "tolerance",
                "t.yaml",
                "--write-sample",
                &k.to_string(),
                &out,
            ],
        );
        assert_eq!(w.code(), 0, "{}", w.stderr);
        assert!(
            w.stdout.contains("without the measured profile `disc.csv`"),
            "{}",
            w.stdout
        );
        let written = dir.read(&out);
        assert!(!written.contains("\nmeasured_profile:"), "{written}");
        let c = cycloid(&dir.path, &["check", &out, "--json", "c.json"]);
        assert_eq!(c.code(), 1, "sample {k} fails its replay too: {}", c.stdout);
        let doc: serde_json::Value = serde_json::from_str(&dir.read("c.json")).unwrap();
        let value = doc["checks"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["id"].as_str().unwrap().ends_with("/min_clearance_mm"))
            .unwrap()["value"]
            .as_f64()
            .unwrap();
        assert_eq!(
            value.to_bits(),
            recorded.to_bits(),
            "sample {k}: {value} vs {recorded}"
        );
    }
}

/// Issue 39 §5: a file of one point measured over and over fixes no disc: it is refused as
/// such (exit 2, the count of distinct points), not fitted into "t = NaN".
#[test]
fn a_file_of_one_repeated_point_is_refused_naming_it() {
    let dir = Scratch::new("measured-repeated");
    export(&dir);
    let exported = dir.read("disc.csv");
    let mut lines = exported.lines().filter(|l| !l.starts_with('#'));
    let (header, point) = (lines.next().unwrap(), lines.nth(10).unwrap());
    dir.write(
        "one.csv",
        format!("{header}\n{}", format!("{point}\n").repeat(200)),
    );
    let run = fit(&dir, "one.csv", "csv");
    assert_eq!(run.code(), 2, "{run:?}");
    assert!(
        run.stderr
            .contains("1 distinct profile points (of 200; the others repeat them)"),
        "{}",
        run.stderr
    );
    assert!(!run.stderr.contains("NaN"), "{}", run.stderr);
}
