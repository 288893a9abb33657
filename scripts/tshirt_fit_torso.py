#!/usr/bin/env python3
"""Measure the T-shirt placement's torso frame on the fit bodies of its sizes: the table kFitTorso in
plugins/garments/tshirt/placement.cpp (docs/garments.md, "Sizes").

    /usr/bin/python3 scripts/tshirt_fit_torso.py [--drape build/bin/drape] [--out-dir DIR]

The fit body of a size is the parametric body of the mean height and sex (1.75 m, 0.5) whose girth is the size's
grade times the mean body's (drape/bodies/fit_body.hpp); the BMIs below are the ones fit_body reaches for the
grades 0.9 ... 1.7 and the range's ends (10 and 65). Each body is written by `drape body` and measured here:

- the chest: the horizontal loop around the body's axis at y = 1.24-1.28 (largest |x|; the z extent's half and
  centre);
- the neck: the loop around (x 0, z -0.01) at y = 1.50-1.54 (the same three);
- the left upper arm: the centroids of its sections by the planes x = 0.30-0.60, a line through them (its angle
  below horizontal; its y and z at x = 0.292, where the frame's arm point lies), and the half-depth of its section
  at x = 0.30 (the shoulders' depth at the arm's root).

Prints each body's girth-relative measures as differences from the mean body's: the table's rows. Plain numpy
and scripts/reference/obj_file.py.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference"))
from obj_file import read_obj  # noqa: E402

# BMI of the fit bodies (1.75 m, sex 0.5): the mean first.
FIT_BMI = [24.671, 10.0, 21.10, 29.31, 34.85, 41.78, 49.25, 57.25, 65.0]
KEYS = ["half_width", "half_depth", "centre_z", "neck_half_width", "neck_half_depth", "neck_centre_z",
        "arm_angle_deg", "arm_axis_y", "arm_axis_z", "shoulder_half_depth"]


def section_loops(v, f, normal, offset):
    """The closed loops in which the plane normal . x = offset cuts the mesh, as point arrays."""
    d = v @ normal - offset
    d[np.abs(d) < 1e-12] = 1e-12
    s = np.sign(d[f])
    cut = ~((s[:, 0] == s[:, 1]) & (s[:, 1] == s[:, 2]))
    nbr, pos = {}, {}
    for tri in f[cut]:
        ends = []
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            if (d[a] > 0) != (d[b] > 0):
                key = (min(a, b), max(a, b))
                pos[key] = v[a] + d[a] / (d[a] - d[b]) * (v[b] - v[a])
                ends.append(key)
        if len(ends) == 2:
            nbr.setdefault(ends[0], []).append(ends[1])
            nbr.setdefault(ends[1], []).append(ends[0])
    seen, loops = set(), []
    for start in nbr:
        if start in seen:
            continue
        loop, prev, cur = [start], None, start
        seen.add(start)
        while True:
            nxt = [k for k in nbr[cur] if k != prev and k not in seen]
            if not nxt:
                break
            prev, cur = cur, nxt[0]
            seen.add(cur)
            loop.append(cur)
        loops.append(np.array([pos[k] for k in loop]))
    return loops


def encloses(loop2, p):
    x, y = loop2[:, 0], loop2[:, 1]
    x2, y2 = np.roll(x, -1), np.roll(y, -1)
    hit = ((y > p[1]) != (y2 > p[1])) & (p[0] < (x2 - x) * (p[1] - y) / (y2 - y + 1e-300) + x)
    return hit.sum() % 2 == 1


def horizontal_loop(v, f, y, centre):
    for loop in section_loops(v, f, np.array([0.0, 1.0, 0.0]), y):
        if encloses(loop[:, [0, 2]], centre):
            return loop
    raise RuntimeError(f"no loop around {centre} at y = {y}")


def measure(v, f):
    out = {}
    for name, heights, centre in (("", np.linspace(1.24, 1.28, 5), (0.0, 0.0)),
                                  ("neck_", np.linspace(1.50, 1.54, 5), (0.0, -0.01))):
        loops = [horizontal_loop(v, f, y, centre) for y in heights]
        widths = [np.abs(L[:, 0]).max() for L in loops]
        lo = [L[:, 2].min() for L in loops]
        hi = [L[:, 2].max() for L in loops]
        if name:  # the neck: the mean over its band
            out["neck_half_width"] = np.mean(widths)
            out["neck_centre_z"] = 0.5 * (np.mean(lo) + np.mean(hi))
            out["neck_half_depth"] = 0.5 * (np.mean(hi) - np.mean(lo))
        else:  # the chest: its extremes over its band
            out["half_width"] = max(widths)
            out["centre_z"] = 0.5 * (min(lo) + max(hi))
            out["half_depth"] = 0.5 * (max(hi) - min(lo))
    xs, centroids, depth = [], [], []
    for x in np.linspace(0.30, 0.60, 31):
        arm = [L for L in section_loops(v, f, np.array([1.0, 0.0, 0.0]), x) if L[:, 1].mean() > 0.95]
        if len(arm) != 1:
            continue
        xs.append(x)
        centroids.append(arm[0].mean(0))
        depth.append(0.5 * (arm[0][:, 2].max() - arm[0][:, 2].min()))
    c = np.array(centroids)
    slope, intercept = np.polyfit(c[:, 0], c[:, 1], 1)
    out["arm_angle_deg"] = np.degrees(np.arctan(-slope))
    out["arm_axis_y"] = intercept + slope * 0.292
    out["arm_axis_z"] = np.polyval(np.polyfit(c[:, 0], c[:, 2], 1), 0.292)
    out["shoulder_half_depth"] = depth[0] if xs[0] == 0.30 else float("nan")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--drape", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "bin", "drape"))
    ap.add_argument("--out-dir", default=None, help="keep the body OBJs here (default: a temporary folder)")
    args = ap.parse_args()
    folder = args.out_dir or tempfile.mkdtemp(prefix="fit-torso-")
    os.makedirs(folder, exist_ok=True)
    rows, base = [], None
    for bmi in FIT_BMI:
        path = os.path.join(folder, f"fit_bmi{bmi:g}.obj")
        subprocess.run([args.drape, "body", "--bmi", str(bmi), "--height", "1.75", "--sex", "0.5", "--out", path],
                       check=True, capture_output=True)
        v, f = read_obj(path)
        m = measure(v, f)
        base = base or m
        rows.append((bmi, m))
    print("BMI    " + " ".join(f"{k:>19}" for k in KEYS))
    for bmi, m in rows:
        print(f"{bmi:6.2f} " + " ".join(f"{m[k] - base[k]:+19.4f}" for k in KEYS))
    print("(the mean body's own: " + ", ".join(f"{k} {base[k]:.4f}" for k in KEYS) + ")")
    return 0


if __name__ == "__main__":
    sys.exit(main())
