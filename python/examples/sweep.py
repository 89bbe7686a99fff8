"""A notebook-style sweep: the profile shift of the loaded reducer, design by design.

    python python/examples/sweep.py [--spec specs/reducer-loaded.yaml] [--png sweep.png]

Prints one row per shift (smallest clearance, largest roller force, transmission-error
fluctuation, verdict). With matplotlib installed it also plots them into the PNG; without
it, the table alone.
"""

from __future__ import annotations

import argparse
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import cycloid


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spec", default="specs/reducer-loaded.yaml")
    parser.add_argument("--png", default="sweep.png", help="where the plot goes (needs matplotlib)")
    args = parser.parse_args()

    base = cycloid.load(args.spec)
    scene = base.scene_names[0]
    shifts_mm = np.linspace(-0.02, 0.005, 11)
    designs = [base.replace(**{"modification.shift_mm": float(s)}) for s in shifts_mm]
    # The engine releases the GIL: threads check designs in parallel.
    with ThreadPoolExecutor() as pool:
        runs = list(pool.map(cycloid.check, designs))

    rows = []
    for shift, run in zip(shifts_mm, runs):
        s = run.scenes[scene]
        te = s.get("te_arcsec")
        rows.append(
            (
                shift,
                s.get("min_clearance_mm", float("nan")),
                float(s["roller_force_n"].max()) if "roller_force_n" in s else float("nan"),
                float(te.max() - te.min()) if te is not None else float("nan"),
                "PASS" if run.passed else "FAIL",
            )
        )
    print(f"{base.name}: scene `{scene}`, modification.shift_mm swept")
    print(f"{'shift_mm':>9} {'min_clearance_mm':>17} {'max_roller_force_n':>19} {'te_fluct_arcsec':>16}  verdict")
    for shift, gap, force, te, verdict in rows:
        print(f"{shift:9.4f} {gap:17.5f} {force:19.1f} {te:16.3f}  {verdict}")

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(matplotlib not installed: no plot)")
        return
    table = np.array([r[:4] for r in rows])
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.5))
    for ax, col, label in zip(
        axes, (1, 2, 3), ("min clearance, mm", "max roller force, N", "TE fluctuation, arcsec")
    ):
        ax.plot(table[:, 0], table[:, col], "o-")
        ax.set_xlabel("shift, mm")
        ax.set_ylabel(label)
    fig.tight_layout()
    fig.savefig(args.png, dpi=100)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
