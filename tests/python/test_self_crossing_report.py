"""drape simulate and drape generate say when a garment ends crossing itself (SimulationResult::self_crossings),
counted against scripts/count_self_crossings.py, which shares no code with drape. The coarse shirt without its
self-contact on a BMI 45 body folds through itself at the sides (docs/scenes.md); with it, a drape that still
crossed itself used to pass the generator's checks unnamed (seed 7's shard 9, docs/poses.md)."""
import re
import sys

import numpy as np

from conftest import SOURCE, read_obj, run_drape

sys.path.insert(0, str(SOURCE / "scripts"))
from count_self_crossings import crossings  # numpy edge-face tests  # noqa: E402


def scene_without_self_contact(tmp_path):
    scene = tmp_path / "no_self_contact.yaml"
    scene.write_text(f"base: {SOURCE / 'graphs' / 'scenes' / 'tshirt_coarse.yaml'}\n"
                     "description: the coarse shirt without its self-contact\n"
                     "effects:\n  self_contact: null\n"
                     # The folds cross by the 30th settling step (100 pairs at BMI 45; 478 settled, 0 at 15
                     # steps): a third less simulation than settling, for what the tests count.
                     "solver: {settle_steps: 30}\n")
    return scene


def test_simulate_counts_the_edges_through_the_garment_as_the_independent_test_does(tmp_path):
    scene = scene_without_self_contact(tmp_path)
    out, _ = run_drape("simulate", scene, "--bmi", 45, "--out", tmp_path / "g.obj", "--threads", 1, expect=(0, 1))
    reported = int(re.search(r"the garment through itself (\d+) edge-face pairs", out).group(1))
    v, f = read_obj(tmp_path / "g.obj")
    pairs, _ = crossings(np.asarray(v, float), np.asarray(f))
    assert len(pairs) > 0  # the fold this scene is chosen for
    assert reported == len(pairs)  # (touching pairs would differ: drape counts them, the script does not)


def test_generate_names_the_drapes_that_cross_themselves(tmp_path):
    scene = scene_without_self_contact(tmp_path)
    out, _ = run_drape("generate", scene, "--count", 1, "--bmi", 45, "--seed", 0, "--threads", 1,
                       "--out", tmp_path / "d.h5")
    assert re.search(r"1 crossing themselves", out), out
    assert "garments crossing themselves: sample 0 (global index)" in out
    # The command it suggests leaves that drape out of the slim copy, and the copy says so.
    suggested = re.search(r"`drape (dataset slim .*)` leaves them out", out).group(1)
    words = suggested.replace("SLIM", str(tmp_path / "slim.h5")).split()
    assert words[-2:] == ["--drop", "0"], suggested
    slimmed, _ = run_drape(*words)
    assert "0 samples without body vertices (1 global index dropped: 1 row)" in slimmed
    info, _ = run_drape("dataset", "info", tmp_path / "slim.h5")
    assert "dropped: 0" in info
