#!/usr/bin/env python3
"""MakeHuman's T-shirt graded to each MakeHuman body (garment: {grade: auto}), both sexes over BMI 15-32:
each drape simulated by `drape simulate graphs/scenes/makehuman_tshirt_graded.yaml` with its front view, laid
out as one SVG grid labelled with the grade worn and how the drape ended (docs/garments.md, "grade: auto").

    /usr/bin/python3 scripts/figures/makehuman_graded.py [--drape build/bin/drape] [--work DIR] --out grid.svg

Needs the CC0 MakeHuman data (../shared/assets/makehuman or $DRAPE_MAKEHUMAN_DIR). A body the garment cannot
be put on gets a cell with the reason instead of a picture.
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from svg_grid import simulated_cell, write_grid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(HERE))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--drape", default=os.path.join(ROOT, "build", "bin", "drape"))
    ap.add_argument("--work", default="makehuman-graded")
    ap.add_argument("--bmis", default="15,20,25,32")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    scene = os.path.join(ROOT, "graphs", "scenes", "makehuman_tshirt_graded.yaml")
    cells = []
    for row, sex in enumerate((0, 1)):
        for col, bmi in enumerate(float(b) for b in a.bmis.split(",")):
            label = f"{'F' if sex == 0 else 'M'}, BMI {bmi:g}"
            cells.append(simulated_cell(a.drape, scene, ["--bmi", bmi, "--sex", sex], os.path.join(a.work, f"sex{sex}_bmi{bmi:g}"),
                                        row, col, label))
            print(label, "->", cells[-1]["note"], flush=True)
    write_grid(a.out, "MakeHuman's T-shirt, grade: auto (each body's own grade), MakeHuman bodies", cells)


if __name__ == "__main__":
    main()
