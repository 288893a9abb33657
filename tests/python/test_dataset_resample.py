"""drape dataset resample (docs/bodies.md, "One encoder for both rigs"): the human rig's drapes with each body read at
the mannequin template's vertices. Checked against closest points found by brute force in numpy
(scripts/reference/closest_point.py), not drape's BVH: every resampled body is the source body interpolated at the
closest points of the target template's vertices on the source template."""
import h5py
import numpy as np
import pytest

import drape
from conftest import SOURCE, run_drape

from closest_point import closest_points  # scripts/reference, numpy only

HUMAN_SHARD = SOURCE / "datasets" / "bodyspace2000-human" / "shard-00-of-40.h5"
MANNEQUIN = SOURCE / "graphs" / "scenes" / "tshirt_coarse_sized.yaml"


@pytest.fixture(scope="module")
def resampled(tmp_path_factory):
    out = tmp_path_factory.mktemp("resample") / "resampled.h5"
    stdout, _ = run_drape("dataset", "resample", HUMAN_SHARD, "--onto", MANNEQUIN, "--out", out)
    assert "50 drapes" in stdout and "6904 vertices" in stdout and "6490 vertices" in stdout
    return out


def test_the_bodies_are_the_source_bodies_at_the_closest_points(resampled):
    # The two scenes' template bodies: each body model's mean body, as the assets hold it.
    human = drape.assets(resolution="coarse", body_params={"rig": "human"}, eigen_k=1, levels=1)
    source, source_faces = np.asarray(human.body_vertices, np.float64), np.asarray(human.body_faces)
    target = np.asarray(drape.assets(resolution="coarse", eigen_k=1, levels=1).body_vertices, np.float64)
    rng = np.random.default_rng(0)
    picked = np.sort(rng.choice(len(target), 200, replace=False))
    face, bary, dist = closest_points(source, source_faces, target[picked])
    corners = source_faces[face]  # [200, 3]

    bodies_in = drape.Dataset(str(HUMAN_SHARD))
    with h5py.File(resampled, "r") as f:
        out_bodies = np.asarray(f["bodies/vertices"], dtype=np.float64)
        out_garments = np.asarray(f["garments/vertices"])
        assert out_bodies.shape == (50, len(target), 3)
        assert "source_scene" in f.attrs and "rig: human" in f.attrs["source_scene"].decode()
        assert "rig" not in f.attrs["scene"].decode()
    data = bodies_in.read(np.arange(50))
    expected = (data["body"][:, corners, :].astype(np.float64) * bary[None, :, :, None]).sum(axis=2)
    # float32 storage of both the source bodies and the result
    assert np.abs(out_bodies[:, picked] - expected).max() < 2e-6
    np.testing.assert_array_equal(out_garments, data["garment"])  # the drapes as simulated
    # A test that could fail: the bodies are not simply the source's first 6490 vertices.
    assert np.abs(out_bodies[:, picked] - data["body"][:, picked]).max() > 0.01


def test_the_mean_bodies_differ_where_the_rigs_do(resampled):
    with h5py.File(resampled, "r") as f:
        note = f.attrs["resampled_from"].decode()
    assert "median" in note and "mm" in note


def test_a_garment_of_another_size_or_a_posed_dataset_is_refused(tmp_path):
    _, err = run_drape("dataset", "resample", HUMAN_SHARD, "--onto", SOURCE / "graphs" / "scenes" / "tshirt.yaml",
                       "--out", tmp_path / "x.h5", expect=2)
    assert "garment" in err and "991" in err
    posed = SOURCE / "datasets" / "posespace2000" / "shard-00-of-40.h5"
    _, err = run_drape("dataset", "resample", posed, "--onto", MANNEQUIN, "--out", tmp_path / "y.h5", expect=2)
    assert "posed" in err
    assert not (tmp_path / "x.h5").exists() and not (tmp_path / "y.h5").exists()


def test_a_resampled_set_is_not_slimmed(resampled, tmp_path):
    # Its bodies are no shape of the body model: the slim copy was written (exit 0) and then refused by every reader.
    _, err = run_drape("dataset", "slim", resampled, "--out", tmp_path / "slim.h5", expect=2)
    assert "its bodies were resampled onto another template" in err and "slim the source set instead" in err
    assert not (tmp_path / "slim.h5").exists()
