"""The Python package against the command line: the same JSON, the same errors at the same
places, numpy arrays of the documented shapes, threads that run in parallel."""

from __future__ import annotations

import gc
import json
import re
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import cycloid
from conftest import ROOT, cli_json, run_cli

SPECS = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "specs").rglob("*.yaml"))
FAST_SPECS = [s for s in SPECS if s != "specs/paper.yaml"]
BAD_SPECS = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "tests" / "bad-specs").glob("*.yaml"))


def py_check(spec: str):
    """(the run, None) or (None, the error) of checking `spec` from Python."""
    try:
        return cycloid.check(cycloid.load(spec)), None
    except cycloid.CycloidError as e:
        return None, e


def float_shape(js):
    """The shape of a non-empty JSON list of floats, or of equal-shape such lists; None else."""
    if not isinstance(js, list) or not js:
        return None
    if all(isinstance(x, float) for x in js):
        return (len(js),)
    shapes = {float_shape(r) for r in js}
    if len(shapes) == 1 and None not in shapes:
        return (len(js),) + shapes.pop()
    return None


def numbers(js) -> bool:
    """A non-empty JSON list of numbers, or a rectangular array of floats of any dimension."""
    if not isinstance(js, list) or not js:
        return False
    scalar = lambda x: isinstance(x, (int, float)) and not isinstance(x, bool)
    return all(scalar(x) for x in js) or float_shape(js) is not None


def assert_arrays_are_the_json(py, js, where=""):
    """Every value of the Python document equals the JSON's: arrays element for element, in
    the JSON's shape."""
    if isinstance(js, dict):
        assert isinstance(py, dict) and set(py) == set(js), where
        for k in js:
            assert_arrays_are_the_json(py[k], js[k], f"{where}.{k}")
    elif numbers(js):
        assert isinstance(py, np.ndarray), where
        assert py.shape == np.shape(js), where
        ints = all(isinstance(x, int) for x in np.array(js, dtype=object).flat)
        assert py.dtype == (np.int64 if ints else np.float64), where
        assert np.array_equal(py, np.array(js, dtype=py.dtype)), where
    elif isinstance(js, list):
        assert isinstance(py, list) and len(py) == len(js), where
        for i, (p, j) in enumerate(zip(py, js)):
            assert_arrays_are_the_json(p, j, f"{where}[{i}]")
    else:
        assert py == js and type(py) is type(js), where


@pytest.mark.parametrize("spec", FAST_SPECS)
def test_to_json_equals_the_cli_json(spec, cli, tmp_path):
    code, expected, stderr = cli_json(cli, spec, tmp_path)
    run, error = py_check(spec)
    if code == 2:
        # A spec the engine refuses: the same error, word for word.
        assert run is None and str(error) == stderr.strip()
        return
    assert error is None, str(error)
    assert json.loads(run.to_json()) == expected
    assert run.passed == (code == 0)
    # The Python objects are the JSON's values, arrays as numpy.
    assert_arrays_are_the_json(run.document, expected)


def test_paper_to_json_equals_the_cli_json(paper):
    run = paper["run"]
    assert paper["code"] == 0 and run.passed
    assert json.loads(run.to_json()) == paper["cli"]
    assert_arrays_are_the_json(run.document, paper["cli"])
    assert run.studies and run.studies == run.document["studies"]


def test_progress_is_called_a_few_times_a_second(paper):
    calls = paper["calls"]
    assert len(calls) >= 2, calls
    assert calls[-1][1:] == (1.0, "done")
    assert all(0.0 <= f <= 1.0 and isinstance(p, str) and p for _, f, p in calls)
    # At most one call per 0.25 s, the closing "done" apart: the engine spaces its calls by
    # 0.25 s of its own clock, so n calls before "done" span at least 0.25·(n − 1) s of the
    # call, which Python's clock around the whole call cannot undercut. The gaps as Python
    # sees them are not asserted: a callback that waits for the GIL arrives late, and the one
    # after it early, by however loaded the machine is. A one-sided bound holds on any machine.
    spaced = len(calls) - 1
    assert spaced - 1 <= paper["wall_s"] / 0.25 + 1e-9, (spaced, paper["wall_s"])


@pytest.mark.parametrize("spec", BAD_SPECS)
def test_bad_specs_raise_spec_error_at_the_cli_location(spec, cli):
    done = run_cli(cli, "check", spec)
    assert done.returncode == 2
    text = done.stderr.strip()
    with pytest.raises(cycloid.SpecError) as caught:
        cycloid.check(cycloid.load(spec))
    e = caught.value
    assert str(e) == text
    m = re.match(r"(.+?):(\d+):(\d+): ", text)
    if m:
        assert (e.file, e.line, e.column) == (m.group(1), int(m.group(2)), int(m.group(3)))
    else:
        assert e.line is None
    assert e.message and e.message in text
    if e.key is not None:
        assert f": {e.key}: " in text


SHIFTS_MM = [-0.004, 0.0, 0.003]


@pytest.mark.parametrize("shift_mm", SHIFTS_MM)
def test_a_shift_sweep_equals_the_cli(shift_mm, cli, tmp_path):
    base = cycloid.load("specs/reducer-loaded.yaml")
    spec = base.replace(**{"modification.shift_mm": shift_mm})
    # The text is edited in place: the same lines but the one value.
    changed = [
        (a, b) for a, b in zip(base.to_yaml().splitlines(), spec.to_yaml().splitlines()) if a != b
    ]
    assert len(spec.to_yaml().splitlines()) == len(base.to_yaml().splitlines())
    assert all("shift_mm" in b for _, b in changed) and len(changed) <= 1
    written = tmp_path / "shifted.yaml"
    written.write_text(spec.to_yaml())
    code, expected, stderr = cli_json(cli, str(written), tmp_path)
    assert code in (0, 1), stderr
    got = json.loads(cycloid.check(spec).to_json())
    assert got.pop("spec_path") == "specs/reducer-loaded.yaml"
    expected.pop("spec_path")
    assert got == expected


def test_the_shift_moves_the_clearance():
    """Thicker teeth (+ shift) leave less clearance: the sweep is not the same design thrice."""
    base = cycloid.load("specs/reducer.yaml")
    gaps = [
        cycloid.check(base.replace(**{"modification.shift_mm": s})).scenes["rated"]["min_clearance_mm"]
        for s in SHIFTS_MM
    ]
    assert gaps[0] > gaps[1] > gaps[2]


def test_replace_refuses_a_bad_value_at_its_key():
    spec = cycloid.load("specs/reducer.yaml")
    with pytest.raises(cycloid.SpecError) as caught:
        spec.replace(**{"reducer.roller_radius_mm": -1.0})
    e = caught.value
    assert e.key == "reducer.roller_radius_mm" and e.file == "specs/reducer.yaml"
    assert spec.to_yaml().splitlines()[e.line - 1].lstrip().startswith("roller_radius_mm")
    with pytest.raises(cycloid.SpecError) as caught:
        spec.replace(**{"reducer.no_such_key": 1})
    assert caught.value.key == "reducer.no_such_key"


def test_dict_and_yaml_round_trip():
    spec = cycloid.load("specs/reducer-loaded.yaml")
    d = spec.to_dict()
    assert d["name"] == spec.name and isinstance(d["scenes"], list)
    again = cycloid.Spec.from_dict(d)
    assert again.name == spec.name
    a = json.loads(cycloid.check(spec).to_json())
    b = json.loads(cycloid.check(again).to_json())
    for doc in (a, b):
        doc.pop("spec_path"), doc.pop("spec_sha256")
    assert a == b
    text = cycloid.Spec.from_yaml(spec.to_yaml())
    assert text.to_yaml() == spec.to_yaml() and text.path == "<string>"


def test_spec_error_from_text_is_located():
    bad = cycloid.load("specs/reducer.yaml").to_yaml().replace("teeth:", "teeht:", 1)
    with pytest.raises(cycloid.SpecError) as caught:
        cycloid.Spec.from_yaml(bad)
    e = caught.value
    assert e.file == "<string>" and e.kind == "syntax"
    assert bad.splitlines()[e.line - 1][e.column - 1 :].startswith("teeht")
    assert "did you mean" in str(e)


def test_arrays_are_numpy_of_the_documented_shapes_and_outlive_the_run():
    spec = cycloid.load("specs/reducer-loaded.yaml")
    run = cycloid.check(spec)
    name = spec.scene_names[0]
    scene = run.scenes[name]
    rollers = spec.to_dict()["reducer"]["rollers"]
    angles = scene["crank_deg"].shape[0]
    assert scene["crank_deg"].dtype == np.float64 and scene["crank_deg"].ndim == 1
    assert scene["clearance_mm"].shape == (rollers, angles)
    assert scene["roller_force_n"].shape == (rollers, angles)
    assert scene["roller_force_n"].dtype == np.float64
    assert scene["te_arcsec"].shape == (angles,)
    assert scene["contacts"].dtype == np.int64 and scene["contacts"].shape == (angles,)
    assert isinstance(scene["min_clearance_mm"], float)
    kept = {k: v for k, v in scene.items() if isinstance(v, np.ndarray)}
    copies = {k: v.copy() for k, v in kept.items()}
    del run, scene
    gc.collect()
    # Other runs reuse the freed memory; arrays that pointed into it would change.
    for _ in range(3):
        cycloid.check(spec.replace(**{"modification.shift_mm": -0.02}))
    for k, v in kept.items():
        assert v.flags.owndata or v.base is not None
        assert np.array_equal(v, copies[k]), k
        v[...] = 0  # writable, owned by Python


def test_four_threads_give_the_sequential_results():
    specs = [
        cycloid.load(s)
        for s in ("specs/reducer-loaded.yaml", "specs/reducer-two-discs.yaml", "specs/reducer-torsion.yaml")
    ] + [cycloid.load("specs/reducer-loaded.yaml").replace(**{"modification.shift_mm": -0.003})]
    sequential = [cycloid.check(s).to_json() for s in specs]
    with ThreadPoolExecutor(4) as pool:
        parallel = list(pool.map(lambda s: cycloid.check(s).to_json(), specs))
    assert parallel == sequential


def test_the_gil_is_released_while_computing():
    """A Python thread keeps running while the engine computes.

    The check is made long enough by construction, not by the machine's speed: its crank steps
    are doubled until it lasts 0.4 s (or reaches the spec's bound of 10 rollers x 10^6 steps),
    and the pauses of the counter are judged against the length of that call. The call is the
    binding's computation alone (`_cycloid.check`), not `CheckRun`'s conversion of the results
    into Python objects after it, which needs the GIL and grows with the results as the
    computation does (164 ms of a 649 ms call in one CI run, more than the quarter allowed)."""
    base = cycloid.load("specs/reducer-loaded.yaml")
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    try:
        steps = 4000
        while True:
            spec = base.replace(**{"scenes[0].crank.steps": steps})
            start = time.perf_counter()
            cycloid._cycloid.check(cycloid._spec(spec), False, None)
            end = time.perf_counter()
            if end - start >= 0.4 or steps * 2 > 1_000_000:
                break
            steps *= 2
    finally:
        stop.set()
        t.join()
    during = [x for x in ticks if start < x < end]
    # Without the GIL released the counter would stand still for the whole call: one pause as
    # long as the call. A quarter of it leaves room for a loaded machine's scheduling.
    assert len(during) >= 10 and max(np.diff([start, *during, end])) < (end - start) / 4


def test_a_progress_exception_is_raised_after_the_run():
    def boom(fraction, phase):
        raise KeyError("from the callable")

    spec = cycloid.load("specs/reducer-loaded.yaml").replace(**{"scenes[0].crank.steps": 4000})
    with pytest.raises(KeyError):
        cycloid.check(spec, progress=boom)


def test_profile_equals_the_cli_csv(cli, tmp_path):
    out = tmp_path / "profile.csv"
    assert run_cli(cli, "profile", "specs/reducer.yaml", "--csv", str(out), "--tolerance-um", "0.5").returncode == 0
    rows = [l for l in out.read_text().splitlines() if not l.startswith("#")]
    header, table = rows[0].split(","), np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    got = cycloid.profile("specs/reducer.yaml", tolerance_um=0.5)
    for i, name in enumerate(header):
        assert got[name].shape == (len(table),)
        assert np.allclose(got[name], table[:, i], rtol=0, atol=1e-8), name
    pins = cycloid.load("specs/reducer.yaml").to_dict()["reducer"]["output_pins"]
    r = np.hypot(got["holes_x_mm"], got["holes_y_mm"])
    assert len(r) == pins["count"] and np.allclose(r, pins["circle_radius_mm"])


def test_tolerance_samples_equal_the_cli_csv(cli, tmp_path):
    out = tmp_path / "samples.csv"
    done = run_cli(cli, "tolerance", "specs/reducer-tolerance.yaml", "--samples", "40", "--samples-csv", str(out))
    assert done.returncode in (0, 1), done.stderr
    lines = out.read_text().splitlines()
    header = lines[0].split(",")
    table = [[float(x) for x in l.split(",")] for l in lines[1:]]
    got = cycloid.tolerance("specs/reducer-tolerance.yaml", samples=40)
    assert list(got.samples) == header
    assert got.samples["sample"].dtype == np.int64
    for i, name in enumerate(header):
        assert np.array_equal(got.samples[name], [row[i] for row in table]), name
    other = cycloid.tolerance("specs/reducer-tolerance.yaml", samples=40, seed=7)
    assert not np.array_equal(other.samples[header[1]], got.samples[header[1]])


def test_tolerance_samples_hold_the_json_worst_samples(cli, tmp_path):
    """Each worst sample of `tolerance --json`, read by Python's own JSON reader, is the same
    row of the Python arrays: every part's deviation and every limit's value, bit for bit."""
    out = tmp_path / "report.json"
    done = run_cli(cli, "tolerance", "specs/reducer-tolerance.yaml", "--samples", "40", "--json", str(out))
    assert done.returncode in (0, 1), done.stderr
    report = json.loads(out.read_text())
    got = cycloid.tolerance("specs/reducer-tolerance.yaml", samples=40)
    assert report["worst"]
    for w in report["worst"]:
        k = w["sample"]
        assert got.samples["sample"][k] == k
        for name, value in {**w["deviations_mm"], **w["values"]}.items():
            assert got.samples[name].dtype == np.float64 and got.samples[name].shape == (40,)
            assert got.samples[name][k] == value, (name, k)


def test_optimise_equals_the_check_studies(paper):
    """One study of the paper's, alone, finds what `check` found for it."""
    first = paper["run"].studies[0]
    studies = cycloid.optimise("specs/paper.yaml", study=first["name"])
    assert studies == [first]
    assert first["feasible"] and set(first["variables"]) == {"shift_mm", "equidistant_mm"}
    with pytest.raises(cycloid.SpecError, match="no study named"):
        cycloid.optimise("specs/paper.yaml", study="nope")


def test_fit_finds_the_modification_the_points_were_drawn_with(cli, tmp_path):
    """Points of a disc ground with (shift, equidistant) = (-0.01, 0.03) mm, fitted from a
    spec that says (0, 0): the fit finds the grinding, and prints what the CLI prints."""
    drawn = cycloid.load("specs/reducer.yaml").replace(
        **{"modification.shift_mm": -0.01, "modification.equidistant_mm": 0.03}
    )
    points = cycloid.profile(drawn, tolerance_um=0.05)
    rows = "\n".join(f"{x!r},{y!r}" for x, y in zip(points["x_mm"].tolist(), points["y_mm"].tolist()))
    (tmp_path / "disc.csv").write_text("x_mm,y_mm\n" + rows + "\n")
    text = cycloid.load("specs/reducer.yaml").replace(
        **{"modification.shift_mm": 0.0, "modification.equidistant_mm": 0.0}
    ).to_yaml()
    text += "measured_profile: {file: disc.csv, format: csv, fit: [shift_mm, equidistant_mm]}\n"
    spec_path = tmp_path / "measured.yaml"
    spec_path.write_text(text)
    got = cycloid.fit(str(spec_path))
    assert abs(got["shift_mm"][0] - -0.01) < 1e-5 and abs(got["equidistant_mm"][0] - 0.03) < 1e-5
    assert got["rotation_deg"] is None and got["residual_rms_mm"] < 1e-4
    assert got["form"]["t_deg"].shape == got["form"]["w_um"].shape
    done = run_cli(cli, "fit", str(spec_path))
    assert done.returncode == 0, done.stderr
    assert done.stdout == got["report"]


def test_fit_form_equals_the_cli_form_csv(cli, tmp_path):
    """The shipped measured disc: the form curve is the numbers `fit --form-csv` writes (16
    points a tooth pitch), and each estimate a (value, standard uncertainty) tuple of floats."""
    out = tmp_path / "form.csv"
    done = run_cli(cli, "fit", "specs/reducer-measured.yaml", "--form-csv", str(out))
    assert done.returncode == 0, done.stderr
    lines = out.read_text().splitlines()
    header, table = lines[0].split(","), [[float(x) for x in l.split(",")] for l in lines[1:]]
    got = cycloid.fit("specs/reducer-measured.yaml")
    assert list(got["form"]) == header == ["t_deg", "w_um"]
    for i, name in enumerate(header):
        column = got["form"][name]
        assert column.dtype == np.float64 and column.shape == (16 * 9,)
        assert np.array_equal(column, [row[i] for row in table]), name
    for key in ("centre_x_mm", "centre_y_mm", "orientation_deg", "shift_mm", "equidistant_mm"):
        value = got[key]
        assert isinstance(value, tuple) and len(value) == 2, key
        assert all(isinstance(x, float) for x in value), key
    assert got["rotation_deg"] is None
    assert done.stdout == got["report"]


def test_fit_without_measured_points_is_a_spec_error():
    with pytest.raises(cycloid.SpecError, match="measured_profile"):
        cycloid.fit("specs/reducer.yaml")


def test_a_failed_solve_is_a_computation_error_naming_scene_and_angle(cli):
    spec = "specs/hard/torque-1e5-beyond-capacity.yaml"
    with pytest.raises(cycloid.ComputationError) as caught:
        cycloid.check(spec)
    e = caught.value
    assert (e.scene, e.crank_deg, e.kind) == ("overload", 0.0, "computation")
    assert e.key == "scenes[0].output_torque_nm" and e.line == 22
    assert str(e) == run_cli(cli, "check", spec).stderr.strip()
    assert not isinstance(e, cycloid.SpecError)


def test_check_with_the_tolerance_study_equals_the_cli(cli, tmp_path):
    d = cycloid.load("specs/reducer-tolerance.yaml").to_dict()
    d["tolerances"]["samples"] = 100
    spec = cycloid.Spec.from_dict(d)
    written = tmp_path / "tolerance.yaml"
    written.write_text(spec.to_yaml())
    out = tmp_path / "tolerance.json"
    done = run_cli(cli, "check", str(written), "--tolerance", "--json", str(out))
    assert done.returncode in (0, 1), done.stderr
    run = cycloid.check(spec, tolerance=True)
    assert any(c.id.endswith("/tolerance_failure_rate") for c in run.checks)
    assert not any(c.id.endswith("/tolerance_failure_rate") for c in cycloid.check(spec).checks)
    got, expected = json.loads(run.to_json()), json.loads(out.read_text())
    assert got.pop("spec_path") == "<dict>"
    expected.pop("spec_path")
    assert got == expected


def test_line_load_is_one_3d_array_of_roller_crank_slice():
    """`line_load_n_per_mm` is `[roller][crank][slice]` in the JSON: one float64 array of
    that shape, not a list of 2-D arrays."""
    spec = cycloid.load("specs/reducer-misaligned.yaml")
    run = cycloid.check(spec)
    loaded = [s for s in run.scenes.values() if "line_load_n_per_mm" in s]
    assert loaded, "a scene that resolves the face"
    doc = json.loads(run.to_json())
    for scene in loaded:
        js = next(s for s in doc["scenes"] if s["name"] == scene["name"])["line_load_n_per_mm"]
        load = scene["line_load_n_per_mm"]
        assert isinstance(load, np.ndarray) and load.dtype == np.float64
        rollers = spec.to_dict()["reducer"]["rollers"]
        assert load.ndim == 3 and load.shape[:2] == (rollers, scene["crank_deg"].shape[0])
        assert load.shape == (len(js), len(js[0]), len(js[0][0]))
        assert np.array_equal(load, np.array(js))


def test_replace_adds_a_key_the_spec_lacks_and_validates_it():
    """`replace` adds keys the spec does not have (here a whole `reducer.friction`), and the
    edited spec is validated as the command line validates a file with that text."""
    spec = cycloid.load("specs/reducer.yaml")
    assert "friction" not in spec.to_dict()["reducer"]
    keys = {"reducer.friction.rollers.mode": "fixed", "reducer.friction.rollers.mu": 0.05}
    added = spec.replace(**keys)
    assert added.to_dict()["reducer"]["friction"] == {"rollers": {"mode": "fixed", "mu": 0.05}}
    assert cycloid.check(added).passed
    with pytest.raises(cycloid.SpecError) as caught:
        spec.replace(**dict(keys, **{"reducer.friction.rollers.mu": 1.5}))
    e = caught.value
    assert e.key == "reducer.friction.rollers.mu" and e.kind == "invalid_value"
    assert e.file == "specs/reducer.yaml"
    assert "must lie in [0, 1), got 1.5" in str(e)
    with pytest.raises(cycloid.SpecError) as caught:
        spec.replace(**{"reducer.friction.rollers.mu": 0.05})
    assert caught.value.key == "reducer.friction.rollers" and "mode" in str(caught.value)


def test_design_equals_the_cli_front(cli, tmp_path, monkeypatch):
    """`cycloid.design` finds the front `cycloid design --out` writes: the same spec files,
    text for text, and each design's figures the row of front.csv."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "small.yaml").write_text(SMALL_REQUIREMENTS)
    done = run_cli(cli, "design", "small.yaml", "--out", "front", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    front = cycloid.design("small.yaml")
    files = sorted(p.name for p in (tmp_path / "front").glob("design-*.yaml"))
    assert [d.file for d in front] == files and files
    lines = (tmp_path / "front" / "front.csv").read_text().splitlines()
    names = lines[0].split(",")[1:]
    rows = {cells[0]: [float(x) for x in cells[1:]] for cells in (l.split(",") for l in lines[1:])}
    for d in front:
        assert d.spec.to_yaml() == (tmp_path / "front" / d.file).read_text()
        assert list(d.figures) == names and list(d.figures.values()) == rows[d.file]
    with pytest.raises(cycloid.SpecError):
        cycloid.design(str(ROOT / "specs" / "reducer.yaml"))


# The small search of tests/it/design_search.rs (64 Sobol points, under a second).
SMALL_REQUIREMENTS = """\
name: small
ratio: [9]
rated_torque_nm: 10.0
peak_torque_nm: 15.0
envelope:
  max_outer_diameter_mm: 76.0
  max_axial_length_mm: 19.0
  housing_wall_mm: 5.0
  axial_allowance_mm: 10.0
material:
  youngs_modulus_gpa: 206.0
  poisson_ratio: 0.3
rules:
  max_k1: 0.8
  min_ligament_mm: 1.0
  min_roller_gap_mm: 0.5
limits:
  min_clearance_mm: 0.005
  max_contact_pressure_mpa: 1500.0
objectives: [mass_kg, max_contact_pressure_mpa]
search:
  eccentricity_mm: [1.0, 2.0]
  roller_circle_radius_mm: [24.0, 34.0]
  roller_radius_mm: [2.0, 3.5]
  face_width_mm: [5.0, 10.0]
  pin_circle_radius_mm: [12.0, 20.0]
  pin_radius_mm: [2.0, 3.5]
  shift_mm: [-0.02, 0.0]
  equidistant_mm: [0.0, 0.02]
  pin_counts: [6]
  discs: [1]
  samples: 64
  seed: 3
  refine_budget: 12
  steps_per_mesh_period: 12
"""


def test_the_docstring_names_every_unit_of_the_results():
    """Every unit suffix of a quantity the results carry is in the module docstring's list:
    each numeric key of the shipped specs' scenes ends in a listed unit or is unitless."""
    listed = set(re.findall(r"``(_[a-z0-9_]+)``", cycloid.__doc__))
    unitless = {
        "ratio", "contacts", "efficiency", "mean_efficiency", "face_load_factor",
        "max_face_load_factor", "ratio_fluctuation", "ratio_min", "ratio_max",
        "min_rollers_in_contact", "max_residual", "residual", "tooth_phase", "revolution_share",
        "time_share", "duty_mean_efficiency", "steps", "discs", "rollers", "disc", "roller",
    }
    missing = set()
    for spec in ["specs/reducer-efficiency.yaml", "specs/reducer-misaligned.yaml",
                 "specs/reducer-torsion.yaml", "specs/reducer-duty-cycle.yaml"]:
        for scene in cycloid.check(spec).scenes.values():
            for key, value in scene.items():
                numeric = isinstance(value, (float, np.ndarray)) and not isinstance(value, bool)
                if numeric and key not in unitless and not any(key.endswith(u) for u in listed):
                    missing.add(key)
    assert not missing, f"keys whose unit the docstring does not list: {sorted(missing)}"
