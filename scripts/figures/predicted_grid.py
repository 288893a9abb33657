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
import re
import subprocess
import tempfile

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
    cells, width, height = [], 0.0, 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for row, (sex, sex_name) in enumerate(SEXES):
            for h_index, h in enumerate(HEIGHTS):
                for col, bmi in enumerate(BMIS):
                    path = pathlib.Path(tmp) / f"cell_{sex}_{h}_{bmi}.svg"
                    outside = render(args.drape, args.model, sex, h, bmi, path)
                    svg = path.read_text()
                    w = float(re.search(r'width="([0-9.]+)"', svg).group(1))
                    hh = float(re.search(r'height="([0-9.]+)"', svg).group(1))
                    width, height = max(width, w), max(height, hh)
                    inner = svg[svg.index(">") + 1:svg.rindex("</svg>")]
                    label = f"{sex_name}, {h:.2f} m, BMI {bmi}"
                    cells.append((2 * row + h_index, col, inner, label, outside, w, hh))
    rows, cols = 2 * len(HEIGHTS), len(BMIS)
    title, label_height, pitch = 30.0, 36.0, width + 16.0
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{cols * pitch:.0f}" height="{rows * (height + label_height) + title:.0f}" '
           f'font-family="sans-serif">', '<rect width="100%" height="100%" fill="white"/>',
           f'<text x="12" y="22" font-size="18">predicted drapes over sex x height x BMI '
           f'({pathlib.Path(args.model).name if args.model else "the shipped model"})</text>']
    for r, c, inner, label, outside, w, hh in cells:
        x, y = c * pitch, title + r * (height + label_height)
        out.append(f'<text x="{x + 12:.0f}" y="{y + 14:.0f}" font-size="14" font-weight="bold">{label}</text>')
        if outside:
            out.append(f'<text x="{x + 12:.0f}" y="{y + 30:.0f}" font-size="12" fill="#b00000">outside the model\'s training domain</text>')
        out.append(f'<svg x="{x:.0f}" y="{y + label_height:.0f}" width="{w}" height="{hh}" viewBox="0 0 {w} {hh}">{inner}</svg>')
    out.append("</svg>")
    pathlib.Path(args.out).write_text("\n".join(out))
    print(f"wrote {args.out}: {len(cells)} predictions")


if __name__ == "__main__":
    main()
