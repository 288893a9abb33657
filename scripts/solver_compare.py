#!/usr/bin/env python3
"""Two solvers on the same bodies: cost, settledness and how far their drapes lie apart.

Reads two datasets that `drape generate` made from the same bodies (the same --count, --bmi, --seed ...,
one scene per solver) and prints per body and in total: Newton iterations, CPU seconds, whether each drape
settled, p and crossing counts, and the distance between the two drapes of each body (ME: mean over
vertices, in cm, as docs/training.md measures the ground truth's spread; and the largest vertex distance).

    /usr/bin/python3 scripts/solver_compare.py before.h5 after.h5 [--names "today,new"] [--winding]

Needs numpy and h5py. --winding also counts, for every drape of both files, the garment vertices inside the
body by the generalized winding number of scripts/reference/winding_number.py (numpy, no drape code; the
body's faces come from the drape module: build/python on PYTHONPATH).
"""
import argparse
import sys

import h5py
import numpy as np


def load(path):
    with h5py.File(path, "r") as f:
        done = np.asarray(f["done"][:], dtype=bool) if "done" in f else None
        stats = {k: np.asarray(f["stats"][k][:], dtype=float) for k in f["stats"]}
        garments = np.asarray(f["garments/vertices"][:], dtype=np.float64)
        params = np.asarray(f["bodies/params"][:], dtype=np.float64) if "bodies/params" in f else None
        bodies = np.asarray(f["bodies/vertices"][:], dtype=np.float64) if "bodies/vertices" in f else None
    if done is not None and not done.all():
        sys.exit(f"{path}: {int((~done).sum())} samples are not finished")
    return stats, garments, params, bodies


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("before")
    p.add_argument("after")
    p.add_argument("--names", default="before,after", help="two labels, comma-separated")
    p.add_argument("--winding", action="store_true", help="count vertices inside the body by the winding number")
    args = p.parse_args(argv)
    names = args.names.split(",")
    a_stats, a_x, a_params, a_bodies = load(args.before)
    b_stats, b_x, b_params, b_bodies = load(args.after)
    if a_x.shape != b_x.shape:
        sys.exit(f"the datasets differ in shape: {a_x.shape} against {b_x.shape}")
    if a_params is not None and b_params is not None and not np.allclose(a_params, b_params):
        sys.exit("the datasets hold different bodies (their body parameters differ)")
    n = a_x.shape[0]
    distance = np.linalg.norm(a_x - b_x, axis=2)  # [N, Ng] metres
    me_cm = 100 * distance.mean(axis=1)
    max_cm = 100 * distance.max(axis=1)

    def col(stats, key):
        return stats.get(key, np.full(n, np.nan))

    header = ["sample", "BMI"]
    for name in names:
        header += [f"{name}: iterations", f"{name}: s", f"{name}: settled", f"{name}: stationarity", f"{name}: p %",
                   f"{name}: crossings"]
    header += ["ME apart (cm)", "max apart (cm)"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for i in range(n):
        row = [str(i), f"{col(a_stats, 'bmi')[i]:.1f}"]
        for stats in (a_stats, b_stats):
            row += [f"{col(stats, 'iterations')[i]:.0f}", f"{col(stats, 'seconds')[i]:.1f}",
                    "yes" if col(stats, "converged")[i] > 0 else "NO", f"{col(stats, 'stationarity')[i]:.2e}",
                    f"{100 * col(stats, 'penetration')[i]:.3f}", f"{col(stats, 'crossings')[i]:.0f}"]
        row += [f"{me_cm[i]:.3f}", f"{max_cm[i]:.2f}"]
        print("| " + " | ".join(row) + " |")
    print()
    for name, stats in zip(names, (a_stats, b_stats)):
        it, sec = col(stats, "iterations"), col(stats, "seconds")
        settled = int((col(stats, "converged") > 0).sum())
        print(f"{name}: {it.mean():.1f} Newton iterations and {sec.mean():.2f} s per drape; {settled} of {n} settled; "
              f"p > 0 on {int((col(stats, 'penetration') > 0).sum())}, crossings on {int((col(stats, 'crossings') > 0).sum())}")
    ratio_s = col(b_stats, "seconds").mean() / col(a_stats, "seconds").mean()
    ratio_it = col(b_stats, "iterations").mean() / col(a_stats, "iterations").mean()
    print(f"{names[1]} / {names[0]}: {ratio_s:.3f} of the seconds, {ratio_it:.3f} of the Newton iterations")
    if args.winding:
        import os
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference"))
        import drape
        from winding_number import winding_numbers
        faces = np.asarray(drape.assets(resolution="coarse").body_faces)
        for name, x, bodies in zip(names, (a_x, b_x), (a_bodies, b_bodies)):
            inside = [int((winding_numbers(bodies[i], faces, x[i]) > 0.5).sum()) for i in range(n)]
            print(f"{name}: garment vertices inside the body by the winding number: {sum(inside)} in all "
                  f"({sum(1 for k in inside if k)} drapes with any)")
    print(f"the two drapes of a body: ME {me_cm.mean():.3f} cm on average (largest {me_cm.max():.3f}), "
          f"largest vertex distance {max_cm.max():.2f} cm")


if __name__ == "__main__":
    main(sys.argv[1:])
