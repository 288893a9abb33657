#!/usr/bin/env python3
"""A model of posed drapes given each body of a posed dataset twice: at rest with its stored joint angles
(`Model.predict(rest, pose=...)`), and as its posed mesh alone, the pose read off it (`Model.predict(posed)`,
docs/poses.md, "A body given posed"). Prints the ME of both against the simulated drapes, how far the two
predictions lie apart, and the time a posed mesh takes; a line for each body whose two drapes lie over 1 mm apart.

    PYTHONPATH=build/python /usr/bin/python3 scripts/posed_mesh_eval.py \\
        --data datasets/posespace-human-heldout/seed2-50.h5 [--model models/tshirt-coarse-posed-human.h5] [--samples N]
"""
import argparse
import time
import warnings

import numpy as np

import drape


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", required=True, help="a posed dataset (its samples store their joint angles)")
    parser.add_argument("--model", default="models/tshirt-coarse-posed-human.h5", help="a model of posed drapes")
    parser.add_argument("--samples", type=int, default=0, help="the first N samples (0: all)")
    args = parser.parse_args()

    data = drape.Dataset(args.data)
    names = data.layout["pose_angles"]
    if not names:
        parser.error(f"{args.data} holds A-pose drapes (no joint angles): give a posed dataset")
    model = drape.Model.load(args.model)
    if not model.takes_pose:
        parser.error(f"{args.model} drapes the A-pose only: give a model of posed drapes")
    count = len(data) if args.samples <= 0 else min(args.samples, len(data))
    me_pose, me_mesh, apart, seconds = [], [], [], []
    for i in range(count):
        sample = data[i]
        rest = np.asarray(data.posing([i])["unposed"][0], dtype=np.float32)
        pose = {name: float(v) for name, v in zip(names, sample["pose"])}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the size and domain notes, said alike for both
            from_pose = model.predict(rest, pose=pose)
            start = time.perf_counter()
            from_mesh = model.predict(np.asarray(sample["body"], dtype=np.float32))
            seconds.append(time.perf_counter() - start)
        truth = np.asarray(sample["garment"])
        me_pose.append(np.linalg.norm(from_pose - truth, axis=1).mean() * 100)
        me_mesh.append(np.linalg.norm(from_mesh - truth, axis=1).mean() * 100)
        apart.append(np.linalg.norm(from_mesh - from_pose, axis=1).max() * 1000)
        if apart[-1] > 1:
            print(f"sample {i}: the two drapes {apart[-1]:.2f} mm apart at most", flush=True)
    print(f"{count} bodies of {args.data}: ME {np.mean(me_pose):.3f} cm given at rest with the pose, "
          f"{np.mean(me_mesh):.3f} cm given posed (the pose read off the mesh); the two drapes apart by "
          f"{np.median(apart):.3f} mm (median of the largest), {np.max(apart):.3f} mm at most; "
          f"a posed mesh {np.median(seconds):.2f} s (median)")


if __name__ == "__main__":
    main()
