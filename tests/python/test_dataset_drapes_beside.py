"""scripts/figures/dataset_drapes.py --beside pairs two datasets' drapes of one body by the samples' global index,
and refuses two sets whose bodies of one index differ. Hand-made statistics files, nothing simulated."""
import importlib.util
import sys

import h5py
import numpy as np
import pytest

from conftest import SOURCE

sys.path.insert(0, str(SOURCE / "scripts" / "figures"))
spec = importlib.util.spec_from_file_location("dataset_drapes", SOURCE / "scripts" / "figures" / "dataset_drapes.py")
dataset_drapes = importlib.util.module_from_spec(spec)
spec.loader.exec_module(dataset_drapes)


def write(path, global_index, done, bmi):
    with h5py.File(path, "w") as f:
        f["done"] = np.array(done, dtype=np.uint8)
        f["stats/global_index"] = np.array(global_index, dtype=np.float64)
        f["stats/bmi"] = np.array(bmi, dtype=np.float64)
        f["stats/height"] = np.full(len(bmi), 1.75)
        f["stats/sex"] = np.ones(len(bmi))


def test_pairs_by_global_index_where_both_are_done(tmp_path):
    a, b = tmp_path / "a.h5", tmp_path / "b.h5"
    write(a, [50, 51, 52, 53], [1, 1, 0, 1], [20.0, 30.0, 40.0, 50.0])
    write(b, [53, 52, 51, 50], [1, 1, 0, 1], [50.0, 40.0, 30.0, 20.0])   # the same bodies, stored in another order
    # 51 is not done in b, 52 not in a: neither is paired.
    assert dataset_drapes.same_bodies(str(a), str(b)) == {0: 3, 3: 0}


def test_refuses_two_sets_whose_bodies_differ(tmp_path):
    a, b = tmp_path / "a.h5", tmp_path / "b.h5"
    write(a, [0, 1], [1, 1], [20.0, 30.0])
    write(b, [0, 1], [1, 1], [20.0, 31.0])
    with pytest.raises(SystemExit, match="global index 1 but not the body"):
        dataset_drapes.same_bodies(str(a), str(b))


def test_refuses_two_sets_with_no_body_in_common(tmp_path):
    a, b = tmp_path / "a.h5", tmp_path / "b.h5"
    write(a, [0, 1], [1, 1], [20.0, 30.0])
    write(b, [2, 3], [1, 1], [20.0, 30.0])
    with pytest.raises(SystemExit, match="no done sample of one global index"):
        dataset_drapes.same_bodies(str(a), str(b))
