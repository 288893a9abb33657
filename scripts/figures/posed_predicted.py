#!/usr/bin/env python3
"""Predicted against simulated drapes on posed bodies (issue 56, item 5): for test samples of a posed dataset
spread over BMI, the simulated drape beside each model's prediction for the same body in the same pose (front and
left views by scripts/figures/shaded_views.py, with the body), each prediction's mean vertex error (ME) against
the simulation in its caption; one HTML page, and a PNG of it through headless Chromium with --png.

    PYTHONPATH=build/python /usr/bin/python3 scripts/figures/posed_predicted.py --data posed.h5
        --model unposed=work/drape_unposed.h5 [--model world=work/drape_world.h5] [--count 4] [--split test]
        [--drape build/bin/drape] [--work DIR] --out grid.html [--png grid.png]
    ... --grid [--model NAME=model.h5 (one)]

--grid lays the split's bodies out over poses x BMI instead: a row per pose class (both arms' mean
shoulder abduction below 45, 45-75, above 75 degrees), a column per BMI band (10-20, 20-30, 30-45, 45-65); each
cell the body of that class whose BMI lies nearest its band's middle, simulated and predicted from the front.

A model is fed the body at rest (from `drape dataset unpose`, run here) and the sample's joint angles, as `drape
predict --pose` feeds it.
"""
import argparse
import html
import os
import subprocess
import sys

import numpy as np
import yaml

import drape

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from posed_grid import picture as shaded_picture  # noqa: E402


def scene_body_faces(dataset):
    """The triangles of the body model the dataset's own scene names (its body: model and params): a human-rig
    set's bodies drawn with the mannequin's faces are shards of triangles across the body."""
    body = (yaml.safe_load(dataset.layout["scene"]) or {}).get("body") or {}
    return drape.BodyModel(body.get("model", "parametric"), dict(body.get("params") or {})).faces


def picture(garment, body, faces, body_faces, stem, label, size, views="front,left"):
    """Views of the garment on the body, base64 PNG (posed_grid.py's drawing)."""
    drape.write_obj(stem + ".obj", garment, faces)
    drape.write_obj(stem + "-body.obj", body, body_faces)
    return shaded_picture(stem, label, size, views)


POSE_CLASSES = [("arms low (abduction < 45)", 0, 45), ("arms mid (45-75)", 45, 75), ("arms raised (> 75)", 75, 180)]
BMI_BANDS = [(10, 20), (20, 30), (30, 45), (45, 65)]


def simulated_grade(posed, row, model):
    """The garment grade the sample was simulated in, for a model that takes one (else None, as for a one-size
    dataset): the model is fed that grade, as `drape eval` feeds it, not the size the tailor's rule would choose
    today (shards made before the sizes below small dressed thin bodies in the small)."""
    if "garment_grade" not in model.inputs:
        return None
    try:
        return float(posed.stat("garment_grade", [row])[0])
    except drape.ConfigError:  # a dataset of one garment has no grade statistic
        return None


def grid_picks(posed, wanted):
    """{(pose class, BMI band): row}: per cell the body of that arm class whose BMI is nearest the band's middle."""
    names = posed.layout["pose_angles"]
    arms = [names.index("left_shoulder_abduction"), names.index("right_shoulder_abduction")]
    bmis = posed.stat("bmi", wanted)
    abduction = posed.read([int(r) for r in wanted])["pose"][:, arms].mean(1)
    picks = {}
    for c, (_, lo, hi) in enumerate(POSE_CLASSES):
        for b, (blo, bhi) in enumerate(BMI_BANDS):
            inside = [k for k in range(len(wanted)) if lo <= abduction[k] < hi and blo <= bmis[k] < bhi]
            if inside:
                middle = 0.5 * (blo + bhi)
                picks[(c, b)] = int(wanted[min(inside, key=lambda k: abs(bmis[k] - middle))])
    return picks


def grid(a, posed, rest, done, wanted, name, model, faces, body_faces):
    """The poses x BMI page: each cell simulated beside predicted, the prediction's ME in the caption."""
    names = posed.layout["pose_angles"]
    picks = grid_picks(posed, wanted)
    rows, errors = [], []
    for c, (cname, _, _) in enumerate(POSE_CLASSES):
        cells = []
        for b, (blo, bhi) in enumerate(BMI_BANDS):
            if (c, b) not in picks:
                cells.append("<td>no test body here</td>")
                continue
            row = picks[(c, b)]
            s, r = posed.read([row]), rest.read([done.index(row)])
            pose = {n: float(v) for n, v in zip(names, s["pose"][0])}
            bmi = float(posed.stat("bmi", [row])[0])
            body, simulated = s["body"][0], s["garment"][0]
            predicted = model.predict(r["body"][0], pose=pose, garment_size=simulated_grade(posed, row, model), check=False)
            me = 100 * np.linalg.norm(predicted - simulated, axis=1).mean()
            errors.append(me)
            stem = os.path.join(a.work, f"grid{row}")
            sim = picture(simulated, body, faces, body_faces, stem + "-sim", "simulated", a.size, "front")
            pred = picture(predicted, body, faces, body_faces, stem + "-pred", "predicted", a.size, "front")
            arms = (pose["left_shoulder_abduction"], pose["right_shoulder_abduction"])
            cells.append(f"<td><img src='data:image/png;base64,{sim}'><img src='data:image/png;base64,{pred}'><br>"
                         f"sample {row}, BMI {bmi:.1f}, arms {arms[0]:.0f}/{arms[1]:.0f},<br>twist {pose['spine_twist']:.0f}: "
                         f"ME {me:.2f} cm</td>")
            print(f"{cname}, BMI {blo}-{bhi}: sample {row} (BMI {bmi:.1f}) ME {me:.2f} cm", flush=True)
        rows.append(f"<tr><th>{html.escape(cname)}</th>{''.join(cells)}</tr>")
    head = "".join(f"<th>BMI {lo}-{hi}</th>" for lo, hi in BMI_BANDS)
    with open(a.out, "w") as f:
        f.write(f"""<!doctype html><meta charset=utf-8><title>posed drapes over poses x BMI: predicted against simulated</title>
<style>body{{font:13px sans-serif;background:#fff}} td,th{{vertical-align:top;padding:4px;text-align:left}} th{{width:110px}} td{{white-space:nowrap}}</style>
<h3>{html.escape(name)} on {a.split} bodies of {html.escape(drape.dataset_name(a.data))} over poses x BMI: each cell simulated (left)
and predicted (right), front; mean ME of the {len(errors)} cells {np.mean(errors):.2f} cm</h3>
<table><tr><th></th>{head}</tr>{''.join(rows)}</table>""")
    print("wrote", a.out)
    if a.png:
        width = 140 + len(BMI_BANDS) * (2 * a.size + 12)
        height = 90 + len(POSE_CLASSES) * (a.size * 1.25 + 50)
        subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu", f"--screenshot={os.path.abspath(a.png)}",
                        f"--window-size={int(width)},{int(height)}", "file://" + os.path.abspath(a.out)], capture_output=True)
        print("wrote", a.png)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", required=True, help="a posed dataset (drape generate --poses draw)")
    ap.add_argument("--model", action="append", required=True, help="NAME=model.h5 (repeatable)")
    ap.add_argument("--count", type=int, default=4)
    ap.add_argument("--split", default="test")
    ap.add_argument("--drape", default=os.path.join(ROOT, "build", "bin", "drape"))
    ap.add_argument("--work", default="posed-predicted")
    ap.add_argument("--size", type=int, default=220)
    ap.add_argument("--out", required=True)
    ap.add_argument("--png")
    ap.add_argument("--grid", action="store_true", help="poses x BMI, one model, simulated beside predicted")
    a = ap.parse_args()
    if a.grid and len(a.model) != 1:
        ap.error("--grid draws one model; give --model once")
    os.makedirs(a.work, exist_ok=True)
    rest_file = os.path.join(a.work, "rest.h5")
    if not os.path.exists(rest_file):
        subprocess.run([a.drape, "dataset", "unpose", a.data, "--out", rest_file], check=True, capture_output=True)
    posed, rest = drape.Dataset(a.data), drape.Dataset(rest_file)
    names = posed.layout["pose_angles"]
    done = list(posed.indices("all"))
    wanted = list(posed.indices(a.split))
    bmis = posed.stat("bmi", wanted)
    picks = [wanted[k] for k in np.argsort(bmis)[np.linspace(0, len(wanted) - 1, min(a.count, len(wanted))).astype(int)]]
    models = [(m.split("=", 1)[0], drape.Model.load(m.split("=", 1)[1])) for m in a.model]
    faces = posed.faces
    body_faces = scene_body_faces(posed)
    if a.grid:
        return grid(a, posed, rest, done, wanted, models[0][0], models[0][1], faces, body_faces)
    rows = []
    for row in picks:
        s, r = posed.read([int(row)]), rest.read([done.index(row)])
        pose = {n: float(v) for n, v in zip(names, s["pose"][0])}
        bmi = float(posed.stat("bmi", [int(row)])[0])
        body, simulated = s["body"][0], s["garment"][0]
        stem = os.path.join(a.work, f"sample{row}")
        label = f"BMI {bmi:.0f}"
        cells = [f"<td><img src='data:image/png;base64,{picture(simulated, body, faces, body_faces, stem + '-sim', label, a.size)}'>"
                 f"<br>simulated</td>"]
        for name, model in models:
            predicted = model.predict(r["body"][0], pose=pose, garment_size=simulated_grade(posed, int(row), model), check=False)
            me = 100 * np.linalg.norm(predicted - simulated, axis=1).mean()
            img = picture(predicted, body, faces, body_faces, f"{stem}-{name}", label, a.size)
            cells.append(f"<td><img src='data:image/png;base64,{img}'><br>{html.escape(name)}: ME {me:.2f} cm</td>")
            print(f"sample {row} (BMI {bmi:.1f}): {name} ME {me:.2f} cm", flush=True)
        spec = ", ".join(f"{k.replace('_shoulder_abduction', ' arm')} {v:.0f}" for k, v in pose.items()
                         if k in ("left_shoulder_abduction", "right_shoulder_abduction", "spine_twist", "left_elbow_flexion"))
        rows.append(f"<tr><th>sample {row}<br>BMI {bmi:.1f}<br><small>{html.escape(spec)}</small></th>{''.join(cells)}</tr>")
    head = "".join(f"<th>{html.escape(n)}</th>" for n in ["", "simulated"] + [n for n, _ in models])
    with open(a.out, "w") as f:
        f.write(f"""<!doctype html><meta charset=utf-8><title>posed drapes: predicted against simulated</title>
<style>body{{font:13px sans-serif;background:#fff}} td,th{{vertical-align:top;padding:4px;text-align:left}}</style>
<h3>Posed drapes, {a.split} samples of {html.escape(drape.dataset_name(a.data))}: simulated and predicted (front, left)</h3>
<table><tr>{head}</tr>{''.join(rows)}</table>""")
    print("wrote", a.out)
    if a.png:
        width = 160 + (1 + len(models)) * (2 * a.size + 20)
        height = 90 + len(picks) * (a.size * 1.25 + 40)
        subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu", f"--screenshot={os.path.abspath(a.png)}",
                        f"--window-size={int(width)},{int(height)}", "file://" + os.path.abspath(a.out)], capture_output=True)
        print("wrote", a.png)


if __name__ == "__main__":
    main()
