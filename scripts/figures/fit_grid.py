#!/usr/bin/env python3
"""The fit grid with MakeHuman bodies beside the parametric ones (issue 54): for each sex and BMI MakeHuman
reaches, the shipped model's predicted drape on the parametric body (`drape render`: the shirt in the size the
tailor's rule gives the body) next to a simulated drape of MakeHuman's T-shirt, graded to the MakeHuman body of
the same sex, height and BMI (`drape simulate graphs/scenes/makehuman_tshirt_graded.yaml`). The model cannot
take MakeHuman bodies (another topology), so their column is simulated; each cell's note says how it ended.

    /usr/bin/python3 scripts/figures/fit_grid.py [--drape build/bin/drape] [--work DIR] [--bmis 15,20,25,32] \\
        [--height 1.75] --out grid.svg

Needs the CC0 MakeHuman data (../shared/assets/makehuman or $DRAPE_MAKEHUMAN_DIR) for its column; without it
those cells say so.
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from svg_grid import read_cell, simulated_cell, write_grid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(HERE))


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--drape", default=os.path.join(ROOT, "build", "bin", "drape"))
    ap.add_argument("--work", default="fit-grid")
    ap.add_argument("--bmis", default="15,20,25,32")
    ap.add_argument("--height", type=float, default=1.75)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    scene = os.path.join(ROOT, "graphs", "scenes", "makehuman_tshirt_graded.yaml")
    cells = []
    bmis = [float(b) for b in a.bmis.split(",")]
    for row, sex in enumerate((0, 1)):
        name = "woman" if sex == 0 else "man"
        for k, bmi in enumerate(bmis):
            body = ["--bmi", str(bmi), "--sex", str(sex), "--height", str(a.height)]
            stem = os.path.join(a.work, f"sex{sex}_bmi{bmi:g}")
            # The parametric body: the shipped model's prediction.
            code, text = run([a.drape, "render", *body, "--out", stem + "-predicted.svg"])
            size = re.search(r"size (\w+) by the tailor's rule", text)
            if code == 0:
                inner, w, h = read_cell(stem + "-predicted.svg")
                cells.append(dict(row=k, col=2 * row, inner=inner, w=w, h=h,
                                  label=f"{name}, BMI {bmi:g}: parametric", note=f"predicted, size {size.group(1)}" if size else "predicted"))
            else:
                cells.append(dict(row=k, col=2 * row, inner="", w=None, h=None, label=f"{name}, BMI {bmi:g}: parametric",
                                  note=text.strip().splitlines()[-1][:60]))
            # The MakeHuman body: MakeHuman's T-shirt graded to it, simulated.
            cells.append(simulated_cell(a.drape, scene, body, stem + "-makehuman", k, 2 * row + 1,
                                        f"{name}, BMI {bmi:g}: MakeHuman", prefix="simulated, "))
            print(f"{name} BMI {bmi:g} done", flush=True)
    write_grid(a.out, f"the shipped model on parametric bodies beside MakeHuman's T-shirt simulated on MakeHuman bodies, "
                      f"{a.height:g} m", cells)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
