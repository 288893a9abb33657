"""scripts/train_posed_model.sh: the shipped posed model's recipe, a schedule of cosine cycles each from the one
before (posed: the shipped graph; v2v100: the same graph with L_V2V at 100), checked before any training."""
import os
import re
import subprocess

import h5py

from conftest import BINARY, SOURCE

SCRIPT = SOURCE / "scripts" / "train_posed_model.sh"
SHARD = SOURCE / "datasets" / "posespace2000" / "shard-00-of-40.h5"


def run(work, **env):
    return subprocess.run(["bash", str(SCRIPT), str(work)], capture_output=True, text=True, timeout=600,
                          env={**os.environ, "BUILD_DIR": str(BINARY), "DATA": str(SHARD), **env})


def test_an_unknown_cycle_is_refused_before_any_training(tmp_path):
    work = tmp_path / "work"
    p = run(work, SCHEDULE="posed v2v1000")
    assert p.returncode == 2, p.stderr
    assert "SCHEDULE: unknown cycle 'v2v1000' (posed, v2v100)" in p.stderr
    assert not work.exists()  # nothing trained, nothing written


def test_a_schedule_of_no_cycle_is_refused(tmp_path):
    # CYCLES=0 once made one cycle (printf repeats its format once without arguments); a blank SCHEDULE none.
    for env, message in (({"CYCLES": "0"}, "CYCLES must be a count of cycles, got '0'"),
                         ({"SCHEDULE": "  "}, "SCHEDULE names no cycle")):
        p = run(tmp_path / "work", **env)
        assert p.returncode == 2 and message in p.stderr, p.stderr
        assert not (tmp_path / "work").exists()


def test_each_cycle_trains_its_graph_from_the_one_before(tmp_path):
    work = tmp_path / "work"
    p = run(work, SCHEDULE="posed v2v100", EPOCHS="1")
    assert p.returncode == 0, p.stderr
    for name in ("cycle1.h5", "model.h5", "test.csv", "heldout.csv"):
        assert (work / name).exists(), name

    def meta_and_v2v_weight(model):
        with h5py.File(model, "r", locking=False) as f:
            meta = {k: v.decode() for k, v in f["meta"].attrs.items()}
            graph = f.attrs["graph"].decode()  # the graph as trained, its bases resolved
        return meta, float(re.search(r"\n  v2v:\n(?:    .*\n)*?    weight: ([0-9.]+)", graph).group(1))

    (first, first_v2v), (last, last_v2v) = meta_and_v2v_weight(work / "cycle1.h5"), meta_and_v2v_weight(work / "model.h5")
    assert first["init"].startswith("models/tshirt-coarse.h5")  # the first cycle from the A-pose model, widened
    assert last["init"].startswith(str(work / "cycle1.h5"))  # the second from the first
    assert (first_v2v, last_v2v) == (10.0, 100.0)  # posed, then v2v100
