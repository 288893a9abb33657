"""scripts/check_predictions.py: the shipped human-rig model on a heavy test body of the repository's shard 3 whose
prediction crosses itself at a cuff (13 edges) without the push-out's untangle and not with it, by the script's
numpy checks; and a model of posed drapes given each body's rest shape and joint angles (one posed test body)."""
import subprocess
import sys

import pytest

from conftest import BINARY, DRAPE, SOURCE

SCRIPT = SOURCE / "scripts" / "check_predictions.py"
pytest.importorskip("drape")


def run(*args):
    p = subprocess.run([sys.executable, str(SCRIPT), "--drape", str(DRAPE), *map(str, args)], capture_output=True,
                       text=True, timeout=300, env={"PYTHONPATH": str(BINARY / "python"), "OMP_NUM_THREADS": "1"})
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_the_untangle_shows_in_the_independent_count():
    shard = SOURCE / "datasets" / "bodyspace2000-human" / "shard-03-of-40.h5"
    model = SOURCE / "models" / "tshirt-coarse-human.h5"
    off = run("--model", model, "--data", shard, "--samples", 6, "--set", "post.untangle=false")
    assert "sample 6 (BMI 60.9): p 0.00 %, 0 garment-body crossings, 13 self-crossings" in off
    assert "1 predictions: 0 with a vertex inside the body, 0 crossing the body, 1 crossing themselves (13 edges)" in off
    on = run("--model", model, "--data", shard, "--samples", 6)
    assert "0 crossing themselves (0 edges)" in on


def test_a_posed_model_is_given_the_rest_body_and_the_pose():
    shard = SOURCE / "datasets" / "posespace2000" / "shard-00-of-40.h5"
    out = run("--model", SOURCE / "models" / "tshirt-coarse-posed.h5", "--data", shard, "--samples", 11)
    assert "1 predictions: 0 with a vertex inside the body, 0 crossing the body" in out
