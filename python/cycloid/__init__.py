"""cycloid: design checks for cycloidal speed reducers, from Python.

The same engine as the ``cycloid`` command line (a Rust extension, ``cycloid._cycloid``)::

    import cycloid
    run = cycloid.check(cycloid.load("specs/reducer.yaml"))
    print(run.passed, run.scenes["rated"]["min_clearance_mm"])

Units are in the names, as in the spec, the results JSON and the design front: ``_mm``,
``_m2`` (square metres), ``_n`` (newtons), ``_n_per_mm`` (newtons per millimetre: a line
load along the face, a stiffness), ``_nm`` (newton metres), ``_nmm`` (newton millimetres),
``_nm_per_arcmin``, ``_arcmin_per_knm``, ``_mpa``, ``_gpa``, ``_deg``, ``_rad``, ``_mrad``,
``_arcsec``, ``_arcmin``, ``_rpm``, ``_w`` (watts), ``_j`` (joules), ``_c`` (degrees
Celsius), ``_w_per_m2k``, ``_h`` (hours), ``_kg``, ``_kg_per_m3``; a ratio, a count and an
efficiency have none.
Every computation releases the GIL, so threads run designs in parallel. Errors are
exceptions: :class:`SpecError` (located in the spec, ``str()`` as the command line prints
it) and :class:`ComputationError`.
"""

from __future__ import annotations

import json
import math
import numbers
import os
import dataclasses
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Mapping, Optional, Union

import numpy as np

from . import _cycloid
from ._errors import ComputationError, CycloidError, SpecError

__all__ = [
    "Spec",
    "Check",
    "CheckRun",
    "ToleranceRun",
    "load",
    "check",
    "optimise",
    "tolerance",
    "fit",
    "profile",
    "design",
    "Design",
    "CycloidError",
    "SpecError",
    "ComputationError",
]

__version__: str = _cycloid.__version__

Progress = Callable[[float, str], Any]
SpecLike = Union["Spec", str, "os.PathLike[str]"]


class Spec:
    """A validated spec: the reducer, its modification, scenes, limits and studies, with the
    YAML text it was read from. Immutable: :meth:`replace` returns a new spec."""

    __slots__ = ("_inner",)

    def __init__(self, inner: "_cycloid.Spec") -> None:
        self._inner = inner

    @classmethod
    def from_yaml(cls, text: str, base_dir: Optional[str] = None) -> "Spec":
        """Parse and validate spec ``text``. Files it names (goldens, measured points) are
        relative to ``base_dir`` (default: the working directory); errors name the text
        ``<string>`` (in ``base_dir``)."""
        path = "<string>" if base_dir is None else os.path.join(os.fspath(base_dir), "<string>")
        return cls(_cycloid.parse(path, text))

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], base_dir: Optional[str] = None) -> "Spec":
        """A spec from a dict of the YAML's structure (as :meth:`to_dict` gives); errors are
        located in the YAML text written from it (``<dict>``)."""
        text = _cycloid.json_to_yaml(json.dumps(data))
        path = "<dict>" if base_dir is None else os.path.join(os.fspath(base_dir), "<dict>")
        return cls(_cycloid.parse(path, text))

    def to_yaml(self) -> str:
        """The spec's YAML text, comments included."""
        return self._inner.source

    def to_dict(self) -> Dict[str, Any]:
        """The spec's YAML as plain Python objects (dicts, lists, numbers, strings)."""
        return _cycloid.yaml_to_py(self._inner.source)

    def replace(self, changes: Optional[Mapping[str, Any]] = None, /, **values: Any) -> "Spec":
        """A new, validated spec with the values at dotted keys replaced, e.g.
        ``spec.replace(**{"modification.shift_mm": -0.01, "scenes[0].crank.steps": 90})``
        (keys as in the README's spec table, in the spec's units). The YAML text is edited in
        place (comments and layout kept); a key the spec lacks is added, e.g.
        ``spec.replace(**{"reducer.friction.rollers.mode": "fixed",
        "reducer.friction.rollers.mu": 0.05})`` (under the deepest mapping of its path the
        spec has; a list item must be there already). The edited spec is validated as the
        command line validates a spec: an unknown key or a bad value raises
        :class:`SpecError` located in the edited text."""
        items = dict(changes or {}, **values)
        pairs = [(key, _yaml_scalar(key, value)) for key, value in items.items()]
        return Spec(_cycloid.with_values(self._inner, pairs))

    @property
    def name(self) -> str:
        """The spec's ``name``."""
        return self._inner.name

    @property
    def path(self) -> str:
        """The path the spec was read from (``<string>``, ``<dict>`` for text)."""
        return self._inner.path

    @property
    def scene_names(self) -> List[str]:
        """The scenes' names, in spec order."""
        return list(self._inner.scene_names)

    def __repr__(self) -> str:
        return f"Spec(name={self.name!r}, path={self.path!r})"


def _yaml_scalar(key: str, value: Any) -> str:
    """``value`` as a YAML scalar for ``key``."""
    if isinstance(value, bool) or isinstance(value, np.bool_):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        x = float(value)
        if not math.isfinite(x):
            raise ValueError(f"{key}: {x} is not a finite number")
        return repr(x)
    if isinstance(value, str):
        return json.dumps(value)
    raise TypeError(f"{key}: replace takes numbers, booleans and strings, not {type(value).__name__}")


def load(path: Union[str, "os.PathLike[str]"]) -> Spec:
    """Read and validate the spec file at ``path``; its goldens and measured points are
    relative to its folder. Raises :class:`SpecError`."""
    return Spec(_cycloid.load(os.fspath(path)))


def _spec(spec: SpecLike) -> "_cycloid.Spec":
    if isinstance(spec, Spec):
        return spec._inner
    if isinstance(spec, (str, os.PathLike)):
        return load(spec)._inner
    raise TypeError(f"expected a cycloid.Spec or a path, not {type(spec).__name__}")


@dataclass(frozen=True)
class Check:
    """One check of a run: a limit (``kind == "limit"``) or a golden curve (``"golden"``).
    ``id`` is ``scene/quantity``; ``value`` and ``limit`` are in ``unit``; ``at`` says where
    the value occurs, as the checks table does."""

    id: str
    kind: str
    value: float
    limit: float
    unit: str
    passed: bool
    at: str


class CheckRun:
    """What one :func:`check` computed: the results JSON's content as Python objects.

    - ``passed``: every check passed;
    - ``checks``: a list of :class:`Check`, in the checks table's data order;
    - ``scenes[name][quantity]``: the scene's curves as numpy arrays in the JSON's shapes and
      units (``[angle]`` or ``[roller][angle]``, float64; ``line_load_n_per_mm`` one 3-D
      array ``[roller][crank][slice]``; ``contacts`` int64) and its scalars
      (``min_clearance_mm``, ``max_roller_force_n``, ...), under the JSON's keys;
    - ``summary``, ``golden``, ``studies``: as in the JSON;
    - ``to_json()``: the text ``cycloid check --json`` writes.
    """

    def __init__(self, run: "_cycloid.Run") -> None:
        self._run = run
        doc = run.to_py()
        self.document: Dict[str, Any] = doc
        self.name: str = doc["name"]
        self.passed: bool = bool(doc["passed"])
        known = [f.name for f in dataclasses.fields(Check)]
        self.checks: List[Check] = [Check(**{k: c[k] for k in known}) for c in doc["checks"]]
        self.scenes: Dict[str, Dict[str, Any]] = {s["name"]: s for s in doc["scenes"]}
        self.summary: List[Dict[str, Any]] = doc["summary"]
        self.golden: List[Dict[str, Any]] = doc["golden"]
        self.studies: List[Dict[str, Any]] = doc["studies"]

    def to_json(self) -> str:
        """The results JSON, as ``cycloid check SPEC --json PATH`` writes it."""
        return self._run.to_json()

    @property
    def failed(self) -> List[Check]:
        """The checks that failed."""
        return [c for c in self.checks if not c.passed]

    def __repr__(self) -> str:
        verdict = "PASS" if self.passed else "FAIL"
        return f"<CheckRun {self.name!r} {verdict}: {len(self.checks)} checks>"


def _done(progress: Optional[Progress]) -> None:
    if progress is not None:
        progress(1.0, "done")


def check(spec: SpecLike, *, tolerance: bool = False, progress: Optional[Progress] = None) -> CheckRun:
    """Run ``cycloid check``: every scene, the limits, golden curves and optimisation studies
    of ``spec`` (a :class:`Spec` or a path); with ``tolerance=True`` the tolerance study's
    failure rate too. ``progress(fraction, phase)`` is called at most 4 times a second from
    the working threads, and with ``(1.0, "done")`` at the end. Raises :class:`SpecError`
    or :class:`ComputationError`."""
    run = CheckRun(_cycloid.check(_spec(spec), tolerance, progress))
    _done(progress)
    return run


def optimise(
    spec: SpecLike, study: Optional[str] = None, *, progress: Optional[Progress] = None
) -> List[Dict[str, Any]]:
    """Run the spec's optimisation studies (the one named ``study``, else all): one dict per
    study as in the results JSON's ``studies`` (``variables`` at the optimum in the spec's
    units, ``objective_value``, ``constraints``, ``feasible``, ...)."""
    studies = _cycloid.optimise(_spec(spec), study, progress)
    _done(progress)
    return list(studies)


@dataclass(frozen=True)
class ToleranceRun:
    """A tolerance study: ``samples`` holds the columns of ``--samples-csv`` by name (the
    sample index as int64, then each part's deviation in mm and each limit's value in its
    unit, float64); ``report`` the ``--json`` report as a dict."""

    samples: Dict[str, np.ndarray]
    report: Dict[str, Any]


def tolerance(
    spec: SpecLike,
    samples: Optional[int] = None,
    seed: Optional[int] = None,
    *,
    progress: Optional[Progress] = None,
) -> ToleranceRun:
    """Run the Monte Carlo of the spec's ``tolerances:`` with ``samples`` draws and ``seed``
    in place of the spec's."""
    columns, report = _cycloid.tolerance(_spec(spec), samples, seed, progress)
    _done(progress)
    return ToleranceRun(samples=columns, report=json.loads(report))


def fit(spec: SpecLike) -> Dict[str, Any]:
    """Identify the disc of the spec's ``measured_profile``: each estimate as (value,
    standard uncertainty) in the spec's units (``shift_mm``, ``equidistant_mm``,
    ``rotation_deg``, ``centre_x_mm``, ``centre_y_mm``, ``orientation_deg``; None when not
    fitted), ``modification``, ``residual_rms_mm``, ``residual_max_mm``, ``condition``,
    ``report`` (the text ``cycloid fit`` prints) and ``form`` (``t_deg``, ``w_um`` arrays)."""
    return _cycloid.fit(_spec(spec))


def profile(spec: SpecLike, tolerance_um: float = 0.5) -> Dict[str, Any]:
    """The spec's whole modified profile, every chord within ``tolerance_um`` (µm) of it: the
    columns of ``cycloid profile --csv`` as float64 arrays (``x_mm``, ``y_mm``, ``normal_x``,
    ``normal_y``, ``curvature_per_mm``), and the output-pin holes (``holes_x_mm``,
    ``holes_y_mm``, ``hole_radius_mm``)."""
    tol = float(tolerance_um)
    if not (math.isfinite(tol) and tol > 0):
        raise ValueError(f"tolerance_um must be a positive number, got {tolerance_um}")
    return _cycloid.profile(_spec(spec), tol / 1000.0)


@dataclass(frozen=True)
class Design:
    """One design of the front :func:`design` found: ``file`` is its spec's file name as
    ``cycloid design --out DIR`` writes it (``design-01.yaml``, ...), ``spec`` the spec
    (a :class:`Spec`: the full check's scenes and limits), ``figures`` its row of
    ``front.csv`` by column name (its variables, figures and objectives, units in the names;
    floats)."""

    file: str
    spec: Spec
    figures: Dict[str, float]


def design(
    requirements: Union[str, "os.PathLike[str]"], *, progress: Optional[Progress] = None
) -> List[Design]:
    """Run ``cycloid design`` on the requirements file at ``requirements``: the requirements
    search (README "Design search"), the Pareto front of the designs that meet every
    requirement, sorted by the first objective, as a list of :class:`Design` (empty when no
    design is feasible). Each spec is named after its file in the requirements' folder.
    Raises :class:`SpecError` for a bad requirements file."""
    path = os.fspath(requirements)
    specs, csv = _cycloid.design(path, progress)
    _done(progress)
    lines = [line for line in csv.splitlines() if line]
    names = lines[0].split(",")[1:]
    rows = {cells[0]: cells[1:] for cells in (line.split(",") for line in lines[1:])}
    folder = os.path.dirname(path)
    return [
        Design(
            file=file,
            spec=Spec(_cycloid.parse(os.path.join(folder, file), text)),
            figures={n: float(v) for n, v in zip(names, rows[file])},
        )
        for file, text in specs
    ]
