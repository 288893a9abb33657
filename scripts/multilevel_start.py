#!/usr/bin/env python3
"""Measures a multilevel start: the coarse shirt is draped first, carried to
the default shirt, and the default shirt settles from there (docs/findings.md,
"Tried for speed and convergence, not kept").

Each default-shirt vertex is placed at the barycentric point of its closest
point on the coarse shirt, both as dressed on the mean body, so the carried
shirt lies on the coarse drape's surface. The default scene then starts from
it, its body shrunk until the start is clear (the scene's own separated
start) and grown back in a few morph steps.

  PYTHONPATH=build/python python3 scripts/multilevel_start.py --bmi 35

Prints the Newton iterations and seconds of both stages next to the default
scene draped from the template, so the three numbers come from one run.
"""
import argparse
import json
import time

import numpy as np

import drape


def closest_on_triangles(p, a, b, c):
    """Closest point of p on each triangle (a, b, c rows): barycentrics and distances."""
    ab, ac, ap = b - a, c - a, p - a
    bp, cp = p - b, p - c
    d1, d2 = (ab * ap).sum(1), (ac * ap).sum(1)
    d3, d4 = (ab * bp).sum(1), (ac * bp).sum(1)
    d5, d6 = (ab * cp).sum(1), (ac * cp).sum(1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    bary = np.zeros((len(a), 3))
    # Ericson's regions: vertex, edge and face, resolved in that order.
    region = np.zeros(len(a), dtype=bool)
    def take(mask, weights):
        nonlocal region
        mask = mask & ~region
        bary[mask] = weights[mask]
        region |= mask
    one = np.ones(len(a)); zero = np.zeros(len(a))
    take((d1 <= 0) & (d2 <= 0), np.stack([one, zero, zero], 1))
    take((d3 >= 0) & (d4 <= d3), np.stack([zero, one, zero], 1))
    take((d6 >= 0) & (d5 <= d6), np.stack([zero, zero, one], 1))
    with np.errstate(divide="ignore", invalid="ignore"):
        v = d1 / (d1 - d3)
        take((vc <= 0) & (d1 >= 0) & (d3 <= 0), np.stack([1 - v, v, zero], 1))
        w = d2 / (d2 - d6)
        take((vb <= 0) & (d2 >= 0) & (d6 <= 0), np.stack([1 - w, zero, w], 1))
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        take((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0), np.stack([zero, 1 - w, w], 1))
        den = va + vb + vc
        take(np.ones(len(a), dtype=bool), np.stack([va / den, vb / den, vc / den], 1))
    q = bary[:, :1] * a + bary[:, 1:2] * b + bary[:, 2:] * c
    return bary, np.linalg.norm(q - p, axis=1)


def carry(fine_rest, coarse_rest, coarse_faces, coarse_drape):
    """Each fine vertex at the barycentric point of its closest coarse point."""
    a, b, c = (coarse_rest[coarse_faces[:, k]] for k in range(3))
    out = np.empty_like(fine_rest)
    worst = 0.0
    for i, p in enumerate(fine_rest):
        bary, dist = closest_on_triangles(p, a, b, c)
        f = int(np.argmin(dist))
        worst = max(worst, float(dist[f]))
        out[i] = bary[f] @ coarse_drape[coarse_faces[f]]
    return out, worst


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bmi", type=float, default=35.0)
    ap.add_argument("--coarse-scene", default="graphs/scenes/tshirt_coarse.yaml")
    ap.add_argument("--scene", default="graphs/scenes/tshirt.yaml")
    ap.add_argument("--morph-steps", type=int, default=3, help="morph steps of the default stage")
    args = ap.parse_args()

    coarse = drape.Scene(args.coarse_scene)
    fine = drape.Scene(args.scene)
    carried_scene = drape.Scene({"base": args.scene, "solver": {"morph_steps": args.morph_steps}},
                                base_dir=".")
    body = coarse.body(bmi=args.bmi)

    t = time.time()
    rc = coarse.simulate(body)
    coarse_s = time.time() - t
    start, worst = carry(np.asarray(fine.garment_vertices), np.asarray(coarse.garment_vertices),
                         np.asarray(coarse.garment_faces), np.asarray(rc["garment"]))
    t = time.time()
    rm = carried_scene.simulate(body, start_garment=start, start_body=body)
    fine_s = time.time() - t
    t = time.time()
    rt = fine.simulate(body)
    template_s = time.time() - t

    def row(r, s):
        return {"newton_iterations": r["iterations"], "seconds": round(s, 2), "settled": bool(r["converged"]),
                "stationarity": r["stationarity"], "p": r["penetration"]}
    print(json.dumps({
        "bmi": args.bmi,
        "carried_start_worst_rest_distance_m": worst,
        "coarse_drape": row(rc, coarse_s),
        "default_from_coarse": dict(row(rm, fine_s), start_shrink_m=rm["start_shrink"]),
        "default_from_template": row(rt, template_s),
    }, indent=1))


if __name__ == "__main__":
    main()
