#!/usr/bin/env python3
"""A model's predictions on a dataset's bodies checked by code that shares nothing with drape's contact, as
scripts/check_dataset_drapes.py checks simulated drapes: p by the generalized winding number of the garment's
vertices in the body, garment-body edge-face crossings and the garment's crossings of itself
(scripts/count_self_crossings.py). The predictions come from drape's Python module (`Model.predict`, each body in
the size the model's tailor's rule gives); only the checks are independent of it.

    PYTHONPATH=build/python /usr/bin/python3 scripts/check_predictions.py --model M.h5 --data data.h5 \\
        [--split test] [--samples 6,31] [--set post.untangle=false] [--csv out.csv]

The dataset is read through drape.Dataset (slim shards rebuild their bodies; a glob pattern reads several). For a
model of posed drapes each body's rest shape and joint angles are given to predict and the posed body is checked.
--set changes a parameter of the
model's graph that leaves the weights alone (as drape eval --set), through a copy made by `drape model set`.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from check_dataset_drapes import drape_checks, write_csv  # noqa: E402

SPLITS = {"train": 0, "val": 1, "test": 2}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--model", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--split", default="test", choices=[*SPLITS, "all"])
    ap.add_argument("--set", action="append", default=[], help="node.param=value (repeatable)")
    ap.add_argument("--drape", default=os.path.join(os.path.dirname(HERE), "build", "bin", "drape"))
    ap.add_argument("--samples", help="only these sample indices of the dataset, e.g. 6,31 (in the split chosen)")
    ap.add_argument("--csv")
    a = ap.parse_args()
    import drape  # the module under test: predictions only

    warnings.filterwarnings("ignore", message="size .* by the tailor")  # one per body

    with tempfile.TemporaryDirectory() as tmp:
        model_file = a.model
        if a.set:
            model_file = os.path.join(tmp, "model.h5")
            args = [x for s in a.set for x in ("--set", s)]
            subprocess.run([a.drape, "model", "set", a.model, "--out", model_file, *args], check=True,
                           capture_output=True)
        model = drape.Model.load(model_file)
        data = drape.Dataset(a.data)  # slim shards too: each body rebuilt from its parameters
        chosen = list(range(len(data)) if a.split == "all" else data.indices(a.split))
        if a.samples:
            wanted = {int(x) for x in a.samples.split(",")}
            chosen = [i for i in chosen if int(i) in wanted]
        names = data.layout.get("pose_angles") if model.takes_pose else None
        gf = np.array(model.assets.garment_faces)
        bf = np.array(model.assets.body_faces)
        if chosen and bf.max() + 1 != len(data[int(chosen[0])]["body"]):
            sys.exit(f"{a.data}: its bodies have {len(data[int(chosen[0])]['body'])} vertices, the model's body faces "
                     f"index {bf.max() + 1}")
        rows = []
        for i in chosen:
            sample = data[int(i)]
            body = np.asarray(sample["body"], dtype=np.float32)
            if names:  # a model of posed drapes: the rest body and the sample's joint angles (degrees)
                rest = data.posing([int(i)])["unposed"][0]
                pose = {n: float(v) for n, v in zip(names, sample["pose"])}
                garment = model.predict(rest, pose=pose, check=False)
            else:
                garment = model.predict(body, check=False)
            r = dict(index=int(sample["index"]), bmi=float(data.stat("bmi", [int(i)])[0]),
                     **drape_checks(garment, gf, body, bf))
            rows.append(r)
            print(f"sample {r['index']} (BMI {r['bmi']:.1f}): p {r['p']:.2f} %, {r['garment_body']} garment-body "
                  f"crossings, {r['self_crossings']} self-crossings", flush=True)
    inside = sum(r["p"] > 0 for r in rows)
    through_body = sum(r["garment_body"] > 0 for r in rows)
    crossing_self = sum(r["self_crossings"] > 0 for r in rows)
    print(f"{len(rows)} predictions: {inside} with a vertex inside the body, {through_body} crossing the body, "
          f"{crossing_self} crossing themselves ({sum(r['self_crossings'] for r in rows)} edges)")
    if a.csv and rows:
        write_csv(a.csv, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
