#!/usr/bin/env python3
"""Where a model's error lies on a dataset: by region of the garment, how much of it is a shift or a turn of the
whole garment, and what it follows in the body (docs/poses.md, "What holds the posed model's error").

    PYTHONPATH=build/python python3 scripts/model_error_breakdown.py --data 'datasets/posespace2000/shard-*-of-40.h5' \\
        --model models/tshirt-coarse-posed.h5 [--split test|train|val|all]

Prints the ME (mean vertex distance, cm) over the split's bodies, and:
- by region of the template garment (dressed on the mean body): the sleeves (|x| > 0.19 m), the lower 35 % of the
  rest (the hem) and the upper torso, each with its share of the total error;
- the mean offset of each predicted garment from the simulated one (a shift of the whole garment), and the ME left
  after removing it, then after the best rigid fit (Kabsch) of each prediction onto its drape;
- by frequency over the garment's mesh (--modes K,...): each error split into its smooth part, spanned by the K
  smoothest eigenvectors of the garment's Laplacian (the template assets' spectral basis, the one the network's
  spectral branch uses: orthonormal, ascending, the constant first), and the rest; beside it, how far each simulated drape lies from its own smooth part, which is as close
  as a predictor that got only the K smoothest modes right could come (the folds it would leave out);
- how far the prediction stands off the body: the error along each simulated drape's outward vertex normal (mean,
  signed: negative where the prediction lies outside the drape), and for the simulated vertices by their distance
  from the body (nearest body vertex, bands in cm) how much farther from the body the predicted ones lie; a model
  that trades distance for a drape kept outside the body shows it here;
- the correlation over bodies of each body's ME with its BMI and, for a posed dataset, with the size of each angle.
Running it on the training split beside the test split tells underfitting (both high) from overfitting.
A posed sample is predicted from its body at rest and its stored angles, as drape eval does.
"""
import argparse
import sys

import numpy as np


def rigid_fit(a, b):
    """a moved by the rotation and translation that bring it closest to b (least squares, no reflection)."""
    ca, cb = a.mean(0), b.mean(0)
    u, _, vt = np.linalg.svd((a - ca).T @ (b - cb))
    d = np.sign(np.linalg.det(u @ vt))
    r = u @ np.diag([1.0, 1.0, d]) @ vt
    return (a - ca) @ r + cb


def vertex_normals(x, faces):
    """Area-weighted vertex normals of the mesh x [n, 3] (outward for drape's garments, faces counter-clockwise)."""
    n = np.zeros_like(x)
    f = np.cross(x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]])
    for c in range(3):
        np.add.at(n, faces[:, c], f)
    return n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)


def stand_off(P, G, bodies, faces, bands=(0, 0.5, 1, 2, 4, 1000)):
    """Prints the signed error along the simulated drape's normals and, by the simulated vertex's distance from the
    body, how much farther from the body the predicted vertex lies (both in cm, means over bodies and vertices)."""
    from scipy.spatial import cKDTree
    along, sim_d, pred_d = [], [], []
    for k in range(len(P)):
        n = vertex_normals(G[k], faces)
        along.append(((P[k] - G[k]) * n).sum(1))
        tree = cKDTree(bodies[k])
        sim_d.append(tree.query(G[k])[0])
        pred_d.append(tree.query(P[k])[0])
    along, sim_d, pred_d = (np.concatenate(a) * 100 for a in (along, sim_d, pred_d))
    print(f"  the error along the simulated drape's outward normal: mean {along.mean():+.3f} cm "
          f"(positive: the prediction stands outside the drape), mean |.| {np.abs(along).mean():.3f} cm")
    for lo, hi in zip(bands[:-1], bands[1:]):
        m = (sim_d >= lo) & (sim_d < hi)
        if m.any():
            print(f"    simulated vertices {lo:g}-{hi:g} cm from the body ({100 * m.mean():.0f} %): the predicted ones "
                  f"{(pred_d[m] - sim_d[m]).mean():+.3f} cm farther, along the normal {along[m].mean():+.3f} cm")


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--data", required=True, help="a dataset file or a quoted glob of shards")
    p.add_argument("--model", required=True)
    p.add_argument("--split", default="test", choices=["train", "val", "test", "all"])
    p.add_argument("--modes", default="25,100,300", help="comma-separated counts of smoothest Laplacian modes")
    args = p.parse_args(argv)
    import drape

    data = drape.Dataset(args.data)
    idx = [int(i) for i in (data.indices() if args.split == "all" else data.indices(args.split))]
    if not idx:
        raise SystemExit(f"{args.data}: no done samples in the {args.split} split")
    model = drape.Model.load(args.model)
    batch = data.read(idx)
    posed = "pose" in batch
    names = list(data.layout["pose_angles"]) if posed else []
    bodies = data.posing(idx)["unposed"] if posed else batch["body"]
    # Each body in the garment it was simulated in (drape eval feeds the same
    # grade): a model of sizes would otherwise choose its size by the tailor's rule.
    try:
        grades = data.stat("garment_grade", idx)
    except drape.ConfigError:  # a dataset of one garment has no grade statistic
        grades = None
    predicted = []
    for k in range(len(idx)):
        options = {"pose": {n: float(a) for n, a in zip(names, batch["pose"][k])}} if posed else {}
        if grades is not None and "garment_grade" in model.inputs:
            options["garment_size"] = float(grades[k])
        predicted.append(model.predict(bodies[k], check=False, **options))
    P = np.asarray(predicted, np.float64)
    G = batch["garment"].astype(np.float64)
    E = np.linalg.norm(P - G, axis=2) * 100  # cm, [bodies, vertices]

    # The regions are cut on the template dressed on the mean body: the coarse
    # T-shirt's, or the default one's, whichever has the dataset's vertex count.
    t = assets = None
    for resolution in ("coarse", "default"):
        assets = drape.assets(resolution=resolution)
        t = np.asarray(assets.garment_vertices)
        if len(t) == P.shape[1]:
            break
    if len(t) != P.shape[1]:
        raise SystemExit(f"{args.data}: garments of {P.shape[1]} vertices are neither T-shirt template's")
    sleeves = np.abs(t[:, 0]) > 0.19
    low = t[:, 1].min() + 0.35 * (t[:, 1].max() - t[:, 1].min())
    hem = ~sleeves & (t[:, 1] < low)
    upper = ~sleeves & ~hem
    print(f"{len(idx)} bodies ({args.split}) of {args.data}, model {args.model}: ME {E.mean():.3f} cm")
    for name, m in (("sleeves", sleeves), ("hem (lower 35 %)", hem), ("upper torso", upper)):
        print(f"  {name:<17} {m.sum():5d} vertices  ME {E[:, m].mean():.3f} cm  {100 * E[:, m].sum() / E.sum():.0f} % of the error")
    shift = (P - G).mean(1)
    print(f"  the whole garment's shift: mean {np.linalg.norm(shift, axis=1).mean() * 100:.3f} cm; "
          f"ME without it {np.linalg.norm(P - shift[:, None] - G, axis=2).mean() * 100:.3f} cm, "
          f"after the best rigid fit {np.mean([np.linalg.norm(rigid_fit(P[k], G[k]) - G[k], axis=1).mean() for k in range(len(P))]) * 100:.3f} cm")
    basis = np.asarray(assets.eigenvectors, np.float64)
    for k in sorted(int(m) for m in args.modes.split(",")):
        if k > basis.shape[1]:
            print(f"  {k:4d} smoothest modes: the assets hold {basis.shape[1]}; left out")
            continue
        U = basis[:, :k]
        smooth = lambda X: np.einsum("vk,nkc->nvc", U, np.einsum("vk,nvc->nkc", U, X))  # noqa: E731
        err_smooth = smooth(P - G)
        folds = G - smooth(G)
        print(f"  {k:4d} smoothest modes: the error's smooth part {np.linalg.norm(err_smooth, axis=2).mean() * 100:.3f} cm, "
              f"the rest {np.linalg.norm(P - G - err_smooth, axis=2).mean() * 100:.3f} cm; "
              f"the drapes beyond them (a predictor right in them only) {np.linalg.norm(folds, axis=2).mean() * 100:.3f} cm")
    stand_off(P, G, np.asarray(batch["body"], np.float64), np.asarray(data.faces))
    per_body = E.mean(1)
    bmi = data.stat("bmi", idx)
    print(f"  correlation of a body's ME with its BMI {np.corrcoef(bmi, per_body)[0, 1]:+.2f}")
    for j, name in enumerate(names):
        a = np.abs(batch["pose"][:, j])
        if a.std() > 0:
            print(f"    with |{name}| {np.corrcoef(a, per_body)[0, 1]:+.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
