"""drape predict counts the edges where its garment and the body cross, and its garment's own edges through its faces (p counts vertices only: an edge can pass
through a thin ridge of the body with both ends outside) and warns when there are any. Checked against edge-face
tests in numpy (scripts/count_self_crossings.py) that share no code with drape."""
import re
import sys

import numpy as np

from conftest import SOURCE, TINY_GRAPH, read_obj, run_drape

sys.path.insert(0, str(SOURCE / "scripts"))
from count_self_crossings import crossings  # numpy edge-face tests  # noqa: E402

COUNT = re.compile(r"p = [0-9.]+% of them inside the body, (\d+) edges crossing it")
SELF = re.compile(r"edges crossing it, the garment through itself (\d+) edge-face pairs")


def crossing_edges(garment, garment_faces, body, body_faces):
    """(garment edges through a body face, body edges through a garment face), each edge once."""
    n = len(garment)
    v = np.vstack([garment, body])
    faces = np.vstack([garment_faces, body_faces + n])
    hits, edges = crossings(v, faces)
    edge_in_garment = (edges[hits[:, 0]] < n).all(axis=1)
    face_in_garment = (faces[hits[:, 1]] < n).all(axis=1)
    garment_edges = np.unique(hits[edge_in_garment & ~face_in_garment, 0])
    body_edges = np.unique(hits[~edge_in_garment & face_in_garment, 0])
    return len(garment_edges), len(body_edges)


def test_a_crossing_prediction_is_counted_and_warned(tmp_path, drape_module):
    """An untrained model's shirt on a BMI 40 body (the mean body's shirt, deep in it): the count printed is the
    numpy count, and a warning names both directions."""
    model = tmp_path / "untrained.h5"
    drape_module.Model.untrained(TINY_GRAPH, {"resolution": "coarse"}, seed=1).save(str(model), {})
    out, err = run_drape("predict", "--model", model, "--bmi", 40, "--sex", 1, "--out", tmp_path / "g.obj",
                         "--body-out", tmp_path / "b.obj")
    g, gf = read_obj(str(tmp_path / "g.obj"))
    b, bf = read_obj(str(tmp_path / "b.obj"))
    through_body, through_garment = crossing_edges(g, np.asarray(gf), b, np.asarray(bf))
    assert through_body > 0
    assert int(COUNT.search(out).group(1)) == through_body + through_garment
    assert (f"warning: the garment and the body cross: {through_body} garment edges through the body, "
            f"{through_garment} body edges through the garment") in err
    # The garment through itself, (edge, face) pairs as simulate counts them: numpy's count of the shirt alone.
    self_pairs = len(crossings(g, np.asarray(gf))[0])
    assert int(SELF.search(out).group(1)) == self_pairs
    assert (f"warning: the garment passes through itself: {self_pairs} pairs of an edge and a face" in err) == (self_pairs > 0)


def test_the_shipped_model_reports_no_crossing(tmp_path):
    """The shipped model (its push-out on) on a body of BMI 30: 0 printed, no warning, and 0 by numpy."""
    out, err = run_drape("predict", "--bmi", 30, "--out", tmp_path / "g.obj", "--body-out", tmp_path / "b.obj")
    g, gf = read_obj(str(tmp_path / "g.obj"))
    b, bf = read_obj(str(tmp_path / "b.obj"))
    assert crossing_edges(g, np.asarray(gf), b, np.asarray(bf)) == (0, 0)
    assert int(COUNT.search(out).group(1)) == 0
    assert "warning: the garment and the body cross" not in err
    assert len(crossings(g, np.asarray(gf))[0]) == 0
    assert int(SELF.search(out).group(1)) == 0 and "passes through itself" not in err
