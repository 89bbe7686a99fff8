"""The Python call's time against the command line's whole process, on specs/paper.yaml (not
run in CI; the numbers go into BENCHMARKS.md).

    python python/examples/bench_paper.py [--runs 5] [--spec specs/paper.yaml]

Times, alternating, `cycloid check SPEC` as a process (target/release/cycloid: start-up,
load, check, the printed table) and `cycloid.check(cycloid.load(SPEC))` in this process
(load, check, and the numpy arrays of every scene), and prints the smallest and the median
of each and their ratio.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import time
from pathlib import Path

import cycloid

ROOT = Path(__file__).resolve().parents[2]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--spec", default="specs/paper.yaml")
    args = parser.parse_args()
    exe = ROOT / "target" / "release" / "cycloid"
    cli, py = [], []
    for _ in range(args.runs):
        start = time.perf_counter()
        subprocess.run([str(exe), "check", args.spec], cwd=ROOT, capture_output=True)
        cli.append(time.perf_counter() - start)
        start = time.perf_counter()
        run = cycloid.check(cycloid.load(str(ROOT / args.spec)))
        py.append(time.perf_counter() - start)
        assert run.scenes  # the arrays are built inside the timed call
    for name, t in (("cli process", cli), ("python call", py)):
        print(f"{name:12} min {min(t):.3f} s  median {statistics.median(t):.3f} s  ({len(t)} runs)")
    print(f"python / cli: min {min(py) / min(cli):.3f}, median {statistics.median(py) / statistics.median(cli):.3f}")


if __name__ == "__main__":
    main()
