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


def numbers(js) -> bool:
    """A non-empty JSON list of numbers, or of equal-length lists of floats."""
    if not isinstance(js, list) or not js:
        return False
    scalar = lambda x: isinstance(x, (int, float)) and not isinstance(x, bool)
    if all(scalar(x) for x in js):
        return True
    return all(
        isinstance(r, list) and r and len(r) == len(js[0]) and all(isinstance(x, float) for x in r)
        for r in js
    )


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
        flat = [x for row in js for x in row] if isinstance(js[0], list) else js
        ints = all(isinstance(x, int) for x in flat)
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
    # At most one call per 0.25 s, the closing "done" apart.
    gaps = np.diff([t for t, _, _ in calls[:-1]])
    assert (gaps >= 0.24).all(), gaps


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
    and the pauses of the counter are judged against the length of that call."""
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
            cycloid.check(spec)
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
