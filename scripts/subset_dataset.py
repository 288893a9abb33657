#!/usr/bin/env python3
"""Copy the samples of some datasets that lie in a range of BMI (and a
split) into one dataset of the same layout: a training set that holds a
region of the body space twice, to measure whether a region's share of the
drapes is what holds its error (issue 56: "data per region of the body
space"; docs/poses.md, "Heavy bodies twice").

    PYTHONPATH=build/python python3 scripts/subset_dataset.py SHARD.h5 [...] --bmi 45:65 --split train --out HEAVY.h5

Slim shards give a slim subset (`drape dataset expand` rebuilds its bodies,
as it does every slim shard's). Every per-sample dataset (bodies, garments,
done, split, stats) is indexed; the rest (the garment's faces) and the
file attributes are taken from the first file, whose scene, size chart and
layout every other file must share (`drape dataset expand` checks that
again when the subset is joined to them). Written atomically.
"""
import argparse
import os
import sys

import h5py
import numpy as np

SPLITS = {"train": 0, "val": 1, "test": 2}


def per_sample_datasets(f, n):
    """Paths of the datasets whose first axis is the sample count."""
    out = []

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.ndim >= 1 and obj.shape[0] == n and name != "garments/faces":
            out.append(name)

    f.visititems(visit)
    return sorted(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("data", nargs="+", help="dataset files (slim or whole) of one scene")
    ap.add_argument("--bmi", required=True, help="LO:HI, the BMI range kept (LO <= bmi < HI)")
    ap.add_argument("--split", default="train", choices=list(SPLITS) + ["all"],
                    help="the samples kept (default train: a test drape must not be trained on)")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    try:
        lo, hi = (float(v) for v in args.bmi.split(":"))
    except ValueError:
        sys.exit(f"subset_dataset: --bmi must be LO:HI, got {args.bmi!r}")
    if not lo < hi:
        sys.exit(f"subset_dataset: --bmi {args.bmi}: LO must be below HI")

    first = None
    parts = {}
    faces = None
    for path in args.data:
        with h5py.File(path, "r") as f:
            n = f["done"].shape[0]
            names = per_sample_datasets(f, n)
            if first is None:
                first = ({k: f.attrs[k] for k in f.attrs}, names, path)
                faces = f["garments/faces"][()]
            elif f.attrs["scene"] != first[0]["scene"]:
                sys.exit(f"subset_dataset: {path} was made in another scene than {first[2]}")
            elif names != first[1]:
                only_here, only_first = sorted(set(names) - set(first[1])), sorted(set(first[1]) - set(names))
                sys.exit(f"subset_dataset: {path} and {first[2]} differ in layout: only in the first "
                         f"{only_here or 'nothing'}, only in the second {only_first or 'nothing'}")
            keep = f["done"][()].astype(bool)
            bmi = f["stats/bmi"][()]
            keep &= (bmi >= lo) & (bmi < hi)
            if args.split != "all":
                keep &= f["split"][()] == SPLITS[args.split]
            idx = np.nonzero(keep)[0]
            for name in names:
                parts.setdefault(name, []).append(f[name][idx] if len(idx) else f[name][()][:0])
    total = sum(len(p) for p in parts["done"])
    if total == 0:
        sys.exit(f"subset_dataset: no {args.split} sample with BMI in [{lo}, {hi})")
    tmp = args.out + ".partial"
    with h5py.File(tmp, "w") as o:
        for k, v in first[0].items():
            if k != "merged_from":
                o.attrs[k] = v
        o.attrs["subset_of"] = np.bytes_("\n".join(os.path.basename(p) for p in args.data))
        o.attrs["subset"] = np.bytes_(f"the {args.split} samples with BMI in [{lo:g}, {hi:g}) (scripts/subset_dataset.py)")
        for name, chunks in parts.items():
            o[name] = np.concatenate(chunks)
        o["garments/faces"] = faces
    os.replace(tmp, args.out)
    print(f"wrote {args.out}: {total} samples ({args.split}, BMI {lo:g}-{hi:g}) of {len(args.data)} files")


if __name__ == "__main__":
    main()
