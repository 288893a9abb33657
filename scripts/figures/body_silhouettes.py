#!/usr/bin/env python3
"""Front and side silhouettes of two body models at the same sex, height and BMI, overlaid, with their waist
girths beside a published reference: a picture of where one model puts volume that the other does not
(docs/bodies.md, "Beside MakeHuman, as a picture").

    python3 scripts/figures/body_silhouettes.py --out silhouettes.svg [--drape build/bin/drape] \\
        [--models parametric,makehuman] [--bmi 20,30,39] [--sex 0,1] [--height 1.62,1.75]

Each cell draws the first model in blue and the second in orange, both at half opacity (where they agree
the colours mix), front view (x, y) and side view (z, y), soles at one line. `--height` gives one height
per sex (women first). Bodies are made with `drape body`; a body a model cannot reach (MakeHuman stops
near BMI 33 for women and 39 for men) leaves its cell with one model. Under each cell: the tape girth of
the trunk at its narrowest between the lowest ribs and the hips (the waist, as body_proportions.py finds
it) per model. Needs only numpy and the drape program.
"""
import argparse
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "reference"))
from body_proportions import Slicer, body_model_args, hull_perimeter  # noqa: E402
from obj_file import read_obj  # noqa: E402

COLOURS = ("#1f77b4", "#ff7f0e")
SCALE = 150.0  # pixels per metre


def make_body(drape, model, sex, height, bmi, folder):
    out = pathlib.Path(folder) / f"{model.replace(':', '_')}_{sex}_{height}_{bmi}.obj"
    cmd = [drape, "body", *body_model_args(model), "--sex", sex, "--height", height, "--bmi", bmi, "--out", str(out)]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        print(f"skipped {model} sex {sex} BMI {bmi}: {run.stderr.strip().splitlines()[-1]}", file=sys.stderr)
        return None
    v, f = read_obj(out)
    # Soles at 0; x and z centred on the trunk (50-75 % of the height: no arms or hands in front there).
    v = v - [0, v[:, 1].min(), 0]
    trunk = v[(v[:, 1] > 0.5 * v[:, 1].max()) & (v[:, 1] < 0.75 * v[:, 1].max()) & (np.abs(v[:, 0]) < 0.12)]
    return v - [0.5 * (v[:, 0].min() + v[:, 0].max()), 0, trunk[:, 2].mean()], f


def waist_girth(v, f):
    """Tape girth of the narrowest trunk loop between 45 and 80 % of the crotch-armpit span (m)."""
    H = v[:, 1].max()
    s = Slicer(v, f)
    ys = np.arange(0.30, 0.90, 0.0025) * H
    cuts = [s.loops((0, 1, 0), y) for y in ys]
    trunk = lambda loops: next((l for l in loops if l[:, 0].min() < 0 < l[:, 0].max()), None)
    crotch = next(y for y, c in zip(ys, cuts) if trunk(c) is not None)
    armpit = next(y0 for y0, y, c in zip(ys, ys[1:], cuts[1:]) if y > 0.6 * H and len(c) < 3)
    band = [trunk(c) for y, c in zip(ys, cuts) if crotch + 0.45 * (armpit - crotch) <= y <= crotch + 0.8 * (armpit - crotch)]
    narrowest = min((l for l in band if l is not None), key=lambda l: np.ptp(l[:, 0]))
    return hull_perimeter(narrowest[:, [0, 2]])


def silhouette(points, f, size):
    """A boolean image [size[1], size[0]] of the projected triangles (points in pixels, y down)."""
    mask = np.zeros((size[1], size[0]), bool)
    tri = points[f]  # [F, 3, 2]
    lo = np.floor(tri.min(axis=1)).astype(int).clip(0, [size[0] - 1, size[1] - 1])
    hi = np.ceil(tri.max(axis=1)).astype(int).clip(0, [size[0] - 1, size[1] - 1])
    for t, (x0, y0), (x1, y1) in zip(tri, lo, hi):
        xs, ys = np.meshgrid(np.arange(x0, x1 + 1) + 0.5, np.arange(y0, y1 + 1) + 0.5)
        a, b, c = t
        d = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1])
        if abs(d) < 1e-12:
            continue
        l1 = ((b[1] - c[1]) * (xs - c[0]) + (c[0] - b[0]) * (ys - c[1])) / d
        l2 = ((c[1] - a[1]) * (xs - c[0]) + (a[0] - c[0]) * (ys - c[1])) / d
        inside = (l1 >= 0) & (l2 >= 0) & (l1 + l2 <= 1)
        mask[y0:y1 + 1, x0:x1 + 1] |= inside
    return mask


def png_bytes(rgb):
    """An RGB uint8 image [h, w, 3] as PNG (zlib, no filter): no imaging library needed."""
    import struct
    import zlib
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))
    chunk = lambda kind, data: struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def overlay(masks):
    """Two models' masks in their colours at half opacity over white."""
    rgb = np.full(masks[0].shape + (3,), 255.0)
    for mask, colour in zip(masks, COLOURS):
        c = np.array([int(colour[i:i + 2], 16) for i in (1, 3, 5)], float)
        rgb[mask] = 0.5 * rgb[mask] + 0.5 * c
    return rgb.astype(np.uint8)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="the figure (.svg)")
    ap.add_argument("--drape", default="build/bin/drape")
    ap.add_argument("--models", default="parametric,makehuman", help="two body models; parameters after a colon, e.g. parametric:rig=human")
    ap.add_argument("--bmi", default="20,30,39")
    ap.add_argument("--sex", default="0,1")
    ap.add_argument("--height", default="1.62,1.75", help="one height per sex, in the order of --sex")
    a = ap.parse_args()
    models, bmis, sexes, heights = a.models.split(","), a.bmi.split(","), a.sex.split(","), a.height.split(",")
    if len(heights) != len(sexes):
        ap.error("--height needs one height per --sex")
    import base64
    view_w, view_h = int(0.75 * SCALE), int(2.1 * SCALE)  # one view: 0.75 m wide, 2.1 m tall
    cell_w, cell_h = 2 * view_w + 20, view_h + 50
    parts = []
    with tempfile.TemporaryDirectory() as folder:
        for row, (sex, height) in enumerate(zip(sexes, heights)):
            for col, bmi in enumerate(bmis):
                x0, y0 = 20 + col * cell_w, 40 + row * (cell_h + 20)
                parts.append(f'<text x="{x0}" y="{y0 - 6}" font-size="13">'
                             f'{"woman" if float(sex) < 0.5 else "man"}, {height} m, BMI {bmi}</text>')
                labels, fronts, sides = [], [], []
                for k, model in enumerate(models):
                    body = make_body(a.drape, model, sex, height, bmi, folder)
                    if body is None:
                        labels.append(f"{model}: cannot reach")
                        fronts.append(np.zeros((view_h, view_w), bool)), sides.append(np.zeros((view_h, view_w), bool))
                        continue
                    v, f = body
                    to_pixels = lambda xy: np.c_[0.5 * view_w + SCALE * xy[:, 0], view_h - 2 - SCALE * xy[:, 1]]
                    fronts.append(silhouette(to_pixels(v[:, [0, 1]]), f, (view_w, view_h)))
                    sides.append(silhouette(to_pixels(np.c_[-v[:, 2], v[:, 1]]), f, (view_w, view_h)))
                    labels.append(f"{model}: waist {100 * waist_girth(v, f):.0f} cm")
                image = np.concatenate([overlay(fronts), np.full((view_h, 20, 3), 255, np.uint8), overlay(sides)], axis=1)
                data = base64.b64encode(png_bytes(image)).decode()
                parts.append(f'<image x="{x0}" y="{y0}" width="{image.shape[1]}" height="{image.shape[0]}" '
                             f'href="data:image/png;base64,{data}"/>')
                for i, text in enumerate(labels):
                    parts.append(f'<text x="{x0}" y="{y0 + view_h + 14 + 13 * i}" font-size="11" fill="{COLOURS[i]}">{text}</text>')
    width, height_px = len(bmis) * cell_w + 40, len(sexes) * (cell_h + 20) + 50
    legend = " and ".join(f'<tspan fill="{c}">{m}</tspan>' for m, c in zip(models, COLOURS))
    svg = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height_px:.0f}" font-family="sans-serif">'
           f'<rect width="100%" height="100%" fill="white"/><text x="20" y="20" font-size="14">{legend}: front and side, '
           f'overlaid at half opacity</text>' + "".join(parts) + "</svg>")
    pathlib.Path(a.out).write_text(svg)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
