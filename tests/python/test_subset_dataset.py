"""scripts/subset_dataset.py: the samples of some shards in a BMI range and a split, copied into one dataset.
Checked against the shards read with h5py here (which samples, in which order, every per-sample dataset
the same bytes), by drape itself joining the subset to a shard, and on bad input."""
import h5py
import numpy as np

from conftest import SOURCE, run_drape, run_script

SHARDS = [SOURCE / "datasets" / "posespace2000-human" / f"shard-{k:02d}-of-40.h5" for k in (0, 1)]
OTHER_SCENE = SOURCE / "datasets" / "posespace2000" / "shard-00-of-40.h5"  # the mannequin rig's scene
SCRIPT = SOURCE / "scripts" / "subset_dataset.py"


def subset(*args):
    return run_script(SCRIPT, *args)


def test_the_samples_in_the_range_and_split_in_order(tmp_path):
    out = tmp_path / "heavy.h5"
    p = subset(*SHARDS, "--bmi", "40:60", "--split", "train", "--out", out)
    assert p.returncode == 0, p.stderr
    expected = []  # (shard, index) of every done training sample with 40 <= BMI < 60, shard by shard
    for shard in SHARDS:
        with h5py.File(shard, "r") as f:
            bmi, split, done = f["stats/bmi"][()], f["split"][()], f["done"][()]
            expected += [(shard, i) for i in range(len(bmi)) if done[i] and split[i] == 0 and 40 <= bmi[i] < 60]
    assert 5 < len(expected) < 100  # (the test means something: some kept, some not)
    with h5py.File(out, "r") as o:
        assert o["done"].shape[0] == len(expected)
        assert (o["split"][()] == 0).all()
        for k, (shard, i) in enumerate(expected):
            with h5py.File(shard, "r") as f:
                for name in ("garments/vertices", "bodies/params", "bodies/pose", "bodies/witness", "stats/bmi",
                             "stats/garment_grade", "stats/global_index"):
                    assert np.array_equal(o[name][k], f[name][i]), (name, k)
        with h5py.File(SHARDS[0], "r") as f:
            assert np.array_equal(o["garments/faces"][()], f["garments/faces"][()])
            assert o.attrs["scene"] == f.attrs["scene"] and o.attrs["size_chart"] == f.attrs["size_chart"]
        assert "BMI in [40, 60)" in o.attrs["subset"].decode()
    # drape reads it as a slim dataset of the same scene: joined to a shard, every body rebuilt and checked
    # against its witness.
    joined = tmp_path / "joined.h5"
    run_drape("dataset", "expand", "--out", joined, SHARDS[0], out)
    with h5py.File(joined, "r") as j:
        assert j["done"].shape[0] == 50 + len(expected)


def test_bad_input_is_refused_with_a_reason(tmp_path):
    out = tmp_path / "s.h5"
    p = subset(SHARDS[0], "--bmi", "40", "--out", out)
    assert p.returncode != 0 and "LO:HI" in p.stderr
    p = subset(SHARDS[0], "--bmi", "60:40", "--out", out)
    assert p.returncode != 0 and "below" in p.stderr
    p = subset(SHARDS[0], "--bmi", "70:80", "--out", out)
    assert p.returncode != 0 and "no train sample" in p.stderr
    p = subset(SHARDS[0], OTHER_SCENE, "--bmi", "10:65", "--split", "all", "--out", out)
    assert p.returncode != 0 and "another scene" in p.stderr
    assert not out.exists() and not (tmp_path / "s.h5.partial").exists()
