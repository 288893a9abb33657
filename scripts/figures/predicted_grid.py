#!/usr/bin/env python3
"""A model's predicted drapes over a grid of sex x height x BMI, in one SVG
(issue 21's figure): each cell is `drape render`'s front view of the
prediction, the garment coloured by its distance to the body, with p in its
title.

    python3 scripts/figures/predicted_grid.py [--model M.h5] [--drape build/bin/drape] --out grid.svg

The cells are drawn by the program itself; this script only lays them out.
"""
import argparse
import pathlib
import subprocess
import tempfile

from svg_grid import read_cell, write_grid

SEXES = [(0, "female"), (1, "male")]
HEIGHTS = [1.5, 2.0]
BMIS = [12, 25, 40, 60]


def render(drape, model, sex, height, bmi, out):
    cmd = [drape, "render", "--sex", str(sex), "--height", str(height), "--bmi", str(bmi), "--out", str(out)]
    if model:
        cmd += ["--model", model]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit(f"drape render failed for sex {sex}, height {height}, BMI {bmi}:\n{run.stderr}")
    return run.stderr.count("warning: the body is outside")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--model", default="", help="model file (default: the shipped model)")
    ap.add_argument("--drape", default="build/bin/drape", help="the drape program")
    ap.add_argument("--out", required=True, help="SVG to write")
    args = ap.parse_args()
    cells = []
    with tempfile.TemporaryDirectory() as tmp:
        for row, (sex, sex_name) in enumerate(SEXES):
            for h_index, h in enumerate(HEIGHTS):
                for col, bmi in enumerate(BMIS):
                    path = pathlib.Path(tmp) / f"cell_{sex}_{h}_{bmi}.svg"
                    outside = render(args.drape, args.model, sex, h, bmi, path)
                    inner, w, hh = read_cell(path)
                    cells.append(dict(row=2 * row + h_index, col=col, inner=inner, w=w, h=hh,
                                      label=f"{sex_name}, {h:.2f} m, BMI {bmi}",
                                      note="outside the model's training domain" if outside else ""))
    write_grid(args.out, "predicted drapes over sex x height x BMI "
               f"({pathlib.Path(args.model).name if args.model else 'the shipped model'})", cells)
    print(f"wrote {args.out}: {len(cells)} predictions")


if __name__ == "__main__":
    main()
