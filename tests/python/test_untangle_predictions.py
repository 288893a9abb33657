"""The push-out's untangle on the shipped human-rig model's predictions: three heavy test bodies whose predicted
shirts crossed themselves at the sleeves and the underarm, and one whose sleeve's two layers pinch through each other
(shards 1, 3, 14 and 39 of datasets/bodyspace2000-human), come out with no crossing of the garment through itself,
counted by scripts/count_self_crossings.py (numpy only, no drape code), while `post.untangle=false` gives the
crossings back; the shirt moves by millimetres to centimetres, and no vertex ends inside the body (winding numbers)."""
import subprocess
import sys
import warnings

import numpy as np
import pytest

from conftest import DRAPE, SOURCE

sys.path.insert(0, str(SOURCE / "scripts"))
from count_self_crossings import crossings  # noqa: E402
from winding_number import winding_numbers  # noqa: E402

drape = pytest.importorskip("drape")
MODEL = SOURCE / "models" / "tshirt-coarse-human.h5"
# (shard, sample in it, largest move in m): BMI 60.9 (13-14 self-crossing edges without untangle), BMI 50.6 (7), BMI
# 64.6 (4: a crumple at the underarm; with an older model, 2, which the pulls alone handed on and left), and BMI 30.0
# (27-29: the sleeve's two layers pinched through each other beside the underarm seam, within the crumples' reach;
# the smoothing alone left 7 of the 1 mm model's 29, the template's sides undo them, moving the shirt up to 2.5 cm).
BODIES = [(3, 6, 0.02), (14, 31, 0.02), (1, 18, 0.02), (39, 12, 0.03)]


def test_untangle_undoes_the_heavy_predictions_self_crossings(tmp_path):
    off_file = tmp_path / "off.h5"
    subprocess.run([str(DRAPE), "model", "set", str(MODEL), "--out", str(off_file), "--set", "post.untangle=false"],
                   check=True, capture_output=True)
    on, off = drape.Model.load(str(MODEL)), drape.Model.load(str(off_file))
    gf = np.array(on.assets.garment_faces)
    bf = np.array(on.assets.body_faces)
    for shard, sample, largest_move in BODIES:
        data = drape.Dataset(str(SOURCE / "datasets" / "bodyspace2000-human" / f"shard-{shard:02d}-of-40.h5"))
        body = data[sample]["body"]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            g_on = np.asarray(on.predict(body, check=False), dtype=np.float64)
            g_off = np.asarray(off.predict(body, check=False), dtype=np.float64)
        before, _ = crossings(g_off, gf)
        after, _ = crossings(g_on, gf)
        assert len(before) >= 2, (shard, sample, len(before))
        assert len(after) == 0, (shard, sample, len(after))
        moves = np.linalg.norm(g_on - g_off, axis=1)
        assert 0 < moves.max() < largest_move, (shard, sample, moves.max())
        assert (moves > 0).sum() < 60, (moves > 0).sum()  # a patch at the sleeve, not the shirt
        assert (winding_numbers(body.astype(np.float64), bf, g_on) > 0.5).sum() == 0


def test_optimize_keeps_the_drape_off_itself_where_the_network_folds_it_through(tmp_path):
    # The drape optimised is the network's own plus the push-out's correction of the prediction, held fixed (the
    # push-out is not learnt: docs/optimization.md). Where the network folds the sleeve through the shirt (the BMI 30
    # body: 27-29 crossing edges without untangle) that correction holds the untangle's moves, so the drape starts
    # uncrossed and the self-contact keeps it so. (Moving the network's own drape alone, the crossings stayed in every
    # iterate, and on this body the barrier's shrunk start never grew back: no iterate was a result.)
    model = drape.Model.load(str(MODEL))
    scene = drape.Scene(str(SOURCE / "graphs" / "scenes" / "tshirt_coarse_human.yaml"))
    gf = np.array(model.assets.garment_faces)
    bf = np.array(model.assets.body_faces)
    data = drape.Dataset(str(SOURCE / "datasets" / "bodyspace2000-human" / "shard-39-of-40.h5"))
    body = data[12]["body"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = model.optimize(scene, body, iterations=20)
    assert r["separated"]
    assert r["best_iteration"] > 0  # an optimised drape, not the prediction
    assert r["potential_after"] < r["potential_before"]
    after, _ = crossings(np.asarray(r["after"], dtype=np.float64), gf)
    assert len(after) == 0, len(after)
    assert (winding_numbers(body.astype(np.float64), bf, np.asarray(r["after"], dtype=np.float64)) > 0.5).sum() == 0
