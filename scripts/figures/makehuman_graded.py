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
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from svg_grid import read_cell, write_grid  # noqa: E402

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
    cells, blank = [], None
    for row, sex in enumerate((0, 1)):
        for col, bmi in enumerate(float(b) for b in a.bmis.split(",")):
            stem = os.path.join(a.work, f"sex{sex}_bmi{bmi:g}")
            run = subprocess.run([a.drape, "simulate", scene, "--bmi", str(bmi), "--sex", str(sex), "--threads", "1",
                                  "--out", stem + ".obj", "--svg", stem + ".svg"], capture_output=True, text=True)
            text = run.stdout + run.stderr
            grade = re.search(r"grade auto: .*?, ([0-9.]+) worn", text)
            label = f"{'F' if sex == 0 else 'M'}, BMI {bmi:g}" + (f", grade {grade.group(1)}" if grade else "")
            print(label, "->", "ok" if run.returncode == 0 else f"exit {run.returncode}", flush=True)
            if run.returncode == 0 and os.path.exists(stem + ".svg"):
                inner, w, h = read_cell(stem + ".svg")
                settled = "settled" if re.search(r"\bsettled after", text) and "NOT settled" not in text else "NOT settled"
                p = re.search(r"p = ([0-9.]+)%", text)
                note = f"{settled}, p = {p.group(1)} %" if p else settled
                cells.append(dict(row=row, col=col, inner=inner, w=w, h=h, label=label, note=note))
                blank = blank or (w, h)
            else:
                reason = "refused: " + ("garment through the body at the start" if "starts crossing" in text else
                                        text.strip().splitlines()[-1][:60])
                cells.append(dict(row=row, col=col, inner="", w=None, h=None, label=label, note=reason))
    w, h = blank or (300.0, 400.0)
    for c in cells:
        if c["w"] is None:
            c["w"], c["h"] = w, h
    write_grid(a.out, "MakeHuman's T-shirt, grade: auto (each body's own grade), MakeHuman bodies", cells)


if __name__ == "__main__":
    main()
