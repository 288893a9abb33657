#!/usr/bin/env python3
"""What linear blend skinning does at the shoulder and elbow: the upper left
quarter of the parametric body (x > 3 cm, y > 1 m) in a few poses made by `drape body --pose`,
each drawn from the front and from its left side, one row per pose.

    /usr/bin/python3 scripts/figures/pose_lbs.py [--drape build/bin/drape] --out docs/figures/pose-lbs.png

Uses shaded_views.py's rasteriser (numpy and zlib only).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "reference"))
from obj_file import read_obj  # noqa: E402
from shaded_views import VIEWS, draw_text, rasterise, write_png  # noqa: E402

POSES = [  # label, drape body arguments
    ("A-POSE, BMI 30", "--bmi 30"),
    ("SHOULDER ABDUCTION 90, BMI 30", "--bmi 30 --pose left_shoulder_abduction=90"),
    ("SHOULDER ROTATION -90, BMI 30", "--bmi 30 --pose left_shoulder_rotation=-90"),
    ("ELBOW 80 (ITS LIMIT IS 82), BMI 30", "--bmi 30 --pose left_elbow_flexion=80"),
    ("ELBOW 100 (LIMIT 101), BMI 10", "--bmi 10 --pose left_elbow_flexion=100"),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--drape", default="build/bin/drape")
    ap.add_argument("--size", type=int, default=360)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    tmp = tempfile.mkdtemp()
    views = ["front", "left"]
    top = 26
    canvas = np.full(((args.size + top) * len(POSES), args.size * len(views), 3), 255.0)
    light = np.array([-0.35, 0.55, 0.75])
    for row, (label, body) in enumerate(POSES):
        path = os.path.join(tmp, f"{row}.obj")
        subprocess.run([args.drape, "body", *body.split(), "--out", path], check=True, capture_output=True)
        x, f = read_obj(path)
        c = x[f].mean(axis=1)
        keep = (c[:, 0] > 0.03) & (c[:, 1] > 1.0)
        f = f[keep]
        box = x[np.unique(f)]
        lo, hi = box.min(0), box.max(0)
        origin = 0.5 * (lo + hi)
        scale = args.size / (max(hi - lo) * 1.04)
        for i, name in enumerate(views):
            view = VIEWS[name]
            img = np.full((args.size, args.size, 3), 255.0)
            depth = np.full((args.size, args.size), -np.inf)
            lt = light[0] * view[0] + light[1] * view[1] + light[2] * view[2]
            rasterise(img, depth, x, f, np.tile([235.0, 200.0, 175.0], (len(f), 1)), view, scale, origin,
                      lt / np.linalg.norm(lt))
            y0 = row * (args.size + top) + top
            canvas[y0:y0 + args.size, i * args.size:(i + 1) * args.size] = img
        draw_text(canvas, label + " (FRONT, LEFT SIDE)", 6, row * (args.size + top) + 6)
    write_png(args.out, canvas)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
