"""`cycloid profile --step/--stl` read back by a kernel no one here wrote: Open CASCADE (PyPI
`cadquery-ocp`) reads the STEP solid, checks it and measures it; the STL is checked by counting
its edges and by the divergence theorem. The expected volume comes from a computation written
here: the shoelace area of the profile exported at a 1 nm chordal tolerance, less the holes and
the bore (circles of known radius), times the face width."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.BRepGProp import BRepGProp
from OCP.GProp import GProp_GProps
from OCP.gp import gp_Pnt
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_SHELL, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer

from conftest import ROOT, run_cli

# specs/reducer.yaml (the paper's design: M = 6 holes of radius pin + e = 5 mm, B = 8 mm) with
# a crank bearing of 16 mm outer diameter: the bore.
HOLES, HOLE_RADIUS_MM, BORE_RADIUS_MM, FACE_WIDTH_MM = 6, 5.0, 8.0, 8.0
TOLERANCE_MM = 0.5e-3


def spec_with_bore(tmp_path: Path) -> Path:
    text = (ROOT / "specs" / "reducer.yaml").read_text()
    text = text.replace(
        "reducer:\n",
        "reducer:\n  crank_bearing: {dynamic_load_rating_n: 12000.0, outer_diameter_mm: 16.0}\n",
        1,
    )
    spec = tmp_path / "disc.yaml"
    spec.write_text(text)
    return spec


def csv_points(path: Path) -> np.ndarray:
    return np.loadtxt(path, delimiter=",", comments="#", skiprows=4, usecols=(0, 1))


def expected_volume(cli, spec: Path, tmp_path: Path) -> float:
    """(profile area − holes − bore) × B. The shoelace area of a polygon whose chords lie within
    1 nm of a curve ~190 mm long differs from the curve's by at most 1e-6 × 190 ≈ 2e-4 mm², 1e-7
    of the ~1670 mm² face: far inside the 1e-5 checked."""
    fine = tmp_path / "fine.csv"
    r = run_cli(cli, "profile", str(spec), "--csv", str(fine), "--tolerance-um", "0.001")
    assert r.returncode == 0, r.stderr
    x, y = csv_points(fine).T
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    cut = math.pi * (HOLES * HOLE_RADIUS_MM**2 + BORE_RADIUS_MM**2)
    return (area - cut) * FACE_WIDTH_MM


def test_the_step_solid_is_one_valid_solid_of_the_discs_volume(cli, tmp_path):
    spec = spec_with_bore(tmp_path)
    step, csv = tmp_path / "disc.step", tmp_path / "disc.csv"
    r = run_cli(cli, "profile", str(spec), "--step", str(step), "--csv", str(csv))
    assert r.returncode == 0, r.stderr
    assert "bore 16 mm" in r.stdout
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(step)) == IFSelect_RetDone
    reader.TransferRoots()
    shape = reader.OneShape()
    solids = TopExp_Explorer(shape, TopAbs_SOLID)
    count = 0
    while solids.More():
        count += 1
        solids.Next()
    assert count == 1
    assert BRepCheck_Analyzer(shape).IsValid()
    # Open CASCADE's adaptive integration to 1e-9 relative (its error estimate comes back
    # ~1e-15); the fixed-order default is off by 3e-3 on a face of 30 B-spline spans.
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, 1e-9)
    expected = expected_volume(cli, spec, tmp_path)
    # 1e-5 relative, the bound. Each cubic piece lies within half the 0.5 µm tolerance,
    # so over the ~190 mm profile the face could move by 5.7e-5 of its area at worst; but a
    # piece's Hermite error is ~u²(1 − u)²·h⁴ and falls 16-fold with each halving, so most
    # pieces are far inside it: the paper's disc came back 3.4e-6 smaller.
    assert abs(props.Mass() - expected) <= 1e-5 * expected
    # Every exported point at mid-plane within the tolerance of the solid's surface (its shell:
    # the distance to the solid itself is 0 inside it). 1e-7 mm: Open CASCADE's confusion.
    shell = TopExp_Explorer(shape, TopAbs_SHELL).Current()
    worst = 0.0
    for x, y in csv_points(csv):
        vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(x, y, 0.5 * FACE_WIDTH_MM)).Vertex()
        d = BRepExtrema_DistShapeShape(vertex, shell)
        assert d.IsDone()
        worst = max(worst, d.Value())
    assert worst <= TOLERANCE_MM + 1e-7, worst


def stl_triangles(path: Path) -> np.ndarray:
    rows = [line.split()[1:] for line in path.read_text().splitlines() if line.lstrip().startswith("vertex")]
    return np.array(rows, dtype=float).reshape(-1, 3, 3)


def test_the_stl_mesh_is_closed_and_of_the_discs_volume(cli, tmp_path):
    spec = spec_with_bore(tmp_path)
    stl = tmp_path / "disc.stl"
    r = run_cli(cli, "profile", str(spec), "--stl", str(stl))
    assert r.returncode == 0, r.stderr
    triangles = stl_triangles(stl)
    # Closed and consistently oriented: every directed edge once, and its reverse once.
    directed: dict[tuple, int] = {}
    for t in triangles:
        keys = [tuple(v) for v in t]
        for a, b in zip(keys, keys[1:] + keys[:1]):
            directed[(a, b)] = directed.get((a, b), 0) + 1
    assert all(n == 1 for n in directed.values())
    assert all((b, a) in directed for a, b in directed)
    # Divergence theorem: the volume is Σ v0 · (v1 × v2) / 6 over outward triangles.
    volume = np.sum(np.einsum("ij,ij->i", triangles[:, 0], np.cross(triangles[:, 1], triangles[:, 2]))) / 6
    expected = expected_volume(cli, spec, tmp_path)
    # 1e-3 relative, the bound for a mesh: the polygons, within 0.5 µm of their curves,
    # move the face by at most 0.5e-3 mm × their ~430 mm of outline, 0.2 mm² (1.3e-4 of it).
    assert abs(volume - expected) <= 1e-3 * expected


def test_several_discs_are_solids_each_where_the_reducer_puts_it(cli, tmp_path):
    """specs/reducer-two-discs.yaml: the paper's disc twice (no bore), at crank phases 0 and 180°,
    side by side. Open CASCADE finds two valid solids, each of one disc's volume, each centred
    where MODEL.md's "Several discs" puts it: (e·cos φk, e·sin φk) with e = 2 mm, and mid-face at
    z = (k + ½)·B."""
    spec = ROOT / "specs" / "reducer-two-discs.yaml"
    step = tmp_path / "discs.step"
    r = run_cli(cli, "profile", str(spec), "--step", str(step))
    assert r.returncode == 0, r.stderr
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(step)) == IFSelect_RetDone
    reader.TransferRoots()
    shape = reader.OneShape()
    assert BRepCheck_Analyzer(shape).IsValid()
    solids = []
    explorer = TopExp_Explorer(shape, TopAbs_SOLID)
    while explorer.More():
        solids.append(explorer.Current())
        explorer.Next()
    assert len(solids) == 2
    fine = tmp_path / "fine.csv"
    r = run_cli(cli, "profile", str(spec), "--csv", str(fine), "--tolerance-um", "0.001")
    assert r.returncode == 0, r.stderr
    x, y = csv_points(fine).T
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    expected = (area - math.pi * HOLES * HOLE_RADIUS_MM**2) * FACE_WIDTH_MM
    e = 2.0
    measured = []
    for solid in solids:
        props = GProp_GProps()
        BRepGProp.VolumeProperties_s(solid, props, 1e-9)
        measured.append((props.CentreOfMass(), props.Mass()))
    # Disc k by its height: the file's order is the writer's business.
    measured.sort(key=lambda m: m[0].Z())
    for k, (c, volume) in enumerate(measured):
        # 1e-5 relative, as for one disc (the same B-spline pieces).
        assert abs(volume - expected) <= 1e-5 * expected
        phase = math.pi * k
        # The disc's own centroid is its centre by symmetry (9 equal teeth, 6 equal holes); the
        # pieces within 0.5 µm of the profile can move it by far less than 1e-4 mm.
        for got, want in [(c.X(), e * math.cos(phase)), (c.Y(), e * math.sin(phase)), (c.Z(), (k + 0.5) * FACE_WIDTH_MM)]:
            assert abs(got - want) <= 1e-4, (k, got, want)
