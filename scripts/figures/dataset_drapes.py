#!/usr/bin/env python3
"""A dataset's own simulated drapes over sex x BMI, in one SVG: for each sex
and each target BMI, the stored drape whose body is nearest that BMI (of the
done samples), drawn by `drape render --simulated` (front view, the garment
coloured by its distance to the body, p in its caption) and labelled with
the body's sex, height and BMI. To look at what a model is trained on.

    python3 scripts/figures/dataset_drapes.py --data data.h5 [--bmi 12,25,40,60] [--drape build/bin/drape] --out drapes.svg
        [--beside other.h5 --names "mannequin,human rig"]

With --beside, each drape is drawn above the drape of the same body (the
same global sample index: two sets made with one seed, shard for shard)
from the other dataset, e.g. the same bodies on the mannequin and on the
human rig. The datasets must hold their body vertices (expand a slim one
first: drape dataset expand). Reads the statistics with h5py.
"""
import argparse
import pathlib
import subprocess
import tempfile

import h5py
import numpy as np

from svg_grid import read_cell, write_grid

SEXES = [(0, "female"), (1, "male")]


def pick(data, bmis, among=None):
    """{(sex, bmi): sample index}: the done sample of that sex nearest each BMI (of the samples `among`, when
    given)."""
    with h5py.File(data, "r") as f:
        done = f["done"][:].astype(bool)
        if among is not None:
            done &= np.isin(np.arange(len(done)), list(among))
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


def same_bodies(data, beside):
    """{sample index in data: sample index in beside} for the done samples of both with one global index; refuses
    two sets whose bodies of one global index differ (another seed or body space)."""
    with h5py.File(data, "r") as a, h5py.File(beside, "r") as b:
        ga, gb = a["stats/global_index"][:].astype(int), b["stats/global_index"][:].astype(int)
        da, db = a["done"][:].astype(bool), b["done"][:].astype(bool)
        where = {g: i for i, g in enumerate(gb) if db[i]}
        pairs = {i: where[g] for i, g in enumerate(ga) if da[i] and g in where}
        for i, j in pairs.items():
            for key in ("bmi", "height", "sex"):
                if abs(float(a["stats/" + key][i]) - float(b["stats/" + key][j])) > 1e-6:
                    raise SystemExit(f"{data} sample {i} and {beside} sample {j} share global index {ga[i]} but not "
                                     f"the body ({key} {a['stats/' + key][i]:.4g} against {b['stats/' + key][j]:.4g})")
    if not pairs:
        raise SystemExit(f"{data} and {beside} have no done sample of one global index")
    return pairs


def render_cell(drape, data, i, path):
    run = subprocess.run([drape, "render", "--data", data, "--sample", str(i), "--simulated", "--out", str(path)],
                         capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit(f"drape render failed for {data} sample {i}:\n{run.stderr}")
    return read_cell(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", required=True, help="a dataset with body vertices")
    ap.add_argument("--bmi", default="12,25,40,60", help="target BMIs, comma-separated (the columns)")
    ap.add_argument("--drape", default="build/bin/drape", help="the drape program")
    ap.add_argument("--out", required=True, help="SVG to write")
    ap.add_argument("--beside", help="a second dataset of the same bodies: each drape drawn above its own")
    ap.add_argument("--names", default="", help="with --beside: the two datasets' names for the labels, comma-separated")
    args = ap.parse_args()
    bmis = [float(b) for b in args.bmi.split(",")]
    names = [n.strip() for n in args.names.split(",")] if args.names else [pathlib.Path(args.data).stem,
                                                                            pathlib.Path(args.beside or "").stem]
    pairs = same_bodies(args.data, args.beside) if args.beside else None
    cells = []
    with tempfile.TemporaryDirectory() as tmp:
        chosen = pick(args.data, bmis, among=pairs)  # with --beside, only bodies both sets have
        rows_per_sex = 2 if pairs is not None else 1
        for (sex, target), (i, bmi, height) in chosen.items():
            body = f"{dict(SEXES)[sex]}, {height:.2f} m, BMI {bmi:.1f}"
            inner, w, h = render_cell(args.drape, args.data, i, pathlib.Path(tmp) / f"a_{i}.svg")
            label = f"{names[0]}: {body}" if pairs is not None else f"{body} (sample {i})"
            cells.append(dict(row=rows_per_sex * sex, col=bmis.index(target), inner=inner, w=w, h=h, label=label))
            if pairs is not None:
                j = pairs[i]
                inner, w, h = render_cell(args.drape, args.beside, j, pathlib.Path(tmp) / f"b_{j}.svg")
                cells.append(dict(row=rows_per_sex * sex + 1, col=bmis.index(target), inner=inner, w=w, h=h,
                                  label=f"{names[1]}: the same body"))
    title = f"simulated drapes of {pathlib.Path(args.data).name} over sex x BMI"
    if pairs is not None:
        title += f", each above the same body's in {pathlib.Path(args.beside).name}"
    write_grid(args.out, title, cells)
    print(f"wrote {args.out}: {len(cells)} drapes")


if __name__ == "__main__":
    main()
