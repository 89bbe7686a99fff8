#!/usr/bin/env python3
"""Independent review of the paper goldens: a second implementation, in numpy, by brute force.

It shares no code with cycloid. From the paper's design (Table 1) and MODEL.md only:
- the profile is sampled densely (closed form of MODEL.md "Profile");
- a roller's gap is the distance from its centre (in the disc frame) to the nearest segment of
  that polyline, signed by the outward normal, minus Rrp;
- at each crank angle the disc lag beta solves sum F_i * l_i = T by bisection, with the paper's
  law F = (pi/4) E* B max(0, -gap) and l_i = p_i x n_i;
- the output lag beta_o solves the same for the pins (exact pin-in-hole gap, zero clearance);
- the bearing force is minus the sum of the roller and pin force vectors.
It then compares TE, roller, pin and bearing forces and the clearance with the golden CSVs and
prints the largest differences. Run from the repository root:  python3 tools/review_goldens.py
[CASE ...] (default: every case in CASES). Needs numpy only. About a minute per case.
"""
import csv
import math
import sys

import numpy as np

E, NU, B = 206000.0, 0.3, 8.0
NC, NP, ECC, RP, RRP = 9, 10, 2.0, 30.0, 3.0
M, RW = 6, 18.0
T = 10000.0  # N*mm on the disc
K = math.pi / 4 * (1.0 / (2 * (1 - NU * NU) / E)) * B
ARCSEC = math.pi / (180 * 3600)
CASES = {
    "paper": (0.125, 0.1593),
    "paper-positive-start": (0.135, 0.150),
    "paper-negative-start": (-0.15, -0.135),
    # The optima found by cycloid's optimiser (specs/paper-*-optimum.yaml), full precision.
    "paper-negative-optimum": (-0.020129994269645513, 0.0),
    "paper-positive-optimum": (0.05514788220176706, 0.07014788220176706),
}


def profile(t, drp, drrp):
    r, rr = RP + drp, RRP + drrp
    c = np.stack([r * np.cos(t) - ECC * np.cos(NP * t), r * np.sin(t) - ECC * np.sin(NP * t)], -1)
    d = np.stack(
        [-r * np.sin(t) + ECC * NP * np.sin(NP * t), r * np.cos(t) - ECC * NP * np.cos(NP * t)], -1
    )
    n = np.stack([d[..., 1], -d[..., 0]], -1) / np.linalg.norm(d, axis=-1)[..., None]
    return c - rr * n


def nearest_on(p, poly):
    """Nearest point of a polyline to p: (index of the segment, foot, distance)."""
    a, b = poly[:-1], poly[1:]
    ab = b - a
    w = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.einsum("ij,ij->i", ab, ab), 0, 1)
    q = a + w[:, None] * ab
    dist = np.linalg.norm(p - q, axis=1)
    k = int(np.argmin(dist))
    return k, q[k], ab[k]


def gap_and_normal(p, window):
    """Signed gap of a roller centred at p (disc frame) to the profile, and the outward normal.

    Two levels of brute force: a polyline over the window finds the nearest segment, then a
    polyline 2000 times finer around it gives the foot (chord sag below 1e-12 mm)."""
    t, drp, drrp = window
    k, _, _ = nearest_on(p, profile(t, drp, drrp))
    lo, hi = t[max(k - 2, 0)], t[min(k + 3, len(t) - 1)]
    fine = np.linspace(lo, hi, 10001)
    _, q, seg = nearest_on(p, profile(fine, drp, drrp))
    tangent = seg / np.linalg.norm(seg)
    normal = np.array([tangent[1], -tangent[0]])  # outward for a counter-clockwise profile
    signed = float(np.dot(p - q, normal))
    return signed - RRP, normal


def rot(v, a):
    c, s = math.cos(a), math.sin(a)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def rollers_at(phi, beta, windows):
    psi = -phi / NC + beta
    centre = ECC * np.array([math.cos(phi), math.sin(phi)])
    out = []
    for i in range(NP):
        a = 2 * math.pi * i / NP
        roller = RP * np.array([math.cos(a), math.sin(a)])
        p = rot(roller - centre, -psi)
        g, n = gap_and_normal(p, windows[i])
        arm = p[0] * n[1] - p[1] * n[0]
        out.append((g, arm, rot(n, psi)))
    return out


def solve_beta(phi, windows):
    def moment(beta):
        return sum(K * max(0.0, -g) * l for g, l, _ in rollers_at(phi, beta, windows)) - T

    lo, hi = -0.02, 0.02
    assert moment(lo) < 0 < moment(hi)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if moment(mid) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def pins_at(phi, psi, beta_o):
    centre = ECC * np.array([math.cos(phi), math.sin(phi)])
    out = []
    for j in range(M):
        g = 2 * math.pi * j / M + psi
        arm_vec = RW * np.array([math.cos(g), math.sin(g)])
        pin = RW * np.array([math.cos(g + beta_o), math.sin(g + beta_o)])
        d = pin - (centre + arm_vec)
        u = d / np.linalg.norm(d)
        gap = ECC - np.linalg.norm(d)
        force = K * max(0.0, -gap)
        out.append((force, arm_vec[0] * u[1] - arm_vec[1] * u[0], u))
    return out


def solve_beta_o(phi, psi):
    lo, hi = 0.0, 1e-3
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if sum(f * a for f, a, _ in pins_at(phi, psi, mid)) < T:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def read(case, q):
    with open(f"golden/{case}/{q}.csv") as f:
        rows = list(csv.reader(f))
    return {round(float(r[0]), 6): [float(x) for x in r[1:]] for r in rows[1:]}


def windows_for(phi, drp, drrp, samples=3000):
    """Per roller: the profile parameters around its own locus parameter 2*pi*i/np + phi/nc."""
    out = []
    for i in range(NP):
        t0 = 2 * math.pi * i / NP + phi / NC
        out.append((np.linspace(t0 - 0.3, t0 + 0.3, samples), drp, drrp))
    return out


def spec_modification(case):
    """(shift_mm, equidistant_mm) as written in specs/<case>.yaml, to catch a stale CASES entry."""
    found = {}
    with open(f"specs/{case}.yaml") as f:
        for line in f:
            key, _, value = line.split("#")[0].strip().partition(":")
            if key in ("shift_mm", "equidistant_mm") and value.strip():
                found.setdefault(key, float(value))
    return found.get("shift_mm", 0.0), found.get("equidistant_mm", 0.0)


def main():
    worst_all = {}
    only = sys.argv[1:]
    unknown = [c for c in only if c not in CASES]
    if unknown:
        sys.exit(f"unknown case(s) {unknown}; known: {list(CASES)}")
    for case, (drp, drrp) in CASES.items():
        if only and case not in only:
            continue
        assert spec_modification(case) == (drp, drrp), (case, spec_modification(case))
        gold = {q: read(case, q) for q in
                ["clearance_mm", "te_arcsec", "roller_force_n", "pin_force_n",
                 "bearing_force_n", "bearing_angle_deg"]}
        worst = {k: 0.0 for k in ["clearance_mm", "te_arcsec", "roller_force_n",
                                  "pin_force_n", "bearing_force_n", "bearing_angle_deg"]}
        # Clearance at the ideal pose, every 1.2 deg.
        for k in range(0, 360, 12):
            deg = round(0.1 * k, 6)
            phi = math.radians(deg)
            win = windows_for(phi, drp, drrp)
            for i, (g, _, _) in enumerate(rollers_at(phi, 0.0, win)):
                worst["clearance_mm"] = max(worst["clearance_mm"], abs(g - gold["clearance_mm"][deg][i]))
        # Loaded, every 2.7 deg over 108 deg.
        max_fb = 0.0
        for k in range(0, 1080, 27):
            deg = round(0.1 * k, 6)
            phi = math.radians(deg)
            win = windows_for(phi, drp, drrp)
            beta = solve_beta(phi, win)
            psi = -phi / NC + beta
            beta_o = solve_beta_o(phi, psi)
            rs = rollers_at(phi, beta, win)
            forces = [K * max(0.0, -g) for g, _, _ in rs]
            ps = pins_at(phi, psi, beta_o)
            total = sum((-f * n for f, (_, _, n) in zip(forces, rs)), np.zeros(2))
            total = total + sum((f * u for f, _, u in ps), np.zeros(2))
            fb = -total
            e = np.array([math.cos(phi), math.sin(phi)])
            eps = math.degrees(math.atan2(e[0] * fb[1] - e[1] * fb[0], float(np.dot(e, fb))))
            max_fb = max(max_fb, float(np.linalg.norm(fb)))
            te = (beta + beta_o) / ARCSEC
            worst["te_arcsec"] = max(worst["te_arcsec"], abs(te - gold["te_arcsec"][deg][0]))
            for i in range(NP):
                worst["roller_force_n"] = max(worst["roller_force_n"],
                                              abs(forces[i] - gold["roller_force_n"][deg][i]))
            for j in range(M):
                worst["pin_force_n"] = max(worst["pin_force_n"], abs(ps[j][0] - gold["pin_force_n"][deg][j]))
            worst["bearing_force_n"] = max(worst["bearing_force_n"],
                                           abs(np.linalg.norm(fb) - gold["bearing_force_n"][deg][0]))
            worst["bearing_angle_deg"] = max(worst["bearing_angle_deg"],
                                             abs(eps - gold["bearing_angle_deg"][deg][0]))
        print(f"{case}: largest |python - golden|:")
        for q, v in worst.items():
            print(f"  {q:18s} {v:.3g}")
        print(f"  (largest bearing force seen {max_fb:.1f} N)")
        worst_all[case] = worst
    # Handbook scale of the roller forces: zero modification, all half-ring rollers in contact,
    # F_max = 4 T / (K1 nc Rp).
    k1 = ECC * NP / RP
    print(f"handbook F_max = 4T/(K1 nc Rp) = {4 * T / (k1 * NC * RP):.1f} N")
    return worst_all


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
