#!/usr/bin/env python3
"""Posed drapes over shape x pose, checked by code that shares nothing with drape's contact (issue 55's target):
N bodies drawn by `drape body --sample N --poses` (shape and pose independent, poses by rejection), each draped by
`drape simulate SCENE` with the body's BMI, height, sex, girths and pose; then for every drape

  - p by the generalized winding number (scripts/reference/winding_number.py, numpy) of the garment's vertices
    against the posed body;
  - garment-body crossings: edges through faces of the garment and body meshes taken together, less those of
    each alone (scripts/count_self_crossings.py);
  - garment self-crossings: the same count on the garment alone.

With --compare-apose K the first K bodies are also draped in the A-pose (the same shape), for the cost ratio
posed/A-pose (Newton iterations and seconds, in one run, so the machine's load is shared alike), in the scene
--apose-scene (default: the coarse A-pose scene the posed one derives from, tshirt_coarse_sized.yaml).

    /usr/bin/python3 scripts/posed_drape_check.py N [--seed S] [--scene graphs/scenes/tshirt_coarse_posed.yaml]
        [--compare-apose K] [--bmi 10:65] [--drape build/bin/drape] [--out-dir DIR] [--part K/M]

Writes DIR/drapes.csv (one line per drape) and prints a summary; exit 1 when any drape is unsettled, inside, or
crossing. docs/poses.md reports a run. Each drape's result is also kept as DIR/drape_NNN_KIND.json, so a run
started again on the same DIR resumes where it was killed, and --part K/M drapes only the bodies i with
i % M == K (one process per core on one DIR; the bodies are drawn once, by the first; the summary covers every
drape of DIR that is done; parts started together draw the bodies once).
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(HERE, "reference"))
sys.path.insert(0, HERE)
from obj_file import read_obj  # noqa: E402
from winding_number import winding_numbers  # noqa: E402
from count_self_crossings import crossings  # noqa: E402
from simulate_report import parse_simulate_output  # noqa: E402

GIRTHS = ("chest", "waist", "belly", "hips", "arms", "thighs")


def simulate(a, stem, row, pose, scene):
    cmd = [a.drape, "simulate", scene, "--bmi", row["requested_bmi"], "--height", row["requested_height"], "--sex",
           row["sex"], "--threads", "1", "--out", stem + ".obj", "--body-out", stem + "-body.obj", "--pose", pose]
    for g in GIRTHS:
        if "shape_" + g in row:
            cmd += ["--girth", f"{g}={row['shape_' + g]}"]
    start = time.time()
    run = subprocess.run(cmd, capture_output=True, text=True)
    text = run.stdout + run.stderr
    out = dict(exit=run.returncode, wall=time.time() - start)
    if not os.path.exists(stem + ".obj"):
        lines = [ln for ln in text.strip().splitlines() if ln.strip()]
        out["refused"] = lines[-1] if lines else f"exit {run.returncode}"
        return out
    out.update(parse_simulate_output(text))
    return out


def independent_checks(stem):
    gv, gf = read_obj(stem + ".obj")
    bv, bf = read_obj(stem + "-body.obj")
    w = winding_numbers(bv, bf, gv)
    inside = int((w > 0.5).sum())
    self_pairs, _ = crossings(gv, gf)
    body_pairs, _ = crossings(bv, bf)
    both_v = np.vstack([gv, bv])
    both_f = np.vstack([gf, bf + len(gv)])
    both_pairs, _ = crossings(both_v, both_f)
    return dict(p_winding=100.0 * inside / len(gv), garment_body_crossings=len(both_pairs) - len(self_pairs) - len(body_pairs),
                self_crossings=len(self_pairs))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("n", type=int)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--bmi", default="10:65")
    ap.add_argument("--scene", default=os.path.join(ROOT, "graphs", "scenes", "tshirt_coarse_posed.yaml"))
    ap.add_argument("--drape", default=os.path.join(ROOT, "build", "bin", "drape"))
    ap.add_argument("--compare-apose", type=int, default=0, metavar="K")
    ap.add_argument("--apose-scene", default=os.path.join(ROOT, "graphs", "scenes", "tshirt_coarse_sized.yaml"))
    ap.add_argument("--out-dir", default=None)
    ap.add_argument("--part", default="0/1", metavar="K/M")
    a = ap.parse_args()
    part, parts = (int(x) for x in a.part.split("/"))
    out = a.out_dir or tempfile.mkdtemp(prefix="posed-drapes-")
    os.makedirs(out, exist_ok=True)
    bodies_csv = os.path.join(out, "bodies", "bodies.csv")
    if not os.path.exists(bodies_csv):
        # Drawn into a folder of this process's own, then renamed into place: of two parts started together
        # one rename wins and the other's draw (the same bodies, by the seed) is dropped.
        drawn = os.path.join(out, f"bodies.{os.getpid()}")
        subprocess.run([a.drape, "body", "--sample", str(a.n), "--poses", "--bmi", a.bmi, "--seed", str(a.seed), "--out-dir",
                        drawn], check=True, capture_output=True)
        try:
            os.rename(drawn, os.path.join(out, "bodies"))
        except OSError:  # another part's draw is in place
            shutil.rmtree(drawn)
    with open(bodies_csv) as f:
        bodies = list(csv.DictReader(f))
    if len(bodies) != a.n:
        sys.exit(f"{bodies_csv} holds {len(bodies)} bodies, not {a.n}: another run's folder")
    rows, bad = [], 0
    for i, body in enumerate(bodies):
        pose = ",".join(f"{k[5:]}={float(v):.6f}" for k, v in body.items() if k.startswith("pose_") and k != "pose_redraws")
        for kind in (("posed", "A-pose") if i < a.compare_apose else ("posed",)):
            stem = os.path.join(out, f"drape_{i:03d}_{kind}")
            if os.path.exists(stem + ".json"):
                with open(stem + ".json") as f:
                    r = json.load(f)
            elif i % parts != part:
                continue
            else:
                r = simulate(a, stem, body, pose, a.scene) if kind == "posed" else simulate(a, stem, body, "", a.apose_scene)
                r.update(index=i, kind=kind, bmi=float(body["requested_bmi"]), sex=body["sex"],
                         height=float(body["requested_height"]))
                if "refused" not in r:
                    r.update(independent_checks(stem))
                if r["exit"] >= 0:  # a drape whose simulate was killed (a signal) is done again on the next run
                    with open(stem + ".json.partial", "w") as f:
                        json.dump(r, f)
                    os.replace(stem + ".json.partial", stem + ".json")  # written whole: a killed run redoes the drape
            if "refused" not in r:
                ok = r["settled"] and r["p_winding"] == 0 and r["garment_body_crossings"] == 0 and r["self_crossings"] == 0
            else:
                ok = False
            bad += 0 if ok else 1
            rows.append(r)
            status = r.get("refused") or (f"{'settled' if r['settled'] else 'NOT settled'}, p {r['p_winding']:.2f} %, "
                                          f"{r['garment_body_crossings']} garment-body and {r['self_crossings']} self "
                                          f"crossings, {r['iterations']} it, {r['seconds']:.1f} s, size {r['size']}")
            print(f"{i + 1}/{len(bodies)} {kind} BMI {r['bmi']:.1f} sex {r['sex']}: {status}", flush=True)
    keys = ["index", "kind", "bmi", "height", "sex", "size", "settled", "iterations", "seconds", "wall", "p_winding",
            "garment_body_crossings", "self_crossings", "refused"]
    with open(os.path.join(out, "drapes.csv"), "w") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    posed = [r for r in rows if r["kind"] == "posed" and "refused" not in r]
    print(f"{len(posed)} posed drapes (done in {out}) of {len(bodies)} bodies: {sum(r['settled'] for r in posed)} settled, "
          f"{sum(r['p_winding'] > 0 for r in posed)} with a vertex inside, "
          f"{sum(r['garment_body_crossings'] > 0 for r in posed)} crossing the body, "
          f"{sum(r['self_crossings'] > 0 for r in posed)} crossing themselves; "
          f"{sum(1 for r in rows if 'refused' in r)} refused; wrote {os.path.join(out, 'drapes.csv')}")
    if a.compare_apose:
        pairs = [(p, q) for p in posed for q in rows if q["kind"] == "A-pose" and q["index"] == p["index"] and "refused" not in q]
        if pairs:
            it = np.array([p["iterations"] / q["iterations"] for p, q in pairs])
            sec = np.array([p["seconds"] / q["seconds"] for p, q in pairs])
            print(f"posed / A-pose cost over {len(pairs)} bodies: Newton iterations median {np.median(it):.2f} "
                  f"(max {it.max():.2f}), seconds median {np.median(sec):.2f} (max {sec.max():.2f}); "
                  f"totals {sum(p['seconds'] for p, _ in pairs) / sum(q['seconds'] for _, q in pairs):.2f}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
