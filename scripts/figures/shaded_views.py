#!/usr/bin/env python3
"""Flat-shaded pictures of a garment mesh, close enough to see its folds: each triangle lit by one light,
so a fold spread over several triangles reads as a gradient and a one-triangle crinkle as crumpled paper.

    /usr/bin/python3 scripts/figures/shaded_views.py drape.obj [--body body.obj] [--views front,back,left]
        [--widths] [--label "text"] --out views.png

Orthographic views along the body's axes (drape's bodies stand with Y up, facing +Z). --widths colours the
faces of folds narrower than two triangles red and of two to three yellow, by scripts/fold_width.py's
measure. Only numpy and zlib: a z-buffer rasteriser and a PNG writer (with a 5x7 pixel font for the label).
"""
import argparse
import os
import struct
import sys
import zlib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(HERE, "..", "reference"))
from obj_file import read_obj  # noqa: E402

VIEWS = {  # (right, up, towards the viewer)
    "front": (np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), np.array([0, 0, 1.0])),
    "back": (np.array([-1.0, 0, 0]), np.array([0, 1.0, 0]), np.array([0, 0, -1.0])),
    "left": (np.array([0, 0, -1.0]), np.array([0, 1.0, 0]), np.array([1.0, 0, 0])),
    "right": (np.array([0, 0, 1.0]), np.array([0, 1.0, 0]), np.array([-1.0, 0, 0])),
}


def rasterise(img, depth, x, faces, colours, view, scale, origin, light):
    r, u, t = view
    p = np.column_stack([(x - origin) @ r * scale, -(x - origin) @ u * scale, (x - origin) @ t])
    h, w = depth.shape
    p[:, 0] += w / 2
    p[:, 1] += h / 2
    for f, c in zip(faces, colours):
        q = p[f]
        n = np.cross(x[f[1]] - x[f[0]], x[f[2]] - x[f[0]])
        nn = np.linalg.norm(n)
        if nn == 0:
            continue
        n /= nn
        if n @ t < 0:
            n = -n                      # the inside of the cloth, lit as the outside
        shade = 0.25 + 0.75 * max(n @ light, 0.0)
        x0, x1 = int(max(np.floor(q[:, 0].min()), 0)), int(min(np.ceil(q[:, 0].max()), w - 1))
        y0, y1 = int(max(np.floor(q[:, 1].min()), 0)), int(min(np.ceil(q[:, 1].max()), h - 1))
        if x1 < x0 or y1 < y0:
            continue
        gx, gy = np.meshgrid(np.arange(x0, x1 + 1) + 0.5, np.arange(y0, y1 + 1) + 0.5)
        d = (q[1, 0] - q[0, 0]) * (q[2, 1] - q[0, 1]) - (q[2, 0] - q[0, 0]) * (q[1, 1] - q[0, 1])
        if abs(d) < 1e-12:
            continue
        l1 = ((gx - q[0, 0]) * (q[2, 1] - q[0, 1]) - (q[2, 0] - q[0, 0]) * (gy - q[0, 1])) / d
        l2 = ((q[1, 0] - q[0, 0]) * (gy - q[0, 1]) - (gx - q[0, 0]) * (q[1, 1] - q[0, 1])) / d
        l0 = 1 - l1 - l2
        inside = (l0 >= 0) & (l1 >= 0) & (l2 >= 0)
        z = l0 * q[0, 2] + l1 * q[1, 2] + l2 * q[2, 2]
        sub = depth[y0:y1 + 1, x0:x1 + 1]
        win = inside & (z > sub)
        sub[win] = z[win]
        img[y0:y1 + 1, x0:x1 + 1][win] = np.clip(np.array(c) * shade, 0, 255)


FONT = {  # 5x7, rows top to bottom, bits left to right
    " ": [0] * 7, "-": [0, 0, 0, 31, 0, 0, 0], ".": [0, 0, 0, 0, 0, 12, 12], ",": [0, 0, 0, 0, 12, 4, 8],
    ":": [0, 12, 12, 0, 12, 12, 0], "%": [24, 25, 2, 4, 8, 19, 3], "=": [0, 0, 31, 0, 31, 0, 0],
    "<": [2, 4, 8, 16, 8, 4, 2], ">": [8, 4, 2, 1, 2, 4, 8],
    "(": [2, 4, 8, 8, 8, 4, 2], ")": [8, 4, 2, 2, 2, 4, 8], "/": [1, 1, 2, 4, 8, 16, 16],
    "0": [14, 17, 19, 21, 25, 17, 14], "1": [4, 12, 4, 4, 4, 4, 14], "2": [14, 17, 1, 2, 4, 8, 31],
    "3": [31, 2, 4, 2, 1, 17, 14], "4": [2, 6, 10, 18, 31, 2, 2], "5": [31, 16, 30, 1, 1, 17, 14],
    "6": [6, 8, 16, 30, 17, 17, 14], "7": [31, 1, 2, 4, 8, 8, 8], "8": [14, 17, 17, 14, 17, 17, 14],
    "9": [14, 17, 17, 15, 1, 2, 12],
}
GLYPHS = {
    "A": [14, 17, 17, 31, 17, 17, 17], "B": [30, 17, 17, 30, 17, 17, 30], "C": [14, 17, 16, 16, 16, 17, 14],
    "D": [28, 18, 17, 17, 17, 18, 28], "E": [31, 16, 16, 30, 16, 16, 31], "F": [31, 16, 16, 30, 16, 16, 16],
    "G": [14, 17, 16, 23, 17, 17, 15], "H": [17, 17, 17, 31, 17, 17, 17], "I": [14, 4, 4, 4, 4, 4, 14],
    "J": [7, 2, 2, 2, 2, 18, 12], "K": [17, 18, 20, 24, 20, 18, 17], "L": [16, 16, 16, 16, 16, 16, 31],
    "M": [17, 27, 21, 21, 17, 17, 17], "N": [17, 17, 25, 21, 19, 17, 17], "O": [14, 17, 17, 17, 17, 17, 14],
    "P": [30, 17, 17, 30, 16, 16, 16], "Q": [14, 17, 17, 17, 21, 18, 13], "R": [30, 17, 17, 30, 20, 18, 17],
    "S": [15, 16, 16, 14, 1, 1, 30], "T": [31, 4, 4, 4, 4, 4, 4], "U": [17, 17, 17, 17, 17, 17, 14],
    "V": [17, 17, 17, 17, 17, 10, 4], "W": [17, 17, 17, 21, 21, 21, 10], "X": [17, 17, 10, 4, 10, 17, 17],
    "Y": [17, 17, 10, 4, 4, 4, 4], "Z": [31, 1, 2, 4, 8, 16, 31],
}
FONT.update(GLYPHS)


def draw_text(img, text, x, y, size=2):
    for ch in text.upper():
        rows = FONT.get(ch) or FONT[" "]
        for j, bits in enumerate(rows):
            for i in range(5):
                if bits >> (4 - i) & 1:
                    img[y + j * size:y + (j + 1) * size, x + i * size:x + (i + 1) * size] = 0
        x += 6 * size


def write_png(path, img):
    h, w, _ = img.shape
    raw = b"".join(b"\x00" + img[j].astype(np.uint8).tobytes() for j in range(h))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xffffffff)

    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                  + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("--body")
    ap.add_argument("--views", default="front,back,left")
    ap.add_argument("--widths", action="store_true", help="colour faces of folds narrower than 2 (red) / 3 (yellow) triangles")
    ap.add_argument("--label", default="")
    ap.add_argument("--size", type=int, default=420, help="pixels per view, across")
    ap.add_argument("--out", required=True, help="the picture, a PNG (.png)")
    args = ap.parse_args()
    if not args.out.lower().endswith(".png"):
        ap.error(f"--out {args.out}: the picture is written as a PNG; name it .png")
    x, f = read_obj(args.mesh)
    colours = np.tile([200.0, 205.0, 225.0], (len(f), 1))
    if args.widths:
        import fold_width
        _, _, bent, width = fold_width.summary(x, f)
        colours[bent & (width < 3)] = [250, 215, 60]
        colours[bent & (width < 2)] = [235, 40, 40]
    lo, hi = x.min(0), x.max(0)
    origin = 0.5 * (lo + hi)
    extent = max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) * 1.04
    scale = args.size / extent
    views = args.views.split(",")
    top = 26 if args.label else 0
    canvas = np.full((args.size + top, args.size * len(views), 3), 255.0)
    light = np.array([-0.35, 0.55, 0.75])
    for i, name in enumerate(views):
        view = VIEWS[name]
        img = np.full((args.size, args.size, 3), 255.0)
        depth = np.full((args.size, args.size), -np.inf)
        lt = light[0] * view[0] + light[1] * view[1] + light[2] * view[2]
        lt /= np.linalg.norm(lt)
        if args.body:
            xb, fb = read_obj(args.body)
            rasterise(img, depth, xb, fb, np.tile([235.0, 215.0, 195.0], (len(fb), 1)), view, scale, origin, lt)
        rasterise(img, depth, x, f, colours, view, scale, origin, lt)
        canvas[top:, i * args.size:(i + 1) * args.size] = img
    if args.label:
        draw_text(canvas, args.label, 6, 6)
    write_png(args.out, canvas)


if __name__ == "__main__":
    main()
