#!/usr/bin/env python3
"""Make a measured-points file with a KNOWN form error from `cycloid profile --csv` output.

    cycloid profile specs/reducer.yaml --csv /tmp/profile.csv
    python3 tools/make-measured.py /tmp/profile.csv specs/measured/reducer-disc.csv

What it does (MODEL.md "Measured profiles"; the design is specs/reducer.yaml's, the paper's
Table 1 with its optimum modification):
- keeps every STRIDE-th point of the exported profile (a few hundred points, as a CMM scan of
  the whole disc would give);
- finds each point's locus parameter t: the roller centre C = P + r'·n (n the outward normal,
  r' = Rrp + ΔRrp) lies on the locus C(t) = R'(cos t, sin t) − e(cos np·t, sin np·t),
  R' = Rp + ΔRp, solved by Newton from t = atan2(Cy, Cx);
- moves the point along the normal by the form error w(t) = A·cos(K·t) (w > 0: material
  missing, the point moves inward): P' = P − w(t)·n;
- places the disc on the machine: turned by TURN_DEG about its centre, then shifted by
  (DX, DY) mm (what `cycloid fit` identifies as the centre and orientation);
- writes x_mm, y_mm to 6 decimals (1 nm).

Standard library only; deterministic (no noise), so the file is the same on every run.
"""
import csv
import math
import sys

# specs/reducer.yaml
RP, E, NP, RRP = 30.0, 2.0, 10, 3.0
SHIFT, EQUIDISTANT = 0.125, 0.1593
# The planted form error and the machine placement.
K, A_MM = 2, 0.004
TURN_DEG, DX, DY = 7.0, 0.3, -0.2
STRIDE = 6


def locus_t(cx, cy):
    r = RP + SHIFT
    t = math.atan2(cy, cx)
    for _ in range(50):
        fx = r * math.cos(t) - E * math.cos(NP * t) - cx
        fy = r * math.sin(t) - E * math.sin(NP * t) - cy
        dx = -r * math.sin(t) + NP * E * math.sin(NP * t)
        dy = r * math.cos(t) - NP * E * math.cos(NP * t)
        # Newton on the component of the residual along the tangent.
        step = (fx * dx + fy * dy) / (dx * dx + dy * dy)
        t -= step
        if abs(step) < 1e-15:
            break
    return t


def main(src, dst):
    rows = [r for r in csv.reader(line for line in open(src) if not line.startswith("#"))]
    header, points = rows[0], rows[1:]
    ix, iy, inx, iny = (header.index(k) for k in ("x_mm", "y_mm", "normal_x", "normal_y"))
    c, s = math.cos(math.radians(TURN_DEG)), math.sin(math.radians(TURN_DEG))
    r_eq = RRP + EQUIDISTANT
    out = []
    for row in points[::STRIDE]:
        x, y, nx, ny = (float(row[i]) for i in (ix, iy, inx, iny))
        t = locus_t(x + r_eq * nx, y + r_eq * ny)
        w = A_MM * math.cos(K * t)
        x, y = x - w * nx, y - w * ny
        out.append((c * x - s * y + DX, s * x + c * y + DY))
    with open(dst, "w", newline="\n") as f:
        f.write(
            "# Measured points of specs/reducer.yaml's disc, made by tools/make-measured.py from\n"
            "# `cycloid profile specs/reducer.yaml --csv` (every %dth point) plus a KNOWN form error\n"
            "# w(t) = %g mm * cos(%d t) along the profile normal (t the locus parameter), the disc\n"
            "# turned %g deg and shifted (%g, %g) mm on the machine. No noise.\n"
            % (STRIDE, A_MM, K, TURN_DEG, DX, DY)
        )
        f.write("x_mm,y_mm\n")
        for x, y in out:
            f.write("%.6f,%.6f\n" % (x, y))
    print("%s: %d points" % (dst, len(out)))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
