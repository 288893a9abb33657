#!/usr/bin/env python3
"""Every drape of a dataset checked by code that shares nothing with drape's contact (h5py and numpy only): p by
the generalized winding number of the garment's vertices in the body (scripts/reference/winding_number.py),
garment-body edge-face crossings and the garment's self-crossings (scripts/count_self_crossings.py), and the
stored `converged` flag. The dataset must hold its body vertices (a full shard, or `drape dataset expand` of a
slim one; a slim file is refused) and its garment faces. The drapes not clean are listed by the generator's global
index, with the `drape dataset slim --drop` that leaves them out.

    /usr/bin/python3 scripts/check_dataset_drapes.py data.h5 [--body-faces body.obj] [--csv out.csv]

The body's faces come from --body-faces (any mesh of the body model's topology, e.g. `drape body --out`), else
from `drape body` run here with the body model and parameters of the scene the dataset records (the human rig's
drapes get the human rig's faces). Faces of another topology than the dataset's bodies are refused.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "reference"))
from count_self_crossings import crossings  # noqa: E402
from obj_file import read_obj  # noqa: E402
from winding_number import winding_numbers  # noqa: E402


def scene_body_args(data):
    """`drape body` arguments for the body model (and its parameters, e.g. rig: human) of the scene a dataset
    records; none for a dataset without one."""
    with h5py.File(data, "r") as f:
        text = f.attrs.get("scene", b"")
    text = text.decode() if isinstance(text, bytes) else str(text)
    if not text:
        return []
    import yaml  # python3-yaml: only needed here

    body = (yaml.safe_load(text) or {}).get("body") or {}
    args = ["--model", str(body["model"])] if "model" in body else []
    for name, value in (body.get("params") or {}).items():
        args += ["--param", f"{name}={value}"]
    return args


def drape_checks(garment, garment_faces, body, body_faces):
    """One drape: p (% of the garment's vertices inside the body by winding numbers), garment-body edge-face
    crossings, and the garment's crossings of itself."""
    gv, bv = np.asarray(garment, dtype=np.float64), np.asarray(body, dtype=np.float64)
    inside = int((winding_numbers(bv, body_faces, gv) > 0.5).sum())
    self_pairs, _ = crossings(gv, garment_faces)
    body_pairs, _ = crossings(bv, body_faces)
    both, _ = crossings(np.vstack([gv, bv]), np.vstack([garment_faces, body_faces + len(gv)]))
    return dict(p=100.0 * inside / len(gv), garment_body=len(both) - len(self_pairs) - len(body_pairs),
                self_crossings=len(self_pairs))


def write_csv(path, rows):
    with open(path, "w") as f:
        f.write(",".join(rows[0]) + "\n")
        for r in rows:
            f.write(",".join(str(v) for v in r.values()) + "\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data")
    ap.add_argument("--body-faces")
    ap.add_argument("--drape", default=os.path.join(os.path.dirname(HERE), "build", "bin", "drape"))
    ap.add_argument("--csv")
    a = ap.parse_args()
    if a.body_faces:
        _, bf = read_obj(a.body_faces)
    else:
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run([a.drape, "body", *scene_body_args(a.data), "--out", os.path.join(tmp, "b.obj")],
                           check=True, capture_output=True)
            _, bf = read_obj(os.path.join(tmp, "b.obj"))
    with h5py.File(a.data) as f:
        if "bodies/vertices" not in f:
            sys.exit(f"{a.data}: a slim dataset (its bodies are not stored): check `drape dataset expand --out "
                     f"FULL.h5 {a.data}` instead (this script reads what was simulated, and rebuilds nothing itself)")
        gf = f["garments/faces"][:]
        body_vertices = f["bodies/vertices"].shape[1]
        if bf.max() + 1 != body_vertices:
            sys.exit(f"{a.data}: its bodies have {body_vertices} vertices, the body faces index {bf.max() + 1} "
                     "(another body model or rig): give --body-faces a mesh of the dataset's body topology")
        done = np.flatnonzero(f["done"][:])
        bodies, garments = f["bodies/vertices"], f["garments/vertices"]
        converged = f["stats/converged"][:]
        bmi = f["stats/bmi"][:]
        # The generator's numbering (drape generate's global_index), which `drape dataset slim --drop` takes.
        global_index = f["stats/global_index"][:] if "stats/global_index" in f else None
        rows, rejected = [], []
        for i in done:
            checks = drape_checks(garments[i], gf, bodies[i], bf)
            r = dict(index=int(i), **({} if global_index is None else {"global_index": int(global_index[i])}),
                     bmi=float(bmi[i]), converged=int(converged[i]), **checks)
            clean = r["converged"] == 1 and r["p"] == 0 and r["garment_body"] == 0 and r["self_crossings"] == 0
            if not clean:
                rejected.append(r.get("global_index"))
            rows.append(r)
            print(f"sample {i} (BMI {r['bmi']:.1f}): {'clean' if clean else 'NOT CLEAN'}: converged {r['converged']}, "
                  f"p {r['p']:.2f} %, {r['garment_body']} garment-body crossings, {r['self_crossings']} self-crossings",
                  flush=True)
    bad = len(rejected)
    print(f"{len(rows) - bad} of {len(rows)} drapes clean (settled, p = 0 by winding numbers, no crossing, no "
          "self-crossing)")
    if bad and global_index is not None:
        listed = ",".join(str(g) for g in rejected)
        print(f"not clean: global index {listed} (`drape dataset slim {a.data} --out SLIM --drop {listed}` leaves "
              "them out)")
    if a.csv:
        write_csv(a.csv, rows)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
