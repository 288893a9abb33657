"""The independent inside test of scripts/reference (a generalized winding number in numpy, its own OBJ reader):
what docs and notes use to confirm drape's p from outside. Checked on a cube by hand, then on a body drape
written by the program."""
import subprocess
import sys

import numpy as np
import pytest

from conftest import COARSE, REFERENCE, TINY_GRAPH, read_obj, run_drape
from winding_number import winding_numbers


def write_cube(path):
    """A unit cube [0,1]^3 as 6 quads, outward, 1-based with v/vt/vn-style indices on two faces."""
    v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    quads = [(1, 2, 4, 3), (5, 7, 8, 6), (1, 5, 6, 2), (3, 4, 8, 7), (1, 3, 7, 5), (2, 6, 8, 4)]
    with open(path, "w") as f:
        for p in v:
            f.write("v %g %g %g\n" % p)
        for k, q in enumerate(quads):
            f.write("f " + " ".join(("%d/1/1" % i) if k < 2 else str(i) for i in q) + "\n")


def test_cube_by_hand(tmp_path):
    path = tmp_path / "cube.obj"
    write_cube(path)
    v, f = read_obj(str(path))
    assert v.shape == (8, 3) and f.shape == (12, 3)  # quads fanned into two triangles each
    points = np.array([[0.5, 0.5, 0.5], [0.1, 0.9, 0.2], [1.5, 0.5, 0.5], [0.5, -0.01, 0.5], [3.0, 3.0, 3.0]])
    w = winding_numbers(v, f, points)
    np.testing.assert_allclose(w, [1, 1, 0, 0, 0], atol=1e-9)


def test_a_drape_and_a_pushed_in_copy(tmp_path):
    garment, body = tmp_path / "g.obj", tmp_path / "b.obj"
    # The shipped coarse scene, its steps cut short: the barrier keeps every vertex outside at every step, so an
    # unsettled drape lies as close to the skin as a settled one (exit 1: not settled), in a few seconds, not 17.
    short = tmp_path / "short.yaml"
    short.write_text(f"base: {COARSE}\nsolver: {{morph_steps: 2, settle_steps: 1, max_newton_iterations: 8}}\n")
    run_drape("simulate", short, "--bmi", 22, "--out", garment, "--body-out", body, expect=(0, 1))
    script = str(REFERENCE / "winding_number_meshes.py")
    out = subprocess.run([sys.executable, script, str(garment), str(body)], capture_output=True, text=True, check=True)
    assert "p = 0.000 %" in out.stdout  # the barrier drape: no vertex inside
    # Half of the shirt's vertices pulled 70 % of the way to the body's centre of mass are inside it.
    g, gf = read_obj(str(garment))
    b, _ = read_obj(str(body))
    moved = g.copy()
    half = np.arange(0, len(g), 2)
    centre = b.mean(axis=0)
    moved[half] = centre + 0.3 * (g[half] - centre)
    inside_path = tmp_path / "inside.obj"
    with open(inside_path, "w") as f:
        f.writelines("v %.6f %.6f %.6f\n" % tuple(p) for p in moved)
        f.writelines("f %d %d %d\n" % tuple(t + 1) for t in gf)
    out = subprocess.run([sys.executable, script, str(inside_path), str(body)], capture_output=True, text=True, check=True)
    expected = 100.0 * len(half) / len(g)
    p = float(out.stdout.split("p = ")[1].split(" %")[0])
    assert p == pytest.approx(expected, abs=100.0 * 30 / len(g))  # the body's centre is in its torso; a few may miss


def test_a_prediction_pushed_out(tmp_path, drape_module):
    """drape predict --push-out: a prediction with many vertices inside the body (an untrained model's, so that
    the test does not depend on how well the shipped model fits) has none inside once pushed out, by the
    winding number."""
    garment, pushed, body = tmp_path / "g.obj", tmp_path / "pushed.obj", tmp_path / "b.obj"
    model = tmp_path / "untrained.h5"
    drape_module.Model.untrained(TINY_GRAPH, {"resolution": "coarse"}, seed=1).save(str(model), {})
    shape = ("--model", model, "--bmi", 40, "--sex", 1)
    run_drape("predict", *shape, "--out", garment, "--body-out", body)
    out, _ = run_drape("predict", *shape, "--push-out", "--out", pushed)
    assert "pushed out:" in out
    g, _ = read_obj(str(garment))
    q, _ = read_obj(str(pushed))
    b, bf = read_obj(str(body))
    inside = winding_numbers(b, bf, g) > 0.5
    assert inside.mean() > 0.10  # deep in: the mean body's shirt on BMI 40
    assert not (winding_numbers(b, bf, q) > 0.5).any()
    # Every vertex that was inside moved; those surely beyond the 1 mm clearance did not. (A point of a
    # triangle is within its longest edge of a corner: a vertex farther than that plus 1 mm from every body
    # vertex is more than 1 mm from the surface.)
    moved = np.linalg.norm(q - g, axis=1) > 1e-6
    assert moved[inside].all()
    nearest = np.array([np.linalg.norm(b - x, axis=1).min() for x in g])
    longest_edge = max(np.linalg.norm(b[bf[:, i]] - b[bf[:, (i + 1) % 3]], axis=1).max() for i in range(3))
    far = ~inside & (nearest > longest_edge + 0.001)
    assert far.any() and not moved[far].any()
