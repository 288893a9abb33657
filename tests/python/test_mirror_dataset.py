"""scripts/mirror_dataset.py: a posed drape mirrored left for right. Checked from outside the script: the body
model's own bodies in a pose and in its mirror (drape body), the surface distances by brute force
(scripts/reference/closest_point.py), a symmetric mesh whose mirror is known by construction, and a shipped
shard mirrored twice."""
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import SOURCE, run_drape, run_script

sys.path.insert(0, str(SOURCE / "scripts"))
import mirror_dataset  # noqa: E402

from closest_point import closest_points  # scripts/reference, numpy only  # noqa: E402

SHARD = SOURCE / "datasets" / "posespace2000-human" / "shard-00-of-40.h5"
REFLECT = np.array([-1.0, 1.0, 1.0])


def read_obj(path):
    v, f = [], []
    for line in open(path):
        if line.startswith("v "):
            v.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            f.append([int(x.split("/")[0]) - 1 for x in line.split()[1:4]])
    return np.array(v), np.array(f)


def mirror(*args):
    p = run_script(SOURCE / "scripts" / "mirror_dataset.py", *args)
    assert p.returncode == 0, p.stderr
    return p.stdout


def pose_arg(names, values):
    return ",".join(f"{n}={v:g}" for n, v in zip(names, values))


def test_a_body_in_the_mirrored_pose_is_the_reflected_body(tmp_path):
    with h5py.File(SHARD, "r") as f:
        names = f.attrs["pose_angles"].decode().split(",")
    # Every angle away from zero, the two sides different (a drawn pose the body accepts).
    pose = {"spine_flexion": 10, "spine_bend": 10, "spine_twist": 15, "neck_flexion": 5, "neck_bend": 6, "neck_twist": 10,
            "left_shoulder_abduction": 60, "right_shoulder_abduction": 40, "left_shoulder_flexion": 20,
            "right_shoulder_flexion": -10, "left_shoulder_rotation": 30, "right_shoulder_rotation": -10,
            "left_elbow_flexion": 40, "right_elbow_flexion": 10, "left_hip_flexion": 15, "right_hip_flexion": -5,
            "left_hip_abduction": 8, "right_hip_abduction": 3, "left_hip_rotation": 10, "right_hip_rotation": -5,
            "left_knee_flexion": 20, "right_knee_flexion": 5}
    values = np.array([[pose[n] for n in names]], np.float64)
    mirrored = mirror_dataset.mirror_angles(values, names)[0]
    assert mirrored[names.index("right_shoulder_abduction")] == 60 and mirrored[names.index("spine_twist")] == -15
    # The wrong map (sides swapped, nothing negated): what the test must tell apart.
    swapped_only = np.array([values[0][src] for src, _ in mirror_dataset.mirrored_angle_map(names)])
    bodies = {}
    for name, angles in (("pose", values[0]), ("mirror", mirrored), ("swapped", swapped_only)):
        out = tmp_path / f"{name}.obj"
        run_drape("body", "--bmi", "30", "--param", "rig=human", "--pose", pose_arg(names, angles), "--out", out)
        bodies[name] = read_obj(out)
    posed, faces = bodies["pose"]
    rng = np.random.default_rng(0)
    picked = rng.choice(len(posed), 300, replace=False)
    reflected = posed[picked] * REFLECT
    _, _, to_mirror = closest_points(bodies["mirror"][0], faces, reflected)
    _, _, to_swapped = closest_points(bodies["swapped"][0], faces, reflected)
    # The rest body's own asymmetry is about 1.4 mm at the 99th percentile (its mesh is not symmetric).
    assert np.percentile(to_mirror, 99) < 3e-3 and to_mirror.max() < 5e-3
    assert to_swapped.max() > 2e-2


def test_on_a_symmetric_mesh_the_mirror_is_the_mirror_vertex():
    # A grid symmetric about x = 0, its vertices shuffled: each vertex's mirror image is a vertex.
    xs, ys = np.linspace(-0.3, 0.3, 7), np.linspace(0.0, 0.5, 6)
    grid = np.array([[x, y, 0.05 * np.cos(5 * x) + 0.02 * y] for y in ys for x in xs])
    faces = []
    for j in range(len(ys) - 1):
        for i in range(len(xs) - 1):
            a, b, c, d = j * 7 + i, j * 7 + i + 1, (j + 1) * 7 + i, (j + 1) * 7 + i + 1
            faces += [[a, b, d], [a, d, c]]
    rng = np.random.default_rng(1)
    order = rng.permutation(len(grid))
    where = np.argsort(order)
    template, faces = grid[order], where[np.array(faces)]
    corners, weights, dist = mirror_dataset.garment_mirror(template, faces)
    assert dist.max() < 1e-12
    # The mirror vertex of template[k]: the grid point with x negated.
    expected = np.array([where[(order[k] // 7) * 7 + (6 - order[k] % 7)] for k in range(len(grid))])
    picked = corners[np.arange(len(grid)), weights.argmax(axis=1)]
    assert np.array_equal(picked, expected) and np.allclose(weights.max(axis=1), 1.0)
    drapes = template[None] + rng.normal(scale=0.01, size=(3,) + template.shape)
    mirrored = mirror_dataset.mirror_garments(drapes, corners, weights)
    assert np.allclose(mirrored, drapes[:, expected, :] * REFLECT, atol=1e-12)


def test_a_shard_mirrored_and_mirrored_again(tmp_path):
    once, twice, train = tmp_path / "once.h5", tmp_path / "twice.h5", tmp_path / "train.h5"
    assert "50 mirrored samples" in mirror(SHARD, "--split", "all", "--out", once)
    mirror(once, "--split", "all", "--out", twice)
    mirror(SHARD, "--out", train)
    with h5py.File(SHARD, "r") as src, h5py.File(once, "r") as a, h5py.File(twice, "r") as b, h5py.File(train, "r") as t:
        names = src.attrs["pose_angles"].decode().split(",")
        pose, mirrored = src["bodies/pose"][()], a["bodies/pose"][()]
        for k, name in enumerate(names):
            other = name.replace("left_", "@").replace("right_", "left_").replace("@", "right_")
            sign = -1 if name in ("spine_bend", "spine_twist", "neck_bend", "neck_twist") else 1
            assert np.array_equal(mirrored[:, k], sign * pose[:, names.index(other)]), name
        assert np.array_equal(b["bodies/pose"][()], pose)
        assert np.array_equal(a["bodies/params"][()], src["bodies/params"][()])
        assert np.array_equal(a["stats/garment_grade"][()], src["stats/garment_grade"][()])
        assert (a["split"][()] == 0).all() and "bodies/witness" not in a and "bodies/vertices" not in a
        assert t["done"].shape[0] == int((src["split"][()] == 0).sum()) < 50
        # Twice mirrored is the drape again, up to the interpolation on the template (two smoothings).
        g, gg = src["garments/vertices"][()].astype(float), b["garments/vertices"][()].astype(float)
        per_drape = np.linalg.norm(gg - g, axis=2).mean(axis=1)
        assert per_drape.max() < 6e-3 and np.median(per_drape) < 4e-3
        # Once mirrored is not the drape: the sides differ.
        assert np.linalg.norm(a["garments/vertices"][()] - g, axis=2).mean() > 1e-2
    # A slim dataset drape reads and expands (the bodies rebuilt from the mirrored angles).
    stdout, _ = run_drape("dataset", "expand", "--force", "--out", tmp_path / "full.h5", once)
    assert "50 samples" in stdout


def test_an_angle_without_its_mirror_is_refused():
    with pytest.raises(SystemExit, match="left_wrist_flexion has no mirror"):
        mirror_dataset.mirrored_angle_map(["spine_twist", "left_wrist_flexion"])
