"""drape.Dataset against the same file read with h5py (the layout of docs/formats.md)."""
import shutil

import h5py
import numpy as np
import pytest

import drape
from conftest import SOURCE, run_drape


@pytest.fixture(scope="module")
def dataset(tmp_path_factory, request):
    tmp = tmp_path_factory.mktemp("data")
    scene = request.getfixturevalue("module_tiny_scene")
    out = tmp / "data.h5"
    run_drape("generate", scene, "--count", 4, "--bmi", "20:30", "--seed", 3, "--out", out, "--threads", 2)
    return out


@pytest.fixture(scope="module")
def module_tiny_scene(tmp_path_factory):
    from conftest import COARSE
    path = tmp_path_factory.mktemp("scene") / "tiny.yaml"
    path.write_text(f"base: {COARSE}\neffects: {{barrier: null}}\n"
                    "solver: {morph_steps: 0, settle_steps: 1, max_newton_iterations: 8, linear_solver: eigen}\n")
    return path


def test_read_matches_h5py(dataset):
    d = drape.Dataset(str(dataset))
    assert len(d) == d.size == 4
    layout = d.layout
    with h5py.File(dataset, "r") as f:
        split = np.asarray(f["split"])
        for name in ("train", "val", "test"):
            code = {"train": 0, "val": 1, "test": 2}[name]
            np.testing.assert_array_equal(d.indices(name), np.flatnonzero(split == code))
        np.testing.assert_array_equal(d.indices(), np.arange(4))
        idx = np.array([3, 1])
        batch = d.read(idx)
        np.testing.assert_array_equal(batch["indices"], idx)
        np.testing.assert_array_equal(batch["body"], np.asarray(f["bodies/vertices"])[idx])
        np.testing.assert_array_equal(batch["garment"], np.asarray(f["garments/vertices"])[idx])
        np.testing.assert_array_equal(batch["body_params"], np.asarray(f["bodies/params"])[idx])
        np.testing.assert_array_equal(batch["split"], split[idx])
        assert batch["body"].shape == (2, layout["body_vertices"], 3) and batch["body"].dtype == np.float32
        for stat in layout["stats"][:3]:
            np.testing.assert_array_equal(d.stat(stat, idx), np.asarray(f["stats"][stat])[idx])
    assert "tshirt" in layout["scene"] and layout["garment_vertices"] == batch["garment"].shape[1]


def test_bad_indices_and_files(dataset, tmp_path):
    d = drape.Dataset(str(dataset))
    with pytest.raises(ValueError, match=r"indices: sample 4 is not a done sample of this dataset \(it has 4\)"):
        d.read(np.array([0, 4]))
    with pytest.raises(ValueError, match=r"indices: expected an integer array"):
        d.read(np.array([0.5]))
    # An empty list (NumPy makes it float) reads no samples.
    empty = d.read([])
    assert empty["garment"].shape[0] == 0 and empty["indices"].shape == (0,)
    with pytest.raises(drape.ConfigError, match="split"):
        d.indices("tset")
    with pytest.raises(drape.Error, match="missing.h5"):
        drape.Dataset(str(tmp_path / "missing.h5"))


def test_dataset_potential_refuses_a_nan_garment_naming_the_sample(dataset, module_tiny_scene, tmp_path):
    # A NaN in a file whose checksum was zeroed (an h5py edit) crashed `dataset potential` (issue 58).
    # A copy of the module's dataset: any finished dataset of the scene will do (it used to generate its own).
    data = tmp_path / "d.h5"
    shutil.copyfile(dataset, data)
    with h5py.File(data, "r+") as f:
        g = f["garments/vertices"]
        sample = g[1]
        sample[5, 1] = np.nan
        g[1] = sample
    raw = bytearray(data.read_bytes())
    raw[:512] = bytes(512)  # unsealed, as h5py leaves a file it wrote
    data.write_bytes(bytes(raw))
    _, err = run_drape("dataset", "potential", data, "--scene", module_tiny_scene, "--split", "all", expect=2)
    assert "sample 1 has a non-finite garment coordinate" in err and len(err.strip().splitlines()) == 1


def test_eval_names_the_file_of_a_nan_garment_and_a_split_code_the_format_lacks(dataset, tmp_path):
    """h5py edits (unsealed): a NaN drape was "metrics: the ground truth has a non-finite coordinate" (exit 1, no
    file named), and split code 7 put the sample in no split ("the all split has no samples")."""
    def edited(name, edit):
        data = tmp_path / name
        shutil.copyfile(dataset, data)
        with h5py.File(data, "r+") as f:
            edit(f)
        raw = bytearray(data.read_bytes())
        raw[:512] = bytes(512)
        data.write_bytes(bytes(raw))
        return data

    def nan_garment(f):
        sample = f["garments/vertices"][2]
        sample[0, 0] = np.nan
        f["garments/vertices"][2] = sample

    def split_seven(f):
        split = f["split"][...]
        split[1] = 7
        f["split"][...] = split

    model = SOURCE / "models" / "tshirt-coarse.h5"
    _, err = run_drape("eval", "--model", model, "--data", edited("nan.h5", nan_garment), "--split", "all", expect=2)
    assert "nan.h5: sample 2 has a non-finite garment coordinate" in err
    _, err = run_drape("eval", "--model", model, "--data", edited("seven.h5", split_seven), "--split", "all", expect=2)
    assert "seven.h5: sample 1 has split code 7 in /split (0 train, 1 val, 2 test)" in err
    with pytest.raises(drape.Error, match="sample 1 has split code 7"):
        drape.Dataset(str(tmp_path / "seven.h5"))

    # A vertex a flipped exponent sent past 1e30, and a row of zeros marked done (never written): taken until an
    # outside check (a training loss of 1e27; an ME five times the others').
    def far_vertex(f):
        sample = f["garments/vertices"][1]
        sample[5, 1] = 1e30
        f["garments/vertices"][1] = sample

    def unwritten_row(f):
        f["garments/vertices"][3] = np.zeros_like(f["garments/vertices"][3])

    def garbage_scene(f):
        f.attrs["scene"] = "{unclosed: [1, 2"

    _, err = run_drape("eval", "--model", model, "--data", edited("far.h5", far_vertex), "--split", "all", expect=2)
    assert "far.h5: sample 1 has a garment coordinate of 1e+30 m, beyond a thousand kilometres" in err
    _, err = run_drape("eval", "--model", model, "--data", edited("zeros.h5", unwritten_row), "--split", "all", expect=2)
    assert "zeros.h5: sample 3: every garment vertex is at (0, 0, 0)" in err
    # Garments written as whole millimetres: converted without a word (an ME of 1.3e5 cm).
    def int_garments(f):
        g = f["garments/vertices"][...]
        del f["garments/vertices"]
        f.create_dataset("garments/vertices", data=(g * 1000).astype("i4"))

    _, err = run_drape("eval", "--model", model, "--data", edited("int.h5", int_garments), "--split", "all", expect=2)
    assert "int.h5: /garments/vertices holds i32 values, expected floating point (f32)" in err
    # A short /split: it blamed the intact /bodies/params.
    def short_split(f):
        split = f["split"][...]
        del f["split"]
        f.create_dataset("split", data=split[:-1])

    _, err = run_drape("eval", "--model", model, "--data", edited("short.h5", short_split), "--split", "all", expect=2)
    assert "short.h5: /split has 3 rows, /done and /garments/vertices 4" in err
    # eval named "the dataset's stored scene", not the file.
    _, err = run_drape("eval", "--model", model, "--data", edited("scene.h5", garbage_scene), "--split", "all", expect=2)
    assert "scene.h5 (scene attribute):1: malformed YAML" in err


def test_a_dataset_is_indexed_like_a_sequence(dataset):
    # The module's 4-sample dataset (this test used to generate a 3-sample one of its own: the same checks).
    d = drape.Dataset(str(dataset))
    assert len(d) == 4
    batch = d.read(d.indices())
    for k in range(4):
        s = d[k]
        np.testing.assert_array_equal(s["garment"], batch["garment"][k])
        np.testing.assert_array_equal(s["body"], batch["body"][k])
        assert s["index"] == k and s["split"] == batch["split"][k]
    np.testing.assert_array_equal(d[-1]["garment"], batch["garment"][3])
    assert [s["index"] for s in d[1:]] == [1, 2, 3]
    with pytest.raises(IndexError):
        d[4]
    with pytest.raises(TypeError):
        d["0"]


def test_generate_draws_poses_and_the_dataset_gives_them(module_tiny_scene, tmp_path):
    # drape.generate(poses="draw") stores each body's joint angles, read back by Dataset and h5py alike.
    out = tmp_path / "posed.h5"
    done = drape.generate(str(module_tiny_scene), str(out), 2, bmi=(20, 30), seed=3, threads=1, progress=False,
                          poses="draw", pose_ranges={"shoulder_abduction": (50, 60)})
    assert done["samples"] == 2 and not done["already_finished"]
    # The same request again finds it finished: nothing to do; another is refused.
    again = drape.generate(str(module_tiny_scene), str(out), 2, bmi=(20, 30), seed=3, threads=1, progress=False,
                           poses="draw", pose_ranges={"shoulder_abduction": (50, 60)})
    assert again["already_finished"] and again["samples"] == 2
    with pytest.raises(drape.ConfigError, match="made otherwise"):
        drape.generate(str(module_tiny_scene), str(out), 2, bmi=(20, 31), seed=3, threads=1, progress=False,
                       poses="draw", pose_ranges={"shoulder_abduction": (50, 60)})
    d = drape.Dataset(str(out))
    names = d.layout["pose_angles"]
    assert "left_shoulder_abduction" in names and "spine_twist" in names
    s = d[1]
    assert s["pose"].shape == (len(names),)
    with h5py.File(out) as f:
        np.testing.assert_array_equal(f["bodies/pose"][1], s["pose"])
        stored = f.attrs["pose_angles"]  # fixed-length strings read as bytes
        assert (stored.decode() if isinstance(stored, bytes) else stored) == ",".join(names)
    for side in ("left_", "right_"):
        assert 50 <= s["pose"][names.index(side + "shoulder_abduction")] <= 60
    assert d.read([0, 1])["pose"].shape == (2, len(names))
    with pytest.raises(ValueError, match="expected 'scene' or 'draw'"):
        drape.generate(str(module_tiny_scene), str(tmp_path / "x.h5"), 1, poses="random")


def test_posing_gives_what_a_posed_graph_reads(module_tiny_scene, tmp_path):
    # Dataset.posing: each body at rest, its joints' transforms into the stored pose, the angles in radians.
    out = tmp_path / "posed.h5"
    drape.generate(str(module_tiny_scene), str(out), 2, bmi=(20, 30), seed=4, threads=1, progress=False, poses="draw")
    d = drape.Dataset(str(out))
    p = d.posing([0, 1])
    body = d.read([0, 1])["body"]
    assert p["unposed"].shape == body.shape and p["transforms"].shape[2] == 12
    np.testing.assert_allclose(p["angles"], np.radians(d.read([0, 1])["pose"]), rtol=1e-5)
    # Every joint's transform is rigid (a rotation: R R^T = I, det R = 1), and the pose moved the body.
    r = p["transforms"][..., :9].reshape(2, -1, 3, 3).astype(np.float64)
    np.testing.assert_allclose(r @ np.swapaxes(r, -1, -2), np.broadcast_to(np.eye(3), r.shape), atol=1e-5)
    np.testing.assert_allclose(np.linalg.det(r), 1.0, atol=1e-5)
    assert np.abs(p["unposed"] - body).max() > 0.01


def test_the_torch_dataset_gives_pose_and_posing(module_tiny_scene, tmp_path):
    torch = pytest.importorskip("torch")
    import drape.torch_data as td
    out = tmp_path / "posed.h5"
    drape.generate(str(module_tiny_scene), str(out), 2, bmi=(20, 30), seed=5, threads=1, progress=False, poses="draw")
    native = drape.Dataset(str(out))
    s = td.DrapeDataset(out, posing=True)[1]
    assert set(s) == {"body", "garment", "body_params", "split", "index", "pose", "unposed", "transforms", "angles"}
    np.testing.assert_array_equal(s["pose"].numpy(), native[1]["pose"])
    np.testing.assert_array_equal(s["transforms"].numpy(), native.posing([1])["transforms"][0])
    assert s["unposed"].dtype == torch.float32 and s["angles"].shape == (len(native.layout["pose_angles"]),)
    assert "unposed" not in td.DrapeDataset(out)[1]


def test_ctrl_c_stops_generate_within_a_drape_and_keeps_what_is_done(tmp_path):
    """SIGINT during drape.generate ran on to the dataset's end (the fifty-fifth session left it so). A scene of
    1,000 morph steps a drape (minutes each uncut) is stopped a second in: the call raises KeyboardInterrupt at
    the drape's next step, and leaves the dataset to resume, not finished."""
    import os
    import signal
    import threading
    import time
    from conftest import COARSE
    scene = tmp_path / "long.yaml"
    scene.write_text(f"base: {COARSE}\nsolver: {{morph_steps: 1000, settle_steps: 0, max_newton_iterations: 3}}\n")
    out = tmp_path / "long.h5"
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        drape.generate(str(scene), str(out), 2, bmi=(30, 34), seed=1, threads=1, progress=False)
    elapsed = time.monotonic() - started
    timer.join()
    assert elapsed < 30, f"interrupted only after {elapsed:.1f} s"
    assert not out.exists()
    assert (tmp_path / "long.h5.partial").exists()
