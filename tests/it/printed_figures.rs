//! How the terminal and the review print a quantity (issue 44 items 9 and 10): one formatter
//! per quantity wherever it appears, and a torsion loop's hysteresis loss to the loop's
//! resolution, its unit in the column's header.

use crate::common::{cycloid, PaperSpec, Scratch};
use serde_json::Value;

/// The cells of the headline line whose label starts with `label`: (value, where), split at
/// the runs of spaces that align the columns.
fn headline<'a>(out: &'a str, label: &str) -> (&'a str, &'a str) {
    let line = out
        .lines()
        .find(|l| l.trim_start().starts_with(label))
        .unwrap_or_else(|| panic!("no headline `{label}`:\n{out}"));
    let cells: Vec<&str> = line[2..]
        .split("  ")
        .map(str::trim)
        .filter(|c| !c.is_empty())
        .collect();
    assert_eq!(cells.len(), 3, "{line}");
    (cells[1], cells[2])
}

/// The shipped efficiency spec without any loss: every friction coefficient and the no-load
/// torque 0, so the efficiency P_out/(P_out + loss) is exactly 1.
fn lossless() -> String {
    let text = std::fs::read_to_string(format!(
        "{}/specs/reducer-efficiency.yaml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let text = text
        .replace("mu: 0.06 ", "mu: 0.0 ")
        .replace("mu: 0.0025 ", "mu: 0.0 ")
        .replace("no_load_torque_nmm: 30.0", "no_load_torque_nmm: 0.0");
    assert_eq!(text.matches("mu: 0.0 ").count(), 3, "{text}");
    text
}

/// An efficiency of exactly 1 reads "1.000" in the checks table and in the headline alike (it
/// is a ratio, not a count: before, the headline printed "1" beside the table's "1.000").
#[test]
fn a_whole_efficiency_reads_alike_in_the_table_and_the_headline() {
    let dir = Scratch::new("printed-efficiency");
    dir.write("s.yaml", lossless());
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
    assert_eq!(code, 0, "{out}{err}");
    let row = out
        .lines()
        .find(|l| l.starts_with("rated/min_mean_efficiency"))
        .unwrap_or_else(|| panic!("{out}"));
    let cells: Vec<&str> = row.split_whitespace().collect();
    assert_eq!(cells[1..5], ["1.000", "≥", "0.8500", "pass"], "{row}");
    assert_eq!(headline(&out, "mean efficiency").0, "1.000", "{out}");
}

/// A count reads as a whole number in the checks table as in the headline: the fewest rollers
/// in contact under a limit on it (before, the table printed "2.000" beside the headline's
/// "2"). The paper's design at 10 N·m has at least 2 rollers loaded at every angle.
#[test]
fn a_count_reads_alike_in_the_table_and_the_headline() {
    let text = PaperSpec::new()
        .rated_period(8)
        .with("limits:\n  min_rollers_in_contact: 1\n");
    let dir = Scratch::new("printed-count");
    dir.write("s.yaml", text.text());
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
    assert_eq!(code, 0, "{out}{err}");
    let row = out
        .lines()
        .find(|l| l.starts_with("rated/min_rollers_in_contact"))
        .unwrap_or_else(|| panic!("{out}"));
    let cells: Vec<&str> = row.split_whitespace().collect();
    let value = headline(&out, "fewest rollers in contact").0;
    assert_eq!(cells[1], value, "{row}\n{out}");
    assert_eq!(cells[2..4], ["≥", "1"], "{row}");
    assert!(
        value.parse::<u32>().is_ok_and(|n| n >= 2),
        "a whole count: {value}"
    );
}

/// The paper's design (its clearance: no preload) at 20 N·m rated, 20 steps a quarter, locked
/// at 0°, with fixed rollers at μ 0.05; `shift_mm`: the modification (ΔRp, 0) instead.
fn torsion_with_friction(shift_mm: Option<f64>) -> String {
    let mut spec = PaperSpec::new();
    if let Some(shift) = shift_mm {
        spec = spec.modification(shift, 0.0);
    }
    spec.scenes(
        "  - name: torsion\n    torque_sweep: { rated_nm: 20.0, steps: 20 }\n    crank: { \
         from_deg: 0.0, to_deg: 36.0, steps: 1 }\n    effects: [roller_contact]\n",
    )
    .edit(
        "modification:",
        "  friction: { rollers: { mode: fixed, mu: 0.05 } }\nmodification:",
    )
    .text()
    .to_string()
}

/// Without preload no contact is loaded at either edge of the dead band, so the hysteresis
/// loss is 0 (README, MODEL.md); what the loop computes there is friction at the one-sided
/// torques ±1e-6·rated, some 1e-8 arcmin. The headline reads 0 and says to what resolution:
/// the lag change of one torque step, ΔT/K = (20 N·m / 20) / K, K the torsional rigidity the
/// JSON gives. The review's table reads 0 too, its unit in the header. Preloaded by 1 µm the
/// loss is well above the resolution: printed as computed (to 4 digits), without a unit in the
/// review's cell.
#[test]
fn the_hysteresis_loss_prints_to_the_loops_resolution() {
    let dir = Scratch::new("printed-hysteresis");
    dir.write("s.yaml", torsion_with_friction(None));
    let args = ["check", "s.yaml", "--json", "r.json", "--report", "rev"];
    let (code, out, err) = cycloid(&dir.path, &args).parts();
    assert_eq!(code, 0, "{out}{err}");
    let doc: Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let scene = &doc["scenes"][0];
    let rigidity = scene["torsional_rigidity_nm_per_arcmin"][0]
        .as_f64()
        .unwrap();
    let resolution_arcmin = 1.0 / rigidity;
    let loss = scene["hysteresis_loss_arcmin"][0].as_f64().unwrap();
    assert!(loss.abs() < 1e-3 * resolution_arcmin, "{loss} arcmin");

    let (value, at) = headline(&out, "max hysteresis loss");
    assert_eq!(value, "0 arcmin", "{out}");
    let (head, tail) = (
        "crank 0.00° locked; 0 to the loop's resolution, ",
        " arcmin (the lag change of one torque step at the torsional rigidity)",
    );
    let printed = at
        .strip_prefix(head)
        .and_then(|r| r.strip_suffix(tail))
        .unwrap_or_else(|| panic!("{at}"));
    // Printed to 4 significant digits: within half a unit of the fourth.
    let printed: f64 = printed.parse().unwrap();
    assert!(
        (printed - resolution_arcmin).abs() <= 5e-4 * resolution_arcmin,
        "{printed} against ΔT/K = {resolution_arcmin}"
    );
    let page = dir.read("rev/index.html");
    assert!(page.contains("<th>hysteresis loss (arcmin)</th>"), "{page}");
    assert!(page.contains("<td><b>0</b></td>"), "{page}");

    dir.write("p.yaml", torsion_with_friction(Some(0.001)));
    let args = ["check", "p.yaml", "--json", "p.json", "--report", "prev"];
    let (code, out, err) = cycloid(&dir.path, &args).parts();
    assert_eq!(code, 0, "{out}{err}");
    let doc: Value = serde_json::from_str(&dir.read("p.json")).unwrap();
    let loss = doc["scenes"][0]["hysteresis_loss_arcmin"][0]
        .as_f64()
        .unwrap();
    let (value, _) = headline(&out, "max hysteresis loss");
    let shown = value
        .strip_suffix(" arcmin")
        .unwrap_or_else(|| panic!("{value}"));
    let shown_loss: f64 = shown.parse().unwrap();
    assert!(
        (shown_loss - loss).abs() <= 5e-4 * loss && loss > resolution_arcmin,
        "{value} against {loss}"
    );
    let page = dir.read("prev/index.html");
    assert!(page.contains(&format!("<td><b>{shown}</b></td>")), "{page}");
}
