#!/usr/bin/env python3
"""p (percent of garment vertices inside the body) of a model's predictions on
a dataset split, by the generalized winding number of winding_number.py (numpy): it
shares no code with drape's own inside test (docs/garments.md uses it for the
MakeHuman model).

    PYTHONPATH=build/python /usr/bin/python3 scripts/reference/winding_number_p.py MODEL.h5 DATA.h5 [--split test]
"""
import argparse

import h5py
import numpy as np

import drape
from winding_number import winding_numbers

SPLITS = {"train": 0, "val": 1, "test": 2}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model")
    parser.add_argument("data")
    parser.add_argument("--split", default="test", choices=sorted(SPLITS))
    args = parser.parse_args()
    model = drape.Model.load(args.model)
    faces = np.asarray(model.assets.body_faces)
    with h5py.File(args.data, "r") as f:
        rows = np.where(f["split"][:] == SPLITS[args.split])[0]
        bodies = f["bodies/vertices"][rows.tolist()]
        stats = {k: f["stats/" + k][:] for k in ("sex", "height", "bmi")}
    predictions = model.predict(np.ascontiguousarray(bodies, dtype=np.float32))
    ps = []
    for i, row in enumerate(rows):
        inside = winding_numbers(bodies[i].astype(np.float64), faces, np.asarray(predictions[i], dtype=np.float64)) > 0.5
        ps.append(100.0 * inside.mean())
        print("sample %d (sex %d, %.2f m, BMI %.1f): p = %.2f %%" %
              (row, stats["sex"][row], stats["height"][row], stats["bmi"][row], ps[-1]), flush=True)
    ps = np.array(ps)
    print("%s split, %d samples: mean p %.3f %%, max %.2f %%, above 1 %%: %d" %
          (args.split, len(ps), ps.mean(), ps.max(), int((ps > 1).sum())))


if __name__ == "__main__":
    main()
