"""scripts/ground_truth_spread.py: the simulation's spread under a body change far below any body's, and the
error floor it implies. Checked on a tiny scene (one settling step, penalty contact) so that it runs in seconds."""
import csv
import importlib.util

import h5py
import numpy as np
import pytest

import drape
from conftest import COARSE, SOURCE, penalty_scene, run_drape
from conftest import run_script as run_any_script

SCRIPT = SOURCE / "scripts" / "ground_truth_spread.py"
spec = importlib.util.spec_from_file_location("ground_truth_spread", SCRIPT)
spread = importlib.util.module_from_spec(spec)
spec.loader.exec_module(spread)


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("spread")
    scene = penalty_scene(tmp / "tiny.yaml")
    data = tmp / "data.h5"
    run_drape("generate", scene, "--count", 3, "--bmi", "20:40", "--seed", 5, "--out", data, "--threads", 1)
    return scene, data


def run_script(*args):
    return run_any_script(SCRIPT, *args)


def run_for_rows(out, *args):
    """The script run with --out out, which must succeed: its output and the per-body rows it wrote."""
    p = run_script(*args, "--out", out)
    assert p.returncode == 0, p.stderr
    return p, list(csv.DictReader(open(out)))


def test_picks_are_spread_evenly_over_bmi():
    done = np.array([1, 1, 1, 1, 1, 0], np.uint8)
    split = np.array([2, 2, 0, 2, 2, 2], np.int8)
    bmi = np.array([40.0, 10.0, 30.0, 20.0, 65.0, 50.0])
    # the finished test samples in BMI order are 1 (10), 3 (20), 0 (40), 4 (65); sample 5 is not done
    assert list(spread.pick_samples(done, split, bmi, "test", 2)) == [1, 4]
    assert list(spread.pick_samples(done, split, bmi, "test", 10)) == [1, 3, 0, 4]
    assert list(spread.pick_samples(done, split, bmi, "all", 5)) == [1, 3, 2, 0, 4]


def test_scaling_about_the_soles_keeps_the_soles_and_scales_heights():
    body = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 0.0], [-1.0, 1.0, 3.0]])
    out = spread.scaled_about_soles(body, 2.0)
    # centre: (0, 0, 1) -- the centroid's x and z at the soles' height
    assert np.allclose(out, [[0.0, 0.0, -1.0], [2.0, 4.0, -1.0], [-2.0, 2.0, 5.0]])


def test_the_same_body_twice_gives_the_same_drape_and_a_zero_floor(tiny, tmp_path):
    scene, data = tiny
    p, rows = run_for_rows(tmp_path / "rows.csv", "--data", data, "--scene", scene, "--split", "all", "--count", 2,
                           "--epsilon", 0, "--threads", 2)
    assert len(rows) == 2
    for r in rows:
        assert float(r["pair_me_cm"]) == 0.0  # the simulation is deterministic: same body, same drape
        assert np.isfinite(float(r["rerun_to_stored_cm"]))
    assert "| all | 2 | 0.000 | 0.000 |" in p.stdout, p.stdout


def test_a_scaled_body_and_the_model_column(tiny, tmp_path):
    scene, data = tiny
    model = SOURCE / "models" / "tshirt-coarse.h5"
    p, rows = run_for_rows(tmp_path / "rows.csv", "--data", data, "--scene", scene, "--count", 3, "--split", "all",
                           "--epsilon", 0.05, "--model", model, "--threads", 1)
    with h5py.File(data, "r", locking=False) as f:
        stored = f["garments/vertices"][:]
        bodies = f["bodies/vertices"][:]
    m = drape.Model.load(str(model))
    for r in rows:
        i = int(r["sample"])
        # a body 5 % larger drapes elsewhere; the pair distance and the floor say so
        assert float(r["pair_me_cm"]) > 0.0
        expected = 100 * np.linalg.norm(m.predict(bodies[i]) - stored[i], axis=1).mean()
        assert float(r["model_me_cm"]) == pytest.approx(expected, rel=1e-5)
    pairs = [float(r["pair_me_cm"]) for r in rows]
    line = next(l for l in p.stdout.splitlines() if l.startswith("| all |"))
    cells = [c.strip() for c in line.strip("|").split("|")]
    assert float(cells[2]) == pytest.approx(np.mean(pairs), abs=1e-3)
    assert float(cells[3]) == pytest.approx(np.mean(pairs) / 2, abs=1e-3)


def test_a_slim_shard_is_read_as_it_is_and_a_file_that_is_no_dataset_is_refused_by_name(tiny, tmp_path):
    scene, data = tiny
    slim = tmp_path / "slim.h5"
    run_drape("dataset", "slim", data, "--out", slim)
    full_rows, slim_rows = tmp_path / "full.csv", tmp_path / "slim.csv"
    for source, rows in ((data, full_rows), (slim, slim_rows)):
        p = run_script("--data", source, "--scene", scene, "--samples", "1", "--epsilon", 0, "--threads", 1, "--out", rows)
        assert p.returncode == 0, p.stderr
    # The slim shard's body is rebuilt from its parameters: the same drapes, to the rebuild's rounding.
    full, thin = next(csv.DictReader(open(full_rows))), next(csv.DictReader(open(slim_rows)))
    assert float(thin["pair_me_cm"]) == pytest.approx(float(full["pair_me_cm"]), abs=1e-3)
    bad = tmp_path / "bad.h5"
    with h5py.File(bad, "w") as f:
        f["split"] = np.zeros(2, np.int8)
    p = run_script("--data", bad, "--scene", COARSE)
    assert p.returncode != 0
    assert "bad.h5" in p.stderr and "Traceback" not in p.stderr


def test_named_samples_and_a_sample_the_file_does_not_have(tiny, tmp_path):
    scene, data = tiny
    out = tmp_path / "rows.csv"
    p = run_script("--data", data, "--scene", scene, "--samples", "2,0", "--epsilon", 0, "--threads", 1, "--out", out)
    assert p.returncode == 0, p.stderr
    assert [int(r["sample"]) for r in csv.DictReader(open(out))] == [2, 0]
    p = run_script("--data", data, "--scene", scene, "--samples", "0,3")
    assert p.returncode != 0 and "no finished sample 3 (the data has 3)" in p.stderr, p.stderr


@pytest.fixture(scope="module")
def tiny_posed(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("spread_posed")
    scene = penalty_scene(tmp / "tiny.yaml", morph_steps=2)
    data = tmp / "posed.h5"
    run_drape("generate", scene, "--count", 2, "--bmi", "20:30", "--seed", 3, "--poses", "draw", "--out", data,
              "--threads", 1)
    return scene, data


def test_a_posed_dataset_is_simulated_in_its_stored_poses(tiny_posed, tmp_path):
    # Each sample is draped again from its body at rest and its stored angles, as drape generate made it:
    # the new drape lands on the stored one (to the float rounding of the stored body and angles), where a
    # drape of the posed body taken as a rest body, or of the rest body unposed, would be centimetres away.
    scene, data = tiny_posed
    p, rows = run_for_rows(tmp_path / "rows.csv", "--data", data, "--scene", scene, "--split", "all", "--count", 2,
                           "--epsilon", 0, "--threads", 1)
    assert len(rows) == 2
    d = drape.Dataset(str(data))
    for r in rows:
        assert float(r["pair_me_cm"]) == 0.0
        assert float(r["rerun_to_stored_cm"]) < 0.2, r
        # the stored drape is posed: far from the same body's drape at rest
        i = int(r["sample"])
        assert np.abs(d[i]["pose"]).max() > 5.0  # degrees: the draw moved some joint


def test_stepped_angles_move_every_angle_by_the_step_both_ways_the_same_each_run():
    angles = {"a": 10.0, "b": -5.0, "c": 0.0}
    plus, minus = spread.stepped_angles(angles, 2.0, seed=7)
    for name, a in angles.items():
        assert abs(plus[name] - a) == 2.0 and minus[name] - a == -(plus[name] - a)
    assert spread.stepped_angles(angles, 2.0, seed=7) == (plus, minus)
    signs = [np.sign(spread.stepped_angles(angles, 1.0, seed=s)[0]["a"] - 10.0) for s in range(20)]
    assert 0 < signs.count(1.0) < 20  # the signs are drawn, not all one way


def test_off_neighbours_mean_is_zero_for_a_linear_change_and_the_offset_otherwise():
    at = np.zeros((4, 3))
    shift = np.tile([0.03, 0.0, 0.04], (4, 1))  # 5 cm
    assert spread.off_neighbours_mean_cm(at, at + shift, at - shift) == 0.0
    assert np.isclose(spread.off_neighbours_mean_cm(at, at + shift, at + shift), 5.0)
    assert np.isclose(spread.off_neighbours_mean_cm(at, at + 2 * shift, at), 5.0)


def test_pose_steps_drape_each_body_either_side_of_its_angles(tiny_posed, tmp_path):
    scene, data = tiny_posed
    p, rows = run_for_rows(tmp_path / "rows.csv", "--data", data, "--scene", scene, "--split", "all", "--count", 2,
                           "--pose-step", 2, "--threads", 1)
    assert "drapes at the angles +-2 degrees" in p.stdout
    assert len(rows) == 2
    for r in rows:
        assert float(r["pair_me_cm"]) > 0.01, r  # 4 degrees apart in every angle: the drape follows the pose
        assert float(r["off_neighbours_mean_cm"]) > 0.0, r
        assert float(r["rerun_to_stored_cm"]) < 0.2, r  # the drape at the angles is the stored one
    _, again = run_for_rows(tmp_path / "again.csv", "--data", data, "--scene", scene, "--split", "all", "--count", 2,
                            "--pose-step", 2, "--threads", 1)
    assert again == rows  # the same steps each run


def test_pose_steps_need_a_posed_dataset_and_a_small_step(tiny, tmp_path):
    scene, data = tiny
    p = run_script("--data", data, "--scene", scene, "--count", 1, "--pose-step", 1)
    assert p.returncode != 0 and "--pose-step needs a posed dataset" in p.stderr, p.stderr
    p = run_script("--data", data, "--scene", scene, "--pose-step", 20)
    assert p.returncode != 0 and "--pose-step must be in [0, 10] degrees" in p.stderr, p.stderr
