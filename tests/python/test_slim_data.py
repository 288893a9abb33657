"""Data that loads as it is: slim shards (no body vertices) and glob patterns of shards read directly by
drape.Dataset and drape train (bodies rebuilt from their shape parameters), dataset files carry the template's
faces (/garments/faces) and old files without them still load."""
import h5py
import numpy as np
import pytest

import drape
from conftest import TINY_GRAPH, run_drape


@pytest.fixture(scope="module")
def shards(tmp_path_factory):
    """Two generated shards of a 6-drape set (one settle step each), their merge, and their slim copies."""
    from conftest import COARSE
    tmp = tmp_path_factory.mktemp("slim")
    scene = tmp / "tiny.yaml"
    scene.write_text(f"base: {COARSE}\neffects: {{barrier: null}}\n"
                     "solver: {morph_steps: 0, settle_steps: 1, max_newton_iterations: 8, linear_solver: eigen}\n")
    full = []
    for i in range(2):
        out = tmp / f"full-{i}.h5"
        run_drape("generate", scene, "--count", 6, "--bmi", "20:40", "--seed", 5, "--shard", f"{i}/2", "--out", out,
                  "--threads", 2)
        run_drape("dataset", "slim", out, "--out", tmp / f"slim-{i}.h5")
        full.append(out)
    run_drape("dataset", "merge", "--out", tmp / "merged.h5", *full)
    return tmp


def test_a_slim_glob_reads_as_the_merged_file(shards):
    slim = drape.Dataset(str(shards / "slim-*.h5"))
    merged = drape.Dataset(str(shards / "merged.h5"))
    assert slim.files == [str(shards / "slim-0.h5"), str(shards / "slim-1.h5")]
    assert len(slim) == len(merged) == 6 and not slim.layout["body_vertices_stored"]
    for split in ("train", "val", "test"):
        np.testing.assert_array_equal(slim.indices(split), merged.indices(split))
    idx = np.array([5, 0, 3])
    a, b = slim.read(idx), merged.read(idx)
    np.testing.assert_array_equal(a["garment"], b["garment"])
    np.testing.assert_array_equal(a["body_params"], b["body_params"])
    # Rebuilt from the float32 parameters: the simulated body up to their rounding (docs/formats.md).
    assert np.abs(a["body"] - b["body"]).max() < 1e-6
    np.testing.assert_array_equal(slim[-1]["body"], a["body"][0])  # rebuilt once, read again from the cache


def test_the_witness_is_the_simulated_bodies_and_a_damaged_one_is_named(shards, tmp_path):
    """/bodies/witness (docs/formats.md): per block of consecutive body vertices, their mean and RMS spread, computed
    here from the full file's stored bodies by its definition; a witness of the wrong shape is refused by name."""
    import shutil
    with h5py.File(shards / "full-0.h5", "r") as f:
        bodies = np.asarray(f["bodies/vertices"], dtype=np.float64)
    with h5py.File(shards / "slim-0.h5", "r") as f:
        witness = np.asarray(f["bodies/witness"])
    n, nb, _ = bodies.shape
    blocks = min(64, nb)
    assert witness.shape == (n, blocks, 4)
    for b in (0, 17, blocks - 1):
        part = bodies[:, b * nb // blocks:(b + 1) * nb // blocks]
        mean = part.mean(axis=1)
        spread = np.sqrt(((part - mean[:, None]) ** 2).sum(axis=2).mean(axis=1))
        np.testing.assert_allclose(witness[:, b, :3], mean, atol=1e-12)
        np.testing.assert_allclose(witness[:, b, 3], spread, atol=1e-12)
    damaged = tmp_path / "damaged.h5"
    shutil.copy(shards / "slim-0.h5", damaged)
    with h5py.File(damaged, "r+") as f:
        del f["bodies/witness"]
        f["bodies/witness"] = np.zeros((n, blocks, 3))
    with open(damaged, "r+b") as fh:  # drape's seal (a CRC in the user block) zeroed: the file opens unchecked
        fh.write(bytes(512))
    _, err = run_drape("dataset", "expand", damaged, "--out", tmp_path / "out.h5", expect=2)
    assert "damaged.h5: /bodies/witness has shape [%d, %d, 3], expected [%d, %d, 4]" % (n, blocks, n, blocks) in err


def test_faces_are_stored_and_old_files_load(shards, tmp_path):
    d = drape.Dataset(str(shards / "merged.h5"))
    with h5py.File(shards / "merged.h5", "r") as f:
        faces = np.asarray(f["garments/faces"])
        assert faces.dtype == np.int32 and faces.shape[1] == 3 and faces.max() == d.layout["garment_vertices"] - 1
        np.testing.assert_array_equal(d.faces, faces)
        np.testing.assert_array_equal(drape.Dataset(str(shards / "slim-0.h5")).faces, faces)
        # A file as drape wrote them before 2026-11-29: no faces.
        with h5py.File(tmp_path / "old.h5", "w") as old:
            for name in ("bodies", "split", "done", "stats"):
                f.copy(f[name], old, name)
            old.create_group("garments")
            f.copy(f["garments/vertices"], old["garments"], "vertices")
            for k, v in f.attrs.items():
                old.attrs[k] = v
    old = drape.Dataset(str(tmp_path / "old.h5"))
    assert old.faces is None and len(old) == 6
    np.testing.assert_array_equal(old[1]["garment"], d[1]["garment"])


def test_train_and_info_take_a_slim_glob(shards, tmp_path):
    graph = tmp_path / "tiny.yaml"
    # The tiny model with an L2 loss against the drapes (the `target` input).
    graph.write_text(TINY_GRAPH.replace("  body: [body_vertices, 3]\n", "  body: [body_vertices, 3]\n  target: [garment_vertices, 3]\n")
                     + "losses:\n  l2: 1.0\n")
    out, _ = run_drape("train", graph, "--data", shards / "slim-*.h5", "--out", tmp_path / "m.h5", "--epochs", 1,
                       "--batch", 2, "--threads", 1)
    assert (tmp_path / "m.h5").is_file()
    out, _ = run_drape("dataset", "info", shards / "slim-*.h5")
    assert "6" in out
    _, err = run_drape("dataset", "info", shards / "none-*.h5", expect=2)
    assert "none-*.h5: no dataset file matches this pattern" in err


def test_torch_dataset(shards):
    torch = pytest.importorskip("torch")
    import drape.torch_data as td
    data = td.DrapeDataset(shards / "slim-*.h5", split="all")
    native = drape.Dataset(str(shards / "merged.h5"))
    assert len(data) == 6 and data.faces.dtype == torch.int64 and data.faces.shape[1] == 3
    s = data[2]
    assert set(s) == {"body", "garment", "body_params", "split", "index"}
    assert s["body"].dtype == torch.float32 and s["body"].shape == (native.layout["body_vertices"], 3)
    assert int(s["index"]) == 2 and int(s["split"]) == int(native[2]["split"])
    loader = torch.utils.data.DataLoader(data, batch_size=4, num_workers=2)
    batches = list(loader)
    assert [b["garment"].shape[0] for b in batches] == [4, 2]
    np.testing.assert_array_equal(batches[1]["garment"].numpy(), native.read(np.array([4, 5]))["garment"])
    train = drape.TorchDataset(shards / "slim-*.h5", split="train", transform=lambda s: s["garment"])
    assert len(train) == len(native.indices("train")) and train[0].shape == (native.layout["garment_vertices"], 3)


def test_the_package_imports_without_torch():
    import subprocess
    import sys
    code = "import sys, drape; print('torch' in sys.modules, callable(drape.find_file))"
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout
    assert out.split() == ["False", "True"]
