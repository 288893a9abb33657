#!/usr/bin/env python3
"""How a model's predicted shirt fits over sex x height x BMI (issue 54: no crop
top on a heavy body, no box on a thin one unless that size was asked for),
measured on the meshes `drape predict` writes, by numpy code that shares
nothing with drape:

- hem: the height of the shirt's lowest point in front of the body's centre
  above the navel, in cm (negative: the front hem is below the navel, as a
  T-shirt's is). The navel is put at 0.60 of stature (the omphalion's height
  in anthropometric surveys is close to 0.6 of stature for both sexes); a
  positive figure is a crop top.
- gap: the median distance, in cm, from the shirt's vertices in the chest and
  waist band (0.60-0.72 of stature, arms excluded by |x|) to the nearest body
  vertex: how far the shirt stands off the torso (a box stands off).
- p: the share of the shirt's vertices inside the body (generalized winding
  number above 0.5, scripts/reference/winding_number.py).
- size: the size predict chose (its note), when the model takes one.

    /usr/bin/python3 scripts/fit_check.py [--model M.h5] [--drape build/bin/drape] [--csv out.csv]
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "reference"))
from obj_file import read_obj  # noqa: E402
from winding_number import winding_numbers  # noqa: E402

SEXES = [(0, "female"), (1, "male")]
HEIGHTS = [1.5, 1.75, 2.0]
BMIS = [12, 18, 25, 32, 40, 50, 60]
NAVEL = 0.60  # of stature


def predict(drape, model, sex, height, bmi, tmp, extra):
    garment, body = os.path.join(tmp, "g.obj"), os.path.join(tmp, "b.obj")
    cmd = [drape, "predict", "--sex", str(sex), "--height", str(height), "--bmi", str(bmi), "--out", garment,
           "--body-out", body] + extra
    if model:
        cmd += ["--model", model]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit(f"drape predict failed for sex {sex}, height {height}, BMI {bmi}:\n{run.stderr}")
    size = re.search(r"size (\S+) by the tailor's rule", run.stderr)
    return read_obj(garment)[0], read_obj(body), size.group(1) if size else "", run.stderr


def measure(garment, body):
    bv, bf = body
    soles, top = bv[:, 1].min(), bv[:, 1].max()
    stature = top - soles
    centre = bv.mean(axis=0)
    front = garment[:, 2] > centre[2]
    hem = garment[front, 1].min() - (soles + NAVEL * stature)
    # The torso band, without the sleeves: within the body's torso half-width at that height.
    band = (garment[:, 1] > soles + 0.60 * stature) & (garment[:, 1] < soles + 0.72 * stature)
    torso = (bv[:, 1] > soles + 0.60 * stature) & (bv[:, 1] < soles + 0.72 * stature)
    half_width = np.percentile(np.abs(bv[torso, 0] - centre[0]), 90)
    band &= np.abs(garment[:, 0] - centre[0]) < half_width
    d = np.sqrt(((garment[band, None, :] - bv[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
    inside = winding_numbers(bv, bf, garment) > 0.5
    return 100 * hem, 100 * np.median(d), 100 * inside.mean()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--model", default="", help="model file (default: the shipped model)")
    ap.add_argument("--drape", default="build/bin/drape", help="the drape program")
    ap.add_argument("--garment-size", default="", help="ask predict for this size instead of its default")
    ap.add_argument("--csv", help="also write the table")
    args = ap.parse_args()
    extra = ["--garment-size", args.garment_size] if args.garment_size else []
    rows = []
    print(f"{'sex':6} {'height':>6} {'BMI':>4} {'size':>8} {'hem-navel cm':>12} {'gap cm':>7} {'p %':>6}")
    with tempfile.TemporaryDirectory() as tmp:
        for sex, sex_name in SEXES:
            for height in HEIGHTS:
                for bmi in BMIS:
                    garment, body, size, _ = predict(args.drape, args.model, sex, height, bmi, tmp, extra)
                    hem, gap, p = measure(garment, body)
                    rows.append({"sex": sex_name, "height": height, "bmi": bmi, "size": size,
                                 "hem_above_navel_cm": round(hem, 2), "torso_gap_cm": round(gap, 2), "p_percent": round(p, 3)})
                    print(f"{sex_name:6} {height:6.2f} {bmi:4d} {size:>8} {hem:12.1f} {gap:7.2f} {p:6.2f}", flush=True)
    cropped = [r for r in rows if r["hem_above_navel_cm"] > 0]
    print(f"{len(cropped)} of {len(rows)} shirts end above the navel in front; torso gap median "
          f"{np.median([r['torso_gap_cm'] for r in rows]):.2f} cm, largest {max(r['torso_gap_cm'] for r in rows):.2f} cm; "
          f"p above 1 % on {sum(r['p_percent'] > 1 for r in rows)}")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
