#!/usr/bin/env python3
"""MakeHuman bodies posed by MakeHuman's own rig (docs/poses.md, "MakeHuman's rig"), poses x BMI: each body made
by `drape body --model makehuman --bmi B --pose P`, drawn front and side by scripts/figures/shaded_views.py, and
laid out as one HTML page (and a PNG of it through headless Chromium when --png is given). A pose the body is
refused in (it would pass through itself) gets a cell with the reason.

    /usr/bin/python3 scripts/figures/makehuman_posed.py [--bmis 20,30] [--poses NAME=SPEC;...]
        [--drape build/bin/drape] [--work DIR] --out grid.html [--png grid.png]

Needs the CC0 MakeHuman data with its rig (../shared/assets/makehuman/rigs/ or $DRAPE_MAKEHUMAN_DIR).
"""
import argparse
import base64
import html
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
PYTHON = sys.executable or "/usr/bin/python3"
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))
from posed_grid import parse_poses, screenshot, write_page  # noqa: E402

DEFAULT_POSES = ("rest (MakeHuman's own)=;"
                 "arms 30, left elbow 60=shoulder_abduction=30,left_elbow_flexion=60;"
                 "arms raised 90, elbows straight=shoulder_abduction=90,elbow_flexion=0;"
                 "reach, twist, step=left_shoulder_flexion=80,right_shoulder_abduction=60,elbow_flexion=70,"
                 "spine_twist=25,neck_twist=30,left_hip_flexion=30,left_knee_flexion=50")


def body(a, stem, bmi, spec):
    cmd = [a.drape, "body", "--model", "makehuman", "--bmi", str(bmi), "--out", stem + ".obj"]
    if spec:
        cmd += ["--pose", spec]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        lines = [ln for ln in (run.stdout + run.stderr).strip().splitlines() if ln.strip()]
        return lines[-1] if lines else f"exit {run.returncode}"
    return None


def picture(stem, label, size):
    subprocess.run([PYTHON, os.path.join(HERE, "shaded_views.py"), stem + ".obj", "--views", "front,left",
                    "--size", str(size), "--label", label, "--out", stem + ".png"], check=True, capture_output=True)
    with open(stem + ".png", "rb") as f:
        return base64.b64encode(f.read()).decode()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--drape", default=os.path.join(ROOT, "build", "bin", "drape"))
    ap.add_argument("--bmis", default="20,30")
    ap.add_argument("--poses", default=DEFAULT_POSES)
    ap.add_argument("--work", default="makehuman-posed")
    ap.add_argument("--size", type=int, default=260, help="pixels per view, across")
    ap.add_argument("--out", required=True, help="the HTML page")
    ap.add_argument("--png", help="also a PNG of the page (headless Chromium)")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    bmis = [float(b) for b in a.bmis.split(",")]
    poses = parse_poses(a.poses)
    rows = []
    for pi, (name, spec) in enumerate(poses):
        cells = []
        for bmi in bmis:
            stem = os.path.join(a.work, f"pose{pi}_bmi{bmi:g}")
            refused = body(a, stem, bmi, spec)
            print(f"{name}, BMI {bmi:g}: {'refused: ' + refused if refused else 'posed'}", flush=True)
            if refused:
                cells.append(f"<td class=refused>BMI {bmi:g}<br>refused: {html.escape(refused[:300])}</td>")
                continue
            img = picture(stem, f"BMI {bmi:g}", a.size)
            cells.append(f"<td><img src='data:image/png;base64,{img}'><br>BMI {bmi:g}</td>")
        shown = ", ".join(spec.split(",")) if spec else "rest"
        rows.append(f"<tr><th>{html.escape(name)}<br><small>{html.escape(shown)}</small></th>{''.join(cells)}</tr>")
    title = "MakeHuman bodies posed by MakeHuman's rig (plain LBS), poses x BMI (front and left views)"
    write_page(a.out, title, rows, a.size, "width:160px;max-width:160px;font-weight:normal")
    if a.png:
        width = 220 + len(bmis) * (2 * a.size + 30)
        height = 60 + len(poses) * (a.size * 1.2 + 40)
        screenshot(a.out, a.png, width, height)


if __name__ == "__main__":
    main()
