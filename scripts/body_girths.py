#!/usr/bin/env python3
"""Girths of a standing body mesh, measured as a tape would: the convex hull of a plane's cross-section.

    /usr/bin/python3 scripts/body_girths.py body.obj [more.obj ...] [--csv out.csv]

Any topology (drape's parametric bodies, MakeHuman's, SMPL's): the mesh stands with Y up, feet at its lowest
point, facing +Z, arms hanging out to the sides (an A-pose). Nothing from drape: numpy and an OBJ reader.

Horizontal planes at fractions of the height H give the trunk, head, neck and legs: a plane cuts the mesh into
loops (components of the crossed triangles, joined through the edges they share); the trunk's loop is the one
whose centre is on the midline, a leg's the one on the +x side nearest the midline. Arms are cut by planes
across their own axis (found from the loops' centres down the +x arm, twice refined), from the armpit, where
the arm's loop leaves the trunk's, towards the hand.

    head      largest trunk-side girth over 0.90-0.97 H
    neck      smallest over 0.82-0.87 H
    chest     largest over 0.68-0.735 H (the bust for a woman; the arms join the trunk's loop above)
    waist     smallest over 0.56-0.66 H
    hips      largest over 0.46-0.56 H (a loop on the midline only)
    thigh     largest leg girth over 0.38-0.46 H
    calf      largest over 0.14-0.26 H
    ankle     smallest over 0.04-0.10 H
    upper_arm largest over the first 0.09 H of the arm below the armpit
    wrist     smallest over 0.15-0.27 H below the armpit (the forearm's end, before the hand widens)
"""
import argparse
import csv
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "reference"))
from obj_file import read_obj  # noqa: E402


def cross_section_loops(v, f, origin, normal):
    """The loops in which the plane through origin with the given normal cuts the mesh: a list of point arrays."""
    d = (v - origin) @ normal
    d = np.where(np.abs(d) < 1e-12, 1e-12, d)  # no vertex exactly on the plane
    s = d[f] > 0
    crossed = np.where(s.any(axis=1) & ~s.all(axis=1))[0]
    if len(crossed) == 0:
        return []
    edge_id, points, links = {}, [], []
    for t in crossed:
        ends = []
        for a, b in ((0, 1), (1, 2), (2, 0)):
            i, j = f[t, a], f[t, b]
            if (d[i] > 0) != (d[j] > 0):
                key = (min(i, j), max(i, j))
                if key not in edge_id:
                    w = d[i] / (d[i] - d[j])
                    edge_id[key] = len(points)
                    points.append(v[i] + w * (v[j] - v[i]))
                ends.append(edge_id[key])
        if len(ends) == 2:
            links.append(ends)
    parent = list(range(len(points)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in links:
        parent[root(a)] = root(b)
    groups = {}
    for i in range(len(points)):
        groups.setdefault(root(i), []).append(i)
    pts = np.array(points)
    return [pts[idx] for idx in groups.values() if len(idx) >= 3]


def hull_perimeter(points, normal):
    """Perimeter of the convex hull of points lying in a plane with this normal (a tape's girth)."""
    a = np.cross(normal, [1.0, 0, 0] if abs(normal[0]) < 0.9 else [0, 1.0, 0])
    a /= np.linalg.norm(a)
    b = np.cross(normal, a)
    p = sorted(set(map(tuple, np.round(np.column_stack([points @ a, points @ b]), 12))))
    if len(p) < 3:
        return 0.0

    def turn(o, x, y):
        return (x[0] - o[0]) * (y[1] - o[1]) - (x[1] - o[1]) * (y[0] - o[0])

    lower, upper = [], []
    for q in p:
        while len(lower) >= 2 and turn(lower[-2], lower[-1], q) <= 0:
            lower.pop()
        lower.append(q)
    for q in reversed(p):
        while len(upper) >= 2 and turn(upper[-2], upper[-1], q) <= 0:
            upper.pop()
        upper.append(q)
    hull = np.array(lower[:-1] + upper[:-1])
    return float(np.sum(np.linalg.norm(hull - np.roll(hull, 1, axis=0), axis=1)))


def horizontal_girths(v, f, height, lo, hi, pick, steps=40):
    """Girths of the loop `pick` chooses on horizontal planes from lo to hi (fractions of the height)."""
    up = np.array([0, 1.0, 0])
    out = []
    for h in np.linspace(lo, hi, steps):
        loops = cross_section_loops(v, f, np.array([0, h * height, 0]), up)
        loop = pick(loops, height)
        if loop is not None:
            out.append(hull_perimeter(loop, up))
    return out


def midline_loop(loops, height):
    """The widest loop centred on the midline (trunk, neck, head; not a mouth's or an eye's inside), if one is."""
    centred = [p for p in loops if abs(p[:, 0].mean()) < 0.02 * height]
    return max(centred, key=lambda p: np.ptp(p[:, 0]) + np.ptp(p[:, 2]), default=None)


def leg_loop(loops, height):
    """The loop on the +x side nearest the midline below the crotch: the left leg."""
    side = [p for p in loops if p[:, 0].mean() > 0.02 * height]
    return min(side, key=lambda p: p[:, 0].mean(), default=None)


def arm_girths(v, f, height):
    """(upper arm, wrist) of the +x arm, across its own axis."""
    axis = np.array([np.cos(np.radians(45)), -np.sin(np.radians(45)), 0])
    # Start near the shoulder joint (three quarters of the way out to the widest point at
    # the shoulders' height) and walk out along the arm.
    band = np.abs(v[:, 1] - 0.81 * height) < 0.01 * height
    shoulder = np.array([0.75 * v[band, 0].max(), 0.81 * height, 0])
    for _ in range(3):
        centres, girths, offsets = [], [], []
        for s in np.arange(0.02, 0.40, 0.005) * height:
            origin = shoulder + s * axis
            loops = cross_section_loops(v, f, origin, axis)
            # The arm's loop: apart from the trunk (a plane across the shoulder cuts the trunk
            # through the midline), the nearest such to the axis.
            near = [p for p in loops if p[:, 0].min() > 0.03 * height and np.linalg.norm(p.mean(axis=0) - origin) < 0.12 * height]
            if not near:
                continue
            if len(near) > 1 and offsets and s - offsets[0] > 0.1 * height:
                break  # the fingers: the hand begins
            loop = min(near, key=lambda p: np.linalg.norm(p.mean(axis=0) - origin))
            centres.append(loop.mean(axis=0))
            girths.append(hull_perimeter(loop, axis))
            offsets.append(s)
        centres, girths, offsets = np.array(centres), np.array(girths), np.array(offsets)
        # Refit the axis through the centres of the arm down to the wrist.
        c = centres[offsets - offsets[0] < 0.27 * height]
        mean = c.mean(axis=0)
        direction = np.linalg.svd(c - mean)[2][0]
        if direction @ axis < 0:
            direction = -direction
        axis = direction / np.linalg.norm(direction)
        shoulder = mean - ((mean - shoulder) @ axis) * axis
    rel = offsets - offsets[0]  # from the armpit: the first plane that cuts the arm alone
    upper = girths[(rel >= 0) & (rel <= 0.09 * height)]
    wrist = girths[(rel >= 0.15 * height) & (rel <= 0.27 * height)]
    return float(upper.max()), float(wrist.min())


def girths(path):
    v, f = read_obj(path)[:2]
    v = np.asarray(v, float)
    f = np.asarray(f, int)
    v[:, 1] -= v[:, 1].min()
    height = v[:, 1].max()
    out = {"height": height}
    out["head"] = max(horizontal_girths(v, f, height, 0.90, 0.97, midline_loop))
    out["neck"] = min(horizontal_girths(v, f, height, 0.82, 0.87, midline_loop))
    out["chest"] = max(horizontal_girths(v, f, height, 0.68, 0.735, midline_loop))
    out["waist"] = min(horizontal_girths(v, f, height, 0.56, 0.66, midline_loop))
    out["hips"] = max(horizontal_girths(v, f, height, 0.46, 0.56, midline_loop))
    out["thigh"] = max(horizontal_girths(v, f, height, 0.38, 0.46, leg_loop))
    out["calf"] = max(horizontal_girths(v, f, height, 0.14, 0.26, leg_loop))
    out["ankle"] = min(horizontal_girths(v, f, height, 0.04, 0.10, leg_loop))
    out["upper_arm"], out["wrist"] = arm_girths(v, f, height)
    return out


NAMES = ["height", "head", "neck", "chest", "waist", "hips", "thigh", "calf", "ankle", "upper_arm", "wrist"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--csv")
    args = ap.parse_args()
    rows = []
    print("mesh".ljust(28) + "".join(n.rjust(10) for n in NAMES) + "   (m)")
    for path in args.meshes:
        g = girths(path)
        rows.append({"mesh": path, **g})
        print(os.path.basename(path)[:27].ljust(28) + "".join(f"{g[n]:10.3f}" for n in NAMES))
    if args.csv:
        with open(args.csv, "w", newline="") as out:
            w = csv.DictWriter(out, fieldnames=["mesh"] + NAMES)
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
