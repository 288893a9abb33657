#!/usr/bin/env python3
"""p (percent of garment vertices inside the body) of a model's predictions on
a dataset split, by a generalized winding number written here in numpy: it
shares no code with drape's own inside test (docs/garments.md uses it for the
MakeHuman model).

    PYTHONPATH=build/python /usr/bin/python3 scripts/reference/winding_number_p.py MODEL.h5 DATA.h5 [--split test]
"""
import argparse

import numpy as np

SPLITS = {"train": 0, "val": 1, "test": 2}


def winding_numbers(vertices, faces, points, chunk=64):
    """Van Oosterom-Strackee solid angles summed over the faces, / 4 pi."""
    a_all, b_all, c_all = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    w = np.zeros(len(points))
    for s in range(0, len(points), chunk):
        p = points[s:s + chunk, None]
        a, b, c = a_all[None] - p, b_all[None] - p, c_all[None] - p
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        det = np.einsum("ijk,ijk->ij", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ijk,ijk->ij", a, b) * lc + np.einsum("ijk,ijk->ij", b, c) * la +
               np.einsum("ijk,ijk->ij", c, a) * lb)
        w[s:s + chunk] = np.arctan2(det, den).sum(axis=1) / (2 * np.pi)
    return w


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model")
    parser.add_argument("data")
    parser.add_argument("--split", default="test", choices=sorted(SPLITS))
    args = parser.parse_args()
    import h5py  # here, so that winding_numbers can be imported without drape or h5py

    import drape
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
