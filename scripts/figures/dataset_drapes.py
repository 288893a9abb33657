#!/usr/bin/env python3
"""A dataset's own simulated drapes over sex x BMI, in one SVG: for each sex
and each target BMI, the stored drape whose body is nearest that BMI (of the
done samples), drawn by `drape render --simulated` (front view, the garment
coloured by its distance to the body, p in its caption) and labelled with
the body's sex, height and BMI. To look at what a model is trained on.

    python3 scripts/figures/dataset_drapes.py --data data.h5 [--bmi 12,25,40,60] [--drape build/bin/drape] --out drapes.svg

The dataset must hold its body vertices (expand a slim one first: drape
dataset expand). Reads the statistics with h5py.
"""
import argparse
import pathlib
import subprocess
import tempfile

import h5py
import numpy as np

from svg_grid import read_cell, write_grid

SEXES = [(0, "female"), (1, "male")]


def pick(data, bmis):
    """{(sex, bmi): sample index}: the done sample of that sex nearest each BMI."""
    with h5py.File(data, "r") as f:
        done = f["done"][:].astype(bool)
        bmi, sex, height = (f["stats/" + k][:] for k in ("bmi", "sex", "height"))
    chosen = {}
    for s, _ in SEXES:
        pool = np.flatnonzero(done & (np.round(sex) == s))
        if pool.size == 0:
            raise SystemExit(f"{data}: no done sample of sex {s}")
        for target in bmis:
            i = int(pool[np.argmin(np.abs(bmi[pool] - target))])
            chosen[(s, target)] = (i, bmi[i], height[i])
    return chosen


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", required=True, help="a dataset with body vertices")
    ap.add_argument("--bmi", default="12,25,40,60", help="target BMIs, comma-separated (the columns)")
    ap.add_argument("--drape", default="build/bin/drape", help="the drape program")
    ap.add_argument("--out", required=True, help="SVG to write")
    args = ap.parse_args()
    bmis = [float(b) for b in args.bmi.split(",")]
    cells = []
    with tempfile.TemporaryDirectory() as tmp:
        for (s, target), (i, bmi, height) in pick(args.data, bmis).items():
            path = pathlib.Path(tmp) / f"sample_{i}.svg"
            run = subprocess.run([args.drape, "render", "--data", args.data, "--sample", str(i), "--simulated",
                                  "--out", str(path)], capture_output=True, text=True)
            if run.returncode != 0:
                raise SystemExit(f"drape render failed for sample {i}:\n{run.stderr}")
            inner, w, h = read_cell(path)
            cells.append(dict(row=s, col=bmis.index(target), inner=inner, w=w, h=h,
                              label=f"{dict(SEXES)[s]}, {height:.2f} m, BMI {bmi:.1f} (sample {i})"))
    write_grid(args.out, f"simulated drapes of {pathlib.Path(args.data).name} over sex x BMI", cells)
    print(f"wrote {args.out}: {len(cells)} drapes")


if __name__ == "__main__":
    main()
