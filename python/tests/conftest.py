"""Shared fixtures: the repository root (tests run from it), the command-line binary the
Python results are compared with, and one run of each slow spec shared across tests."""

from __future__ import annotations

import json
import os
import subprocess
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def _at_root(monkeypatch):
    """Specs name their files relative to themselves, and errors name the spec as given: run
    both the CLI and Python from the repository root with the same relative paths."""
    monkeypatch.chdir(ROOT)


@pytest.fixture(scope="session")
def cli() -> Path:
    """target/release/cycloid, built by `cargo build --release` when CI's `cargo test
    --release` has not built it yet."""
    exe = ROOT / "target" / "release" / "cycloid"
    if not exe.exists():
        subprocess.run(["cargo", "build", "--release"], cwd=ROOT, check=True)
    return exe


def run_cli(cli: Path, *args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(cli), *args], cwd=cwd, capture_output=True, text=True, env={**os.environ, "NO_COLOR": "1"}
    )


def cli_json(cli: Path, spec: str, tmp: Path) -> tuple[int, dict | None, str]:
    """(exit code, the results JSON or None, stderr) of `cycloid check SPEC --json`."""
    out = tmp / (Path(spec).stem + ".json")
    done = run_cli(cli, "check", spec, "--json", str(out))
    doc = json.loads(out.read_text()) if out.exists() else None
    return done.returncode, doc, done.stderr


@pytest.fixture(scope="session")
def paper(cli, tmp_path_factory):
    """specs/paper.yaml (its studies take seconds), checked once by the CLI and once from
    Python with a progress callable that records (time, fraction, phase)."""
    import cycloid

    os.chdir(ROOT)
    code, doc, err = cli_json(cli, "specs/paper.yaml", tmp_path_factory.mktemp("paper"))
    calls = []
    started = time.perf_counter()
    run = cycloid.check(
        cycloid.load("specs/paper.yaml"),
        progress=lambda f, phase: calls.append((time.perf_counter() - started, f, phase)),
    )
    wall_s = time.perf_counter() - started
    return {"code": code, "cli": doc, "stderr": err, "run": run, "calls": calls, "wall_s": wall_s}
