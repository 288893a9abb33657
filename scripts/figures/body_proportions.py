#!/usr/bin/env python3
"""Proportions of body meshes (Y up, feet at the bottom, facing +Z, A-pose), to
compare body models: one table row per mesh (docs/bodies.md, "Heavy bodies:
where the fat goes").

What it measures, from the mesh alone (so any two models compare):
horizontal slices are cut into closed loops; the trunk is the loop around the
body's midline, legs and arms are loops of their own. The crotch is the lowest
slice whose trunk loop crosses the midline, the armpit the last slice, going
up, before the arms join the trunk; "span" is the height between them.

  sh/H       shoulder width: twice the midline distance of the point where the
             top edge of the front silhouette, followed outwards from the neck,
             first turns steeper than 40 degrees (the arms hang at 45-50):
             the outer end of the shoulders, deltoids included
  chest/H    widest trunk loop (x extent, arms excluded) in the top 15 % of the span
  waist/H    narrowest trunk loop between 45 and 80 % of the span
  hip/H      widest trunk loop in the lowest 35 % of the span
  thighs/H   both thighs' outer width, 3 % of the height below the crotch
  hip/sh, hip/chest   the ratios of those widths
  depth/H    deepest trunk loop (z extent: belly to buttocks) below the chest band
  thighG/H, calfG/H   tape girths (convex hull perimeters) of one leg: at the
             thigh height above, and the widest loop 15-30 % of the height up
  ank/wr     narrowest leg girth 5-15 % of the height up over the wrist girth
             (the narrowest cut across the arm 8-16 % of the height from the
             fingertip)

Widths and girths are fractions of the mesh height H.

    python3 scripts/figures/body_proportions.py a.obj b.obj ...
    python3 scripts/figures/body_proportions.py --generate [--drape build/bin/drape] \\
        [--models parametric,makehuman] [--sex 0,1] [--height 1.75,1.6] [--bmi 20,30,39]

--generate makes every combination with `drape body` in a temporary folder
first; a body a model cannot reach (MakeHuman stops near BMI 33 for women and
39 for men) is reported and skipped.
"""
import argparse
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "reference"))
from obj_file import read_obj  # noqa: E402


class Slicer:
    """Cuts a closed triangle mesh by planes into loops (connected point sets)."""

    def __init__(self, v, f):
        self.v = v
        e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
        self.edges, inv = np.unique(e, axis=0, return_inverse=True)
        self.face_edges = inv.reshape(3, -1).T  # each face's three edge ids

    def loops(self, normal, offset):
        """The loops where the plane normal . x = offset cuts the mesh."""
        d = self.v @ np.asarray(normal, float) - offset
        d[d == 0] = 1e-12  # a vertex exactly on the plane counts as above it
        a, b = self.edges[:, 0], self.edges[:, 1]
        cut = np.sign(d[a]) != np.sign(d[b])
        if not cut.any():
            return []
        points = np.zeros((len(a), 3))
        t = d[a[cut]] / (d[a[cut]] - d[b[cut]])
        points[cut] = self.v[a[cut]] + t[:, None] * (self.v[b[cut]] - self.v[a[cut]])
        # A face the plane crosses has two cut edges: they belong to one loop.
        fe = self.face_edges[cut[self.face_edges].sum(axis=1) == 2]
        fe = fe[cut[fe]].reshape(-1, 2)
        label = np.arange(len(self.edges))
        while True:  # propagate the smallest label until each loop has one
            m = np.minimum(label[fe[:, 0]], label[fe[:, 1]])
            new = label.copy()
            np.minimum.at(new, fe[:, 0], m)
            np.minimum.at(new, fe[:, 1], m)
            new = new[new]
            if (new == label).all():
                break
            label = new
        ids = np.flatnonzero(cut)
        return [points[ids[label[ids] == l]] for l in np.unique(label[ids])]


def hull_perimeter(p2):
    """Perimeter of the convex hull of 2D points: what a tape measure reads."""
    p = np.unique(p2, axis=0)
    if len(p) < 3:
        return 0.0

    def half(points):
        h = []
        for q in points:
            while len(h) >= 2 and np.cross(h[-1] - h[-2], q - h[-2]) <= 0:
                h.pop()
            h.append(q)
        return h

    hull = np.array(half(p)[:-1] + half(p[::-1])[:-1])
    return float(np.linalg.norm(hull - np.roll(hull, 1, axis=0), axis=1).sum())


def shoulder_width(s, mid, neck, H):
    xs = neck + np.arange(0.0, 0.30, 0.0025) * H
    top = np.array([max((l[:, 1].max() for l in s.loops((1, 0, 0), x)), default=-H) for x in xs])
    slope = (top[:-4] - top[4:]) / (xs[4:] - xs[:-4])  # over 1 % of the height
    steep = slope > np.tan(np.radians(40))
    flat = np.argmax(~steep)  # past the neck: the shoulder line
    return 2 * (xs[2 + flat + np.argmax(steep[flat:])] - mid)


def wrist_girth(s, v, f, H):
    """The narrowest cut across the arm 8-16 % of the height from the fingertip
    (a hand is about 11 % of the height long: palm nearer, forearm further).
    The arm's direction is the main axis of the hand and forearm, the vertices
    joined to the fingertip within 20 % of the height."""
    tip = int(np.argmax(v[:, 0]))
    near = np.linalg.norm(v - v[tip], axis=1) < 0.2 * H
    keep = np.zeros(len(v), bool)
    keep[tip] = True
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    e = e[near[e[:, 0]] & near[e[:, 1]]]
    while True:  # grow along mesh edges: the hand and forearm, not a hip nearby
        grown = keep.copy()
        grown[e[keep[e[:, 0]], 1]] = True
        if (grown == keep).all():
            break
        keep = grown
    arm = v[keep]
    axis = np.linalg.svd(arm - arm.mean(axis=0), full_matrices=False)[2][0]
    axis *= np.sign(axis @ (v[tip] - arm.mean(axis=0)))  # towards the fingertip
    e1 = np.cross(axis, [0, 0, 1.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    girths = []
    for back in np.arange(0.08, 0.16, 0.0025) * H:
        c = v[tip] - back * axis
        loop = min(s.loops(axis, axis @ c), key=lambda l: np.linalg.norm(l.mean(axis=0) - c))
        girths.append(hull_perimeter(np.c_[loop @ e1, loop @ e2]))
    return min(girths)


def measure(v, f):
    v = v - [0, v[:, 1].min(), 0]
    H = v[:, 1].max()
    head = v[v[:, 1] > 0.9 * H]
    mid = 0.5 * (head[:, 0].min() + head[:, 0].max())  # the body's midline (x)
    s = Slicer(v, f)
    ys = np.arange(0.30, 0.90, 0.0025) * H
    cuts = [s.loops((0, 1, 0), y) for y in ys]

    def trunk(loops):
        return next((l for l in loops if l[:, 0].min() < mid < l[:, 0].max()), None)

    crotch = next(y for y, c in zip(ys, cuts) if trunk(c) is not None)
    armpit = next(y0 for y0, y, c in zip(ys, ys[1:], cuts[1:]) if y > 0.6 * H and len(c) < 3)
    span = armpit - crotch

    def band(lo, hi):
        return [trunk(c) for y, c in zip(ys, cuts) if crotch + lo * span <= y <= crotch + hi * span and trunk(c) is not None]

    width = lambda l: np.ptp(l[:, 0])
    chest = max(map(width, band(0.85, 1.0)))
    waist = min(map(width, band(0.45, 0.80)))
    hip = max(map(width, band(0.0, 0.35)))
    depth = max(np.ptp(l[:, 2]) for l in band(0.0, 0.85))

    def leg(y):
        """One leg's loop at height y (a loop across the midline is cut there; hands excluded)."""
        pts = [l[l[:, 0] > mid] for l in s.loops((0, 1, 0), y)]
        pts = [p for p in pts if len(p) > 2 and p[:, 0].mean() < mid + 0.6 * (v[:, 0].max() - mid)]
        return max(pts, key=len)

    leg_girth = lambda y: hull_perimeter(leg(y)[:, [0, 2]])
    y_thigh = crotch - 0.03 * H
    legs = [l for l in s.loops((0, 1, 0), y_thigh) if np.ptp(l[:, 0]) < 0.5 * np.ptp(v[:, 0])]
    thighs = max(l[:, 0].max() for l in legs) - min(l[:, 0].min() for l in legs)
    calf = max(leg_girth(y) for y in np.arange(0.15, 0.30, 0.005) * H)
    ankle = min(leg_girth(y) for y in np.arange(0.05, 0.15, 0.0025) * H)

    neck = trunk(s.loops((0, 1, 0), 0.86 * H))[:, 0].max()
    shoulder = shoulder_width(s, mid, neck, H)
    wrist = wrist_girth(s, v, f, H)
    return {"sh/H": shoulder / H, "chest/H": chest / H, "waist/H": waist / H, "hip/H": hip / H,
            "thighs/H": thighs / H, "hip/sh": hip / shoulder, "hip/chest": hip / chest, "depth/H": depth / H,
            "thighG/H": leg_girth(y_thigh) / H, "calfG/H": calf / H, "ank/wr": ankle / wrist}


def print_table(rows):
    keys = list(rows[0][1])
    print("| body | " + " | ".join(keys) + " |")
    print("|---|" + "---:|" * len(keys))
    for name, m in rows:
        print(f"| {name} | " + " | ".join(f"{m[k]:.2f}" if "/H" not in k else f"{m[k]:.3f}" for k in keys) + " |")


def body_model_args(spec):
    """`drape body` options for a model spec: a plugin name, then its parameters after a colon
    ("parametric:rig=human" is `--model parametric --param rig=human`)."""
    model, _, params = spec.partition(":")
    out = ["--model", model]
    for p in filter(None, params.split(",")):
        out += ["--param", p]
    return out


def generate(args, folder):
    for model in args.models.split(","):
        for sex in args.sex.split(","):
            for height in args.height.split(","):
                for bmi in args.bmi.split(","):
                    name = f"{model} {'FM'[int(float(sex))]} {height} m BMI {bmi}"
                    out = pathlib.Path(folder) / (name.replace(" ", "_").replace(":", "_") + ".obj")
                    cmd = [args.drape, "body", *body_model_args(model), "--sex", sex, "--height", height, "--bmi", bmi,
                           "--out", str(out)]
                    run = subprocess.run(cmd, capture_output=True, text=True)
                    if run.returncode != 0:
                        print(f"skipped {name}: {run.stderr.strip().splitlines()[-1]}", file=sys.stderr)
                        continue
                    yield name, out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("obj", nargs="*", help="body meshes (OBJ)")
    ap.add_argument("--generate", action="store_true", help="make the bodies with drape body first")
    ap.add_argument("--drape", default="build/bin/drape", help="the drape program")
    ap.add_argument("--models", default="parametric,makehuman",
                    help="body models, comma-separated; parameters after a colon, e.g. parametric:rig=human")
    ap.add_argument("--sex", default="0,1", help="sexes, comma-separated")
    ap.add_argument("--height", default="1.75,1.6", help="heights in m, comma-separated")
    ap.add_argument("--bmi", default="20,30,39", help="BMIs, comma-separated")
    args = ap.parse_args()
    if not args.generate and not args.obj:
        ap.error("give OBJ files or --generate")
    with tempfile.TemporaryDirectory() as tmp:
        bodies = list(generate(args, tmp)) if args.generate else [(pathlib.Path(p).stem, p) for p in args.obj]
        print_table([(name, measure(*read_obj(path))) for name, path in bodies])


if __name__ == "__main__":
    main()
