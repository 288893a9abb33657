#!/usr/bin/env python3
"""Posed drapes, poses x BMI (issue 55, item 6): each drape simulated by `drape simulate SCENE --bmi B --pose P`
(default the coarse posed scene, graphs/scenes/tshirt_coarse_posed.yaml), drawn front and side by
scripts/figures/shaded_views.py with the body, and laid out as one HTML page (and a PNG of it through headless
Chromium when --png is given). Each cell says how the drape ended: settled or not, p, garment-body crossings, the
garment's self-crossings counted by scripts/count_self_crossings.py (no code shared with the contact), Newton
iterations and seconds. A pose or body the scene refuses gets a cell with the reason.

    /usr/bin/python3 scripts/figures/posed_grid.py [--scene S] [--bmis 18,30,45] [--poses NAME=SPEC;...]
        [--drape build/bin/drape] [--work DIR] --out grid.html [--png grid.png] [--csv grid.csv]

--poses: `name=angle=deg,angle=deg;name=...`, e.g. "arms down=shoulder_abduction=15;raised=shoulder_abduction=90".
"""
import argparse
import base64
import html
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
PYTHON = sys.executable or "/usr/bin/python3"
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "reference"))
from count_self_crossings import crossings  # noqa: E402
from obj_file import read_obj  # noqa: E402
from simulate_report import parse_simulate_output  # noqa: E402

DEFAULT_POSES = ("A-pose (rest)=;"
                 "arms down 15, elbows 20=shoulder_abduction=15,elbow_flexion=20;"
                 "arms raised 90=shoulder_abduction=90;"
                 "twist 25, elbows 60=shoulder_abduction=45,elbow_flexion=60,spine_twist=25")


def parse_poses(text):
    poses = []
    for item in text.split(";"):
        if not item.strip():
            continue
        name, _, spec = item.partition("=")
        poses.append((name.strip(), spec.strip()))
    return poses


def self_crossings(obj):
    vertices, faces = read_obj(obj)
    return len(crossings(vertices, faces)[0])


def drape(a, scene, stem, bmi, spec):
    cmd = [a.drape, "simulate", scene, "--bmi", str(bmi), "--threads", "1", "--out", stem + ".obj",
           "--body-out", stem + "-body.obj"]
    if spec:
        cmd += ["--pose", spec]
    start = time.time()
    run = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - start
    text = run.stdout + run.stderr
    row = dict(exit=run.returncode, wall=wall)
    if run.returncode not in (0, 1) or not os.path.exists(stem + ".obj"):
        lines = [ln for ln in text.strip().splitlines() if ln.strip()]
        row["refused"] = lines[-1] if lines else f"exit {run.returncode}"
        return row
    row.update(parse_simulate_output(text))
    row["self_crossings"] = self_crossings(stem + ".obj")
    return row


def picture(stem, label, size, views="front,left"):
    subprocess.run([PYTHON, os.path.join(HERE, "shaded_views.py"), stem + ".obj", "--body", stem + "-body.obj",
                    "--views", views, "--size", str(size), "--label", label, "--out", stem + ".png"],
                   check=True, capture_output=True)
    with open(stem + ".png", "rb") as f:
        return base64.b64encode(f.read()).decode()


def write_page(path, title, rows, size, header_css="width:120px"):
    """One HTML page: the title over a table of the rows (`<tr>` strings), cells two views of `size` pixels wide."""
    with open(path, "w") as f:
        f.write(f"""<!doctype html><meta charset=utf-8><title>{html.escape(title)}</title>
<style>body{{font:13px sans-serif;background:#fff}} td,th{{vertical-align:top;padding:4px;text-align:left}}
th{{{header_css}}} td{{width:{2 * size}px}} td.refused{{color:#a00}}</style>
<h3>{html.escape(title)}</h3><table>{''.join(rows)}</table>""")
    print("wrote", path)


def screenshot(page, png, width, height):
    """The HTML page `page` as a PNG of width x height pixels, through headless Chromium."""
    subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu", f"--screenshot={os.path.abspath(png)}",
                    f"--window-size={int(width)},{int(height)}", "file://" + os.path.abspath(page)], capture_output=True)
    print("wrote", png)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--drape", default=os.path.join(ROOT, "build", "bin", "drape"))
    ap.add_argument("--scene", default=os.path.join(ROOT, "graphs", "scenes", "tshirt_coarse_posed.yaml"))
    ap.add_argument("--bmis", default="18,30,45")
    ap.add_argument("--poses", default=DEFAULT_POSES)
    ap.add_argument("--work", default="posed-grid")
    ap.add_argument("--size", type=int, default=260, help="pixels per view, across")
    ap.add_argument("--title", default="")
    ap.add_argument("--out", required=True, help="the HTML page")
    ap.add_argument("--png", help="also a PNG of the page (headless Chromium)")
    ap.add_argument("--csv", help="also one line per drape")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    bmis = [float(b) for b in a.bmis.split(",")]
    poses = parse_poses(a.poses)
    rows, table = [], []
    for pi, (name, spec) in enumerate(poses):
        cells = []
        for bmi in bmis:
            stem = os.path.join(a.work, f"pose{pi}_bmi{bmi:g}")
            r = drape(a, a.scene, stem, bmi, spec)
            r.update(pose=name, spec=spec, bmi=bmi)
            table.append(r)
            if "refused" in r:
                print(f"{name}, BMI {bmi:g}: refused: {r['refused']}", flush=True)
                cells.append(f"<td class=refused>BMI {bmi:g}<br>refused: {html.escape(r['refused'][:300])}</td>")
                continue
            note = (f"{'settled' if r['settled'] else 'NOT settled'}, p = {r['p']:.2f} %, {r['crossings']} crossings, "
                    f"{r['self_crossings']} self-crossings, {r['iterations']} it, {r['seconds']:.0f} s")
            print(f"{name}, BMI {bmi:g}: {note}", flush=True)
            img = picture(stem, f"BMI {bmi:g}", a.size)
            cells.append(f"<td><img src='data:image/png;base64,{img}'><br>BMI {bmi:g}: {html.escape(note)}</td>")
        rows.append(f"<tr><th>{html.escape(name)}<br><small>{html.escape(spec or 'rest')}</small></th>{''.join(cells)}</tr>")
    title = a.title or f"Posed drapes: {os.path.basename(a.scene)}, poses x BMI (front and left views)"
    write_page(a.out, title, rows, a.size)
    if a.csv:
        keys = ["pose", "spec", "bmi", "settled", "p", "crossings", "self_crossings", "iterations", "seconds", "wall", "refused"]
        with open(a.csv, "w") as f:
            f.write(",".join(keys) + "\n")
            for r in table:
                f.write(",".join('"' + str(r.get(k, "")).replace('"', "'") + '"' for k in keys) + "\n")
        print("wrote", a.csv)
    if a.png:
        width = 360 + len(bmis) * (2 * a.size + 30)
        height = 80 + len(poses) * (a.size * 1.3 + 60)
        screenshot(a.out, a.png, width, height)


if __name__ == "__main__":
    main()
