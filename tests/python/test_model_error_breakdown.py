"""scripts/model_error_breakdown.py: a model's error split by garment region, the garment's shift and a rigid fit,
checked against drape eval's ME (another code path) and against the split's own definitions."""
import re

import pytest
from conftest import SOURCE, penalty_scene, run_drape
from conftest import run_script as run_any_script

SCRIPT = SOURCE / "scripts" / "model_error_breakdown.py"


def run_script(*args):
    return run_any_script(SCRIPT, *args)


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("breakdown")
    scene = penalty_scene(tmp / "tiny.yaml")
    data = tmp / "data.h5"
    run_drape("generate", scene, "--count", 4, "--bmi", "20:40", "--seed", 5, "--out", data, "--threads", 1)
    return data


def test_the_breakdown_agrees_with_drape_eval_and_its_shares_add_up(tiny, tmp_path):
    model = SOURCE / "models" / "tshirt-coarse.h5"
    p = run_script("--data", tiny, "--model", model, "--split", "all")
    assert p.returncode == 0, p.stderr
    me = float(re.search(r"ME ([0-9.]+) cm\n", p.stdout).group(1))
    csv = tmp_path / "eval.csv"
    run_drape("eval", "--model", model, "--data", tiny, "--split", "all", "--out", csv)
    eval_me = float(next(l for l in open(csv) if l.startswith("ME,")).split(",")[2])
    assert me == pytest.approx(eval_me, abs=2e-3)
    shares = [float(s) for s in re.findall(r"ME [0-9.]+ cm  ([0-9]+) % of the error", p.stdout)]
    assert len(shares) == 3 and abs(sum(shares) - 100) <= 2  # three regions, every vertex in one
    shift = re.search(r"ME without it ([0-9.]+) cm, after the best rigid fit ([0-9.]+) cm", p.stdout)
    without, rigid = float(shift.group(1)), float(shift.group(2))
    # Taking the mean shift out can only lower the squared error; the rigid fit is at least as good for
    # least squares, so on the mean distance it is no worse than a few percent above.
    assert without <= me * 1.02 and rigid <= without * 1.05


def test_a_split_with_no_bodies_is_refused_by_name(tiny):
    p = run_script("--data", tiny, "--model", SOURCE / "models" / "tshirt-coarse.h5", "--split", "val")
    if p.returncode == 0:  # the 4 samples' split may hold a validation body; then ask for an empty file
        pytest.skip("this tiny dataset has a validation body")
    assert "no done samples in the val split" in p.stderr and "Traceback" not in p.stderr


def test_one_mode_is_the_shift_and_every_mode_is_the_whole_error(tiny):
    # The smoothest mode of a graph Laplacian is the constant: the error's part in it is each garment's mean
    # offset, which the script also reports as the shift; in all modes the error is whole and nothing is left.
    model = SOURCE / "models" / "tshirt-coarse.h5"
    p = run_script("--data", tiny, "--model", model, "--split", "all", "--modes", "1,991")
    assert p.returncode == 0, p.stderr
    me = float(re.search(r"ME ([0-9.]+) cm\n", p.stdout).group(1))
    shift = float(re.search(r"the whole garment's shift: mean ([0-9.]+) cm", p.stdout).group(1))
    modes = {int(k): (float(a), float(b)) for k, a, b in
             re.findall(r"(\d+) smoothest modes: the error's smooth part ([0-9.]+) cm, the rest ([0-9.]+) cm", p.stdout)}
    assert modes[1][0] == pytest.approx(shift, abs=2e-3)
    assert modes[991][0] == pytest.approx(me, abs=2e-3) and modes[991][1] < 1e-3


def test_a_garment_moved_out_along_its_normals_stands_off_by_that_much(capsys):
    # An octahedron (faces counter-clockwise seen from outside) as the drape, its vertices moved 1 cm along
    # their outward normals as the prediction, a small body inside it: +1 cm along the normal, +1 cm farther.
    import importlib.util
    import numpy as np
    spec = importlib.util.spec_from_file_location("breakdown", SCRIPT)
    breakdown = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(breakdown)
    x = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float) * 0.2
    faces = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    n = breakdown.vertex_normals(x, faces)
    assert np.allclose(n, x / 0.2)  # outward, unit
    body = x * 0.5
    breakdown.stand_off((x + 0.01 * n)[None], x[None], body[None], faces, bands=(0, 100))
    out = capsys.readouterr().out
    assert "outward normal: mean +1.000 cm" in out
    assert "the predicted ones +1.000 cm farther, along the normal +1.000 cm" in out
