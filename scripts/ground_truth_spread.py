#!/usr/bin/env python3
"""How far the simulated ground truth is a function of the body: the error floor no predictor can beat.

A drape network is scored by ME against one simulated drape per body. If simulating the same body again,
moved by far less than any body differs from another (by default scaled by 1 + 1e-6 about its soles: a
micrometre at the head), gives a drape some distance away, the simulation amplifies rounding into a
different equilibrium (a fold that buckles the other way, a hem that rides up a little further), and that
distance is noise in the labels. For two such drapes X and Y of one body and any prediction f of it,
|X - Y| <= |X - f| + |Y - f|, so a predictor that is a function of the body has a mean error of at least half
the mean pair distance, whatever it is (docs/findings.md, "How far the ground truth is a function of the
body").

    scripts/ground_truth_spread.py --data bodyspace2000.h5 --split test --count 24 \\
        --scene graphs/scenes/tshirt_coarse.yaml [--model models/tshirt-coarse.h5] [--threads 2]

For each of --count samples of the split (spread evenly over their BMI), or of the --samples named, it
simulates the stored body and its scaled copy with the scene, and prints per BMI band: the pair distance
(ME between the two new drapes), the floor (half of it), each new drape's ME to the stored one (non-zero
when the dataset was made by another build or thread count), and with --model the model's ME to the stored
drapes of the same bodies. --out writes the per-body rows as CSV. --data takes slim shards and globs as they
are (drape.Dataset), e.g. --data 'datasets/bodyspace2000-friction/shard-*-of-40.h5'. Needs the drape Python
module (build/python on PYTHONPATH).

A posed dataset (made with poses="draw", docs/poses.md) is simulated as it was made: each body at rest (the
scaled copy scaled at rest) taken to its stored joint angles by the scene's pose path, and the model, if
given, predicts from the body at rest and the same angles.

--pose-step DEG (posed data) asks how smooth the labels are over a finite change of pose rather than an
infinitesimal one: each body is draped at its angles and at its angles moved by +DEG and -DEG (every angle, its
sign drawn per body), and the table gives the two stepped drapes' distance (how fast the drape follows the
pose) and the drape at the angles against the mean of the two (what is left after the change linear in the
angles: a fold or hem that jumps between neighbouring poses, which no smooth predictor follows).
"""
import argparse
import concurrent.futures
import csv
import os
import sys
import threading
import time

import numpy as np


def parse_arguments(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--data", required=True, help="a drape dataset: full or slim, one file or a quoted glob of shards")
    p.add_argument("--scene", required=True, help="the scene the dataset was simulated with")
    p.add_argument("--split", default="test", choices=["train", "val", "test", "all"])
    p.add_argument("--count", type=int, default=24, help="bodies, spread evenly over the split's BMI")
    p.add_argument("--samples", help="these sample indices (comma-separated) instead of --count of the split")
    p.add_argument("--epsilon", type=float, default=1e-6, help="relative scale of the second body (0: the same)")
    p.add_argument("--pose-step", type=float, default=0.0,
                   help="posed data: instead of the scaled copy, drape each body at its angles moved by +DEG and -DEG "
                        "(each angle, signs drawn per body) and report how far the drape at the angles lies from the "
                        "mean of those two (0: off)")
    p.add_argument("--model", help="also the model's ME on the same bodies, against the stored drapes")
    p.add_argument("--bands", default="10,25,35,45,55,65", help="BMI band edges")
    p.add_argument("--threads", type=int, default=os.cpu_count() or 1, help="simulations run at once")
    p.add_argument("--out", help="per-body rows (.csv)")
    a = p.parse_args(argv)
    if a.count < 1:
        p.error("--count must be at least 1")
    if not a.epsilon >= 0:
        p.error("--epsilon must be >= 0")
    if not 0 <= a.pose_step <= 10:
        p.error("--pose-step must be in [0, 10] degrees")
    return a


SPLITS = {"train": 0, "val": 1, "test": 2}


def pick_samples(done, split, bmi, wanted, count):
    """count sample indices of the split, evenly spaced in BMI order (all of them when there are fewer)."""
    candidates = np.where(done.astype(bool) & ((split == SPLITS[wanted]) if wanted != "all" else True))[0]
    if len(candidates) == 0:
        raise SystemExit(f"no finished sample in split '{wanted}'")
    by_bmi = candidates[np.argsort(bmi[candidates], kind="stable")]
    if count >= len(by_bmi):
        return by_bmi
    return by_bmi[np.round(np.linspace(0, len(by_bmi) - 1, count)).astype(int)]


def scaled_about_soles(body, factor):
    """The body scaled by factor about the point under its centroid at the height of its soles (Y up); at
    factor 1 the body itself (c + (b - c) rounds to another body)."""
    if factor == 1.0:
        return body.copy()
    centre = body.mean(axis=0)
    centre[1] = body[:, 1].min()
    return centre + (body - centre) * factor


def mean_distance_cm(a, b):
    return 100.0 * float(np.linalg.norm(np.asarray(a, float) - np.asarray(b, float), axis=1).mean())


def stepped_angles(angles, step, seed):
    """The angles moved by +step and by -step degrees, each along a sign drawn from seed (the same each run)."""
    signs = np.random.default_rng(seed).choice([-1.0, 1.0], size=len(angles))
    plus = {name: a + step * sign for (name, a), sign in zip(angles.items(), signs)}
    minus = {name: a - step * sign for (name, a), sign in zip(angles.items(), signs)}
    return plus, minus


def off_neighbours_mean_cm(at, plus, minus):
    """ME (cm) of the drape at a point from the mean of its drapes a step either side: what is left of the
    change after its part linear in the step (a second difference, half of it)."""
    return mean_distance_cm(at, (np.asarray(plus, float) + np.asarray(minus, float)) / 2)


def main(argv):
    args = parse_arguments(argv)
    # One simulation per thread at a time: the solver's own threads would only contend.
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    import drape

    # drape.Dataset reads full and slim files (a slim shard's bodies are rebuilt
    # from their shape parameters) and globs of several, as one.
    try:
        data = drape.Dataset(args.data)
    except (drape.ConfigError, drape.Error) as e:
        raise SystemExit(f"ground_truth_spread.py: {e}")
    n = len(data)
    if n == 0:
        raise SystemExit(f"{args.data}: no finished samples")
    split = np.full(n, -1, np.int8)
    for name, code in SPLITS.items():
        split[data.indices(name)] = code
    bmi = data.stat("bmi", np.arange(n))
    if args.samples:
        picks = np.array([int(i) for i in args.samples.split(",")])
        bad = [int(i) for i in picks if not 0 <= i < n]
        if bad:
            raise SystemExit(f"{args.data}: no finished sample {bad[0]} (the data has {n})")
    else:
        picks = pick_samples(np.ones(n, np.uint8), split, bmi, args.split, args.count)
    batch = data.read(picks)
    bodies = {int(i): batch["body"][k].astype(np.float64) for k, i in enumerate(picks)}
    # A posed sample is simulated from its body at rest and its angles, as drape generate made it.
    poses = {}
    if "pose" in batch:
        unposed = data.posing([int(i) for i in picks])["unposed"]
        names = list(data.layout["pose_angles"])
        for k, i in enumerate(picks):
            bodies[int(i)] = unposed[k].astype(np.float64)
            poses[int(i)] = {name: float(a) for name, a in zip(names, batch["pose"][k])}
    stored = {int(i): batch["garment"][k].astype(np.float64) for k, i in enumerate(picks)}

    model = drape.Model.load(args.model) if args.model else None
    scenes = {}

    def simulate(body, pose):
        key = threading.get_ident()
        if key not in scenes:  # a Scene per worker thread: simulations share nothing
            scenes[key] = drape.Scene(args.scene)
        r = scenes[key].simulate(body, pose=pose)
        if not r["converged"]:
            print(f"  (a drape did not settle: {r.get('unsettled', '')})", file=sys.stderr)
        return r["garment"], bool(r["converged"])

    # The second drape: the body scaled by 1 + epsilon, or (--pose-step) two drapes at the angles moved by
    # +-step along a direction of signs drawn per body (seeded by the sample index: a re-run drapes the same).
    stepped = args.pose_step > 0
    if stepped and not poses:
        raise SystemExit(f"{args.data}: --pose-step needs a posed dataset (its samples store no angles)")
    steps = {int(i): stepped_angles(poses[int(i)], args.pose_step, int(i)) for i in picks} if stepped else {}

    def job_input(i, which):
        if which == 0:
            return bodies[i], poses.get(i)
        if not stepped:
            return scaled_about_soles(bodies[i], 1.0 + args.epsilon), poses.get(i)
        return bodies[i], steps[i][which - 1]

    jobs = [(int(i), which) for i in picks for which in ((0, 1, 2) if stepped else (0, 1))]
    results = {}
    start = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.threads)) as pool:
        futures = {}
        for i, which in jobs:
            futures[pool.submit(simulate, *job_input(i, which))] = (i, which)
        for n, future in enumerate(concurrent.futures.as_completed(futures), 1):
            try:
                results[futures[future]] = future.result()
            except drape.ConfigError as e:  # a stepped pose refused (a limit passed, the body crossing itself)
                if not stepped or futures[future][1] == 0:
                    raise
                results[futures[future]] = (None, False)
                print(f"\n  sample {futures[future][0]}: stepped pose refused: {e}", file=sys.stderr)
            elapsed = time.time() - start
            eta = elapsed / n * (len(jobs) - n)
            bar = "#" * (30 * n // len(jobs))
            print(f"\r[{bar:<30}] {n}/{len(jobs)} simulations, {elapsed:.0f} s, ETA {eta:.0f} s", end="",
                  file=sys.stderr, flush=True)
    print(file=sys.stderr)

    rows = []
    for i in map(int, picks):
        (first, settled_first), (second, settled_second) = results[(i, 0)], results[(i, 1)]
        if stepped:
            third, settled_third = results[(i, 2)]
            if second is None or third is None:
                continue
            # The pair spans 2 steps; the drape at the angles against the mean of its two neighbours is what is
            # left after the part of the change that is linear in the angles (a smooth predictor's).
            row = {"sample": i, "bmi": float(bmi[i]), "pair_me_cm": mean_distance_cm(second, third),
                   "off_neighbours_mean_cm": off_neighbours_mean_cm(first, second, third)}
            settled_second = settled_second and settled_third
        else:
            row = {"sample": i, "bmi": float(bmi[i]), "pair_me_cm": mean_distance_cm(first, second)}
        row.update({"rerun_to_stored_cm": mean_distance_cm(first, stored[i]),
                    "settled": int(settled_first and settled_second)})
        if model is not None:
            pose = {"pose": poses[i]} if i in poses else {}
            row["model_me_cm"] = mean_distance_cm(model.predict(bodies[i].astype(np.float32), **pose), stored[i])
        rows.append(row)

    edges = [float(x) for x in args.bands.split(",")]
    if not rows:
        raise SystemExit("no body had both stepped poses draped")
    second = (f"drapes at the angles +-{args.pose_step:g} degrees" if stepped
              else f"second body scaled by 1 + {args.epsilon:g}")
    print(f"{len(rows)} bodies of {args.data} ({args.split}), {second}, scene {args.scene}")
    header = ("| BMI | bodies | pair +- step (cm) | drape off its neighbours' mean (cm) | new drape to stored (cm) |"
              if stepped else "| BMI | bodies | pair ME (cm) | floor = pair / 2 (cm) | new drape to stored (cm) |")
    header += " model ME (cm) |" if model is not None else ""
    print(header)
    print("|---" * (header.count("|") - 1) + "|")
    def in_band(r, lo, hi):
        return lo <= r["bmi"] < hi or (hi == edges[-1] and r["bmi"] == hi)

    bands = [(f"{lo:g}-{hi:g}", lo, hi) for lo, hi in zip(edges[:-1], edges[1:])] + [("all", -np.inf, np.inf)]
    for name, lo, hi in bands:
        sel = [r for r in rows if in_band(r, lo, hi)]
        if not sel:
            continue
        pair = np.mean([r["pair_me_cm"] for r in sel])
        second_column = np.mean([r["off_neighbours_mean_cm"] for r in sel]) if stepped else pair / 2
        line = (f"| {name} | {len(sel)} | {pair:.3f} | {second_column:.3f} | "
                f"{np.mean([r['rerun_to_stored_cm'] for r in sel]):.3f} |")
        if model is not None:
            line += f" {np.mean([r['model_me_cm'] for r in sel]):.3f} |"
        print(line)
    unsettled = sum(1 - r["settled"] for r in rows)
    if unsettled:
        print(f"{unsettled} of {len(rows)} bodies had a drape that did not settle")
    if args.out:
        tmp = args.out + ".tmp"
        with open(tmp, "w", newline="") as out:
            w = csv.DictWriter(out, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
        os.replace(tmp, args.out)  # atomically: a killed run leaves no half-written table
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
