#!/usr/bin/env python3
"""Mirror a posed dataset's drapes left for right: a drape on a body in pose
a, reflected through the body's plane of symmetry (x = 0), is a drape on the
same body in the mirrored pose. Doubles the training drapes of a pose space
for no simulation (docs/poses.md, "Mirrored drapes").

    PYTHONPATH=build/python python3 scripts/mirror_dataset.py SHARD.h5 [...] --out MIRRORED.h5 [--split train]

The output is a slim dataset (bodies rebuilt from their parameters and the
mirrored angles by the body model, as every slim shard's are) holding the
mirror of each sample of the chosen split, all in the training split: a
mirrored test drape is its original's twin and must not be trained on.

The mirror of each part:
  - the angles: left and right swapped, and the spine's and the neck's
    lateral bend and twist negated (the parametric body's rig: checked by
    tests/python/test_mirror_dataset.py, a body in the mirrored pose lies on
    the reflected body to within the rest body's own asymmetry);
  - the body: rebuilt by the body model from the same shape parameters (the
    rest body is symmetric: its reflection lies within 1.4 mm of its
    surface at the 99th percentile);
  - the garment: the T-shirt's mesh is not symmetric (its panels are meshed
    one by one), so each vertex of the mirrored drape is the reflection of
    the drape's point at the vertex's mirror image on the template of the
    sample's size, dressed on the mean body of the dataset's scene (the
    closest point of the reflected vertex on that template's surface, as a
    face and barycentric weights; the template's own asymmetry, 0.6 mm at
    the median and 3.1 mm at the 99th percentile for the regular size on
    the human rig, is what this adds to the label).

Written without the witness of its bodies (docs/formats.md): the witness
records the bodies a drape was simulated on, and these were not simulated.
"""
import argparse
import os
import sys

import h5py
import numpy as np
import yaml

REFLECT = np.array([-1.0, 1.0, 1.0])
NEGATED = {"spine_bend", "spine_twist", "neck_bend", "neck_twist"}
SIZE_NAMES = ["regular", "small", "large", "xlarge", "2xlarge", "3xlarge", "4xlarge", "5xlarge", "6xlarge",
              "xsmall", "2xsmall", "3xsmall"]
SPLITS = {"train": 0, "val": 1, "test": 2}


def mirrored_angle_map(names):
    """(source column, sign) of each mirrored angle."""
    out = []
    for name in names:
        if name.startswith("left_"):
            other = "right_" + name[len("left_"):]
        elif name.startswith("right_"):
            other = "left_" + name[len("right_"):]
        else:
            other = name
        if other not in names:
            sys.exit(f"mirror_dataset: angle {name} has no mirror {other} among the dataset's pose_angles")
        out.append((names.index(other), -1.0 if name in NEGATED else 1.0))
    return out


def mirror_angles(pose, names):
    m = mirrored_angle_map(names)
    return np.stack([sign * pose[:, src] for src, sign in m], axis=1).astype(pose.dtype)


def garment_mirror(template, faces):
    """(corner vertices [N, 3], weights [N, 3], distance [N]): where each vertex's mirror image lies on the template."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference"))
    from closest_point import closest_points  # numpy, every face
    face, weights, dist = closest_points(template, faces, template * REFLECT)
    return faces[face], weights, dist


def mirror_garments(garments, corners, weights):
    return ((garments[:, corners, :] * weights[None, :, :, None]).sum(axis=2) * REFLECT).astype(garments.dtype)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("data", nargs="+", help="posed dataset files (slim or whole)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--split", default="train", choices=list(SPLITS) + ["all"],
                    help="the samples mirrored (default train: never a test or validation drape's twin)")
    args = ap.parse_args()
    import drape

    maps = {}
    parts = {k: [] for k in ("params", "pose", "garments", "stats", "sizes")}
    first = None
    for path in args.data:
        with h5py.File(path, "r") as f:
            if first is None:
                first = {k: f.attrs[k] for k in f.attrs}
                scene = yaml.safe_load(first["scene"].decode() if isinstance(first["scene"], bytes) else first["scene"])
                body, garment = scene.get("body") or {}, scene.get("garment") or {}
                faces = f["garments/faces"][()]
                omitted = f.attrs.get("body_vertices_omitted")
                body_vertices = int(omitted) if omitted is not None else f["bodies/vertices"].shape[1]
            names = f.attrs["pose_angles"].decode().split(",") if isinstance(f.attrs["pose_angles"], bytes) \
                else str(f.attrs["pose_angles"]).split(",")
            keep = f["done"][()].astype(bool)
            if args.split != "all":
                keep &= f["split"][()] == SPLITS[args.split]
            idx = np.nonzero(keep)[0]
            if len(idx) == 0:
                continue
            parts["params"].append(f["bodies/params"][idx])
            parts["pose"].append(mirror_angles(f["bodies/pose"][idx], names))
            sizes = f["stats/garment_size"][idx].astype(int) if "stats/garment_size" in f else np.zeros(len(idx), int)
            g = f["garments/vertices"][idx]
            out = np.empty_like(g)
            for s in np.unique(sizes):
                if s not in maps:
                    # The template of that size dressed on the scene's mean body (its garment and body
                    # model's parameters); the eigenbasis is not needed.
                    a = drape.assets(garment=garment.get("template", "tshirt"),
                                     garment_params={**garment.get("params", {}), "size": SIZE_NAMES[s]},
                                     body_model=body.get("model", "parametric"), body_params=body.get("params", {}),
                                     eigen_k=1, levels=1)
                    tmpl = np.asarray(a.garment_vertices, float)
                    if tmpl.shape[0] != g.shape[1]:
                        sys.exit(f"mirror_dataset: the {SIZE_NAMES[s]} template has {tmpl.shape[0]} vertices, "
                                 f"{path}'s garments {g.shape[1]}")
                    corners, weights, dist = garment_mirror(tmpl, np.asarray(a.garment_faces))
                    maps[s] = (corners, weights)
                    print(f"{SIZE_NAMES[s]}: the template's mirror image lies {1e3 * np.median(dist):.2f} mm "
                          f"(99 %: {1e3 * np.percentile(dist, 99):.2f}, most {1e3 * dist.max():.2f}) off its surface")
                sel = sizes == s
                out[sel] = mirror_garments(g[sel], *maps[s])
            parts["garments"].append(out)
            parts["stats"].append({k: f["stats/" + k][idx] for k in f["stats"]})
    if not parts["params"]:
        sys.exit("mirror_dataset: no sample of the split asked for")
    n = sum(len(p) for p in parts["params"])
    tmp = args.out + ".partial"
    with h5py.File(tmp, "w") as o:
        for k, v in first.items():
            if k != "merged_from":
                o.attrs[k] = v
        o.attrs["body_vertices_omitted"] = np.bytes_(str(body_vertices))
        o.attrs["mirrored_from"] = np.bytes_("\n".join(os.path.basename(p) for p in args.data))
        o.attrs["mirrored"] = np.bytes_(
            "each sample the mirror of a " + args.split + " sample of mirrored_from (scripts/mirror_dataset.py): "
            "angles left for right, bend and twist negated, the garment reflected through x = 0 onto the "
            "template's vertices; no witness: these bodies were not simulated")
        o["bodies/params"] = np.concatenate(parts["params"])
        o["bodies/pose"] = np.concatenate(parts["pose"])
        o["done"] = np.ones(n, np.uint8)
        o["garments/faces"] = faces
        o["garments/vertices"] = np.concatenate(parts["garments"])
        o["split"] = np.zeros(n, np.int8)
        for k in parts["stats"][0]:
            o["stats/" + k] = np.concatenate([s[k] for s in parts["stats"]])
    os.replace(tmp, args.out)
    print(f"wrote {args.out}: {n} mirrored samples")


if __name__ == "__main__":
    main()
