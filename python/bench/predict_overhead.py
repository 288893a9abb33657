#!/usr/bin/env python3
"""The overhead of a Python drape.Model.predict call over the C++ Model::predict at batch 1
(the issue's target: at most 5 %).

Both sides run in this one process on the same model, body and OpenBLAS kernels: the C++ side is
Model::predict timed inside C++ (Model._predict_timed, the GIL released, no Python in the loop), the Python
side is model.predict(body, check=False) timed around the call with time.perf_counter -- argument checks,
the placement, the float32
copy of the body, the GIL release, the result handed over as a NumPy array. Rounds alternate between the
two so that a noisy, shared machine disturbs both alike. Reported: the median of the quietest round (best
of several rounds) and the median over all calls, per side, and their ratios. check=False leaves out the
domain check and the fit note, which measure the body (work the C++ side does not do: docs/python.md); a model of
several sizes is given the size the tailor's rule chose for the body (the C++ side chooses it once), and the call
without it is timed beside.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/predict_overhead.py [--model M] [--calls 200] [--rounds 10]

With --drape PATH it also prints `drape bench infer` on the same model for reference: a separate process,
which may run other BLAS kernels than this one.
"""
import argparse
import re
import statistics
import subprocess
import time
import warnings

import numpy as np

import drape


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--model", default=None, help="model file (default: the shipped one)")
    ap.add_argument("--bmi", type=float, default=35.0)
    ap.add_argument("--calls", type=int, default=200, help="calls per round and side")
    ap.add_argument("--rounds", type=int, default=10)
    ap.add_argument("--drape", default=None, help="the drape program, to print `drape bench infer` too")
    args = ap.parse_args()

    model = drape.Model.load(args.model)
    body = model.body(bmi=args.bmi)
    # A model of several sizes chooses one per call by the tailor's rule, which measures the body's girth (about
    # 2 ms on the human rig); the C++ side chooses it once. The Python side is given the size the rule chose, so
    # that both time the same work, and the rule's cost is printed beside.
    size = None
    with warnings.catch_warnings(record=True) as notes:
        warnings.simplefilter("always")
        model.predict(body, check=False)
    for note in notes:
        found = re.search(r"size (\S+) by the tailor's rule", str(note.message))
        size = found.group(1) if found else size
    for _ in range(20):  # warm-up: caches, OpenMP threads, allocator
        model.predict(body, check=False, garment_size=size)
    model._predict_timed(body, 20)

    cpp, py = [], []  # per round: the calls' times
    for _ in range(args.rounds):
        cpp.append(model._predict_timed(body, args.calls))
        times = []
        for _ in range(args.calls):
            t0 = time.perf_counter()
            model.predict(body, check=False, garment_size=size)
            times.append(time.perf_counter() - t0)
        py.append(times)
    rule = []
    if size is not None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for _ in range(args.calls):
                t0 = time.perf_counter()
                model.predict(body, check=False)
                rule.append(time.perf_counter() - t0)

    # "best": the quietest round's median (a lone fastest call is an outlier on a shared machine);
    # "median": over every call.
    best_c = min(statistics.median(r) for r in cpp)
    best_p = min(statistics.median(r) for r in py)
    med_c = statistics.median(t for r in cpp for t in r)
    med_p = statistics.median(t for r in py for t in r)
    print(f"model {model.file}, garment {model.garment_vertex_count} vertices, body {model.body_vertex_count}, batch 1")
    better = drape.better_blas_coretype()
    print(f"OpenBLAS kernels: {drape.blas_corename() or '(not OpenBLAS)'}" +
          (f" (this CPU runs {better}: set OPENBLAS_CORETYPE={better} before Python starts)" if better else ""))
    print(f"{args.rounds} rounds x {args.calls} calls per side\n")
    print("| | ms per call (best round's median) | median of all calls |")
    print("|---|---|---|")
    print(f"| C++ Model::predict (in process) | {1e3 * best_c:.3f} | {1e3 * med_c:.3f} |")
    print(f"| Python model.predict | {1e3 * best_p:.3f} | {1e3 * med_p:.3f} |")
    print(f"| overhead | {100 * (best_p / best_c - 1):+.1f} % ({1e6 * (best_p - best_c):.0f} us) "
          f"| {100 * (med_p / med_c - 1):+.1f} % ({1e6 * (med_p - med_c):.0f} us) |")
    if rule:
        print(f"\nwithout garment_size (the size {size} chosen by the tailor's rule at each call): "
              f"{1e3 * statistics.median(rule):.3f} ms per call, median")
    if args.drape:
        out = subprocess.run([args.drape, "bench", "infer", "--model", str(model.file), "--bmi", str(args.bmi),
                              "--repeats", "50"], capture_output=True, text=True, check=True).stdout
        rows = [line for line in out.splitlines() if line.startswith("| ") and line[2:3].isdigit()]
        if rows:
            print(f"\ndrape bench infer (its own process), ms per body best | median: {rows[0]}")


if __name__ == "__main__":
    main()
