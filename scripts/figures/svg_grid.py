"""Lays out `drape render` SVG front views as the cells of one SVG grid, each
with a bold label and an optional red note under it (the figure scripts of
this folder share it)."""
import os
import pathlib
import re
import subprocess


def read_cell(path):
    """(inner markup, width, height) of one `drape render` SVG."""
    svg = pathlib.Path(path).read_text()
    w = float(re.search(r'width="([0-9.]+)"', svg).group(1))
    h = float(re.search(r'height="([0-9.]+)"', svg).group(1))
    return svg[svg.index(">") + 1:svg.rindex("</svg>")], w, h


def simulated_cell(drape, scene, body_args, stem, row, col, label, prefix=""):
    """A cell of `drape simulate SCENE BODY_ARGS --svg`'s front view (the mesh kept as stem.obj), its note the grade
    worn (a graded scene), whether it settled and p; a body the garment cannot be put on gets the reason instead of a
    picture (w and h None: write_grid gives it the others' size)."""
    run = subprocess.run([drape, "simulate", scene, *map(str, body_args), "--threads", "1", "--out", stem + ".obj",
                          "--svg", stem + ".svg"], capture_output=True, text=True)
    text = run.stdout + run.stderr
    if run.returncode == 0 and os.path.exists(stem + ".svg"):
        inner, w, h = read_cell(stem + ".svg")
        settled = "settled" if re.search(r"\bsettled after", text) and "NOT settled" not in text else "NOT settled"
        grade = re.search(r"grade auto: .*?, ([0-9.]+) worn", text)
        p = re.search(r"p = ([0-9.]+)%", text)
        note = prefix + (f"grade {grade.group(1)}, " if grade else "") + settled + (f", p = {p.group(1)} %" if p else "")
        return dict(row=row, col=col, inner=inner, w=w, h=h, label=label, note=note)
    reason = ("refused: garment through the body at the start" if "starts crossing" in text else
              (text.strip().splitlines() or [f"exit {run.returncode}"])[-1][:60])
    return dict(row=row, col=col, inner="", w=None, h=None, label=label, note=reason)


def write_grid(out, title, cells):
    """cells: dicts with row, col, inner, w, h, label and optional note; a cell without a picture (w None) gets the
    first picture's size."""
    blank = next(((c["w"], c["h"]) for c in cells if c["w"] is not None), (300.0, 400.0))
    for c in cells:
        if c["w"] is None:
            c["w"], c["h"] = blank
    width = max(c["w"] for c in cells)
    height = max(c["h"] for c in cells)
    rows = 1 + max(c["row"] for c in cells)
    cols = 1 + max(c["col"] for c in cells)
    top, label_height, pitch = 30.0, 36.0, width + 16.0
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{cols * pitch:.0f}" '
           f'height="{rows * (height + label_height) + top:.0f}" font-family="sans-serif">',
           '<rect width="100%" height="100%" fill="white"/>',
           f'<text x="12" y="22" font-size="18">{title}</text>']
    for c in cells:
        x, y = c["col"] * pitch, top + c["row"] * (height + label_height)
        svg.append(f'<text x="{x + 12:.0f}" y="{y + 14:.0f}" font-size="14" font-weight="bold">{c["label"]}</text>')
        if c.get("note"):
            svg.append(f'<text x="{x + 12:.0f}" y="{y + 30:.0f}" font-size="12" fill="#b00000">{c["note"]}</text>')
        svg.append(f'<svg x="{x:.0f}" y="{y + label_height:.0f}" width="{c["w"]}" height="{c["h"]}" '
                   f'viewBox="0 0 {c["w"]} {c["h"]}">{c["inner"]}</svg>')
    svg.append("</svg>")
    pathlib.Path(out).write_text("\n".join(svg))
