"""Every T-shirt size as drape dresses it (on its fit body, docs/garments.md "Sizes") is clear of itself, by the
independent count of scripts/count_self_crossings.py (numpy, no code shared with drape): the rest garments of
a scene of each size (those drape.assets holds too, bit for bit), at the coarse and the default resolution."""
import sys

import numpy as np
import pytest

import drape
from conftest import SOURCE

sys.path.insert(0, str(SOURCE / "scripts"))
import count_self_crossings  # noqa: E402

SIZES = ["3xsmall", "2xsmall", "xsmall", "small", "regular", "large", "xlarge", "2xlarge", "3xlarge", "4xlarge", "5xlarge", "6xlarge"]


@pytest.mark.parametrize("resolution", ["coarse", "default"])
def test_every_size_rests_clear_of_itself(resolution):
    found = {}
    for size in SIZES:
        # The scene's own garment, dressed on the size's fit body (no effect needs more than gravity to dress it).
        scene = drape.Scene({"body": {"model": "parametric"}, "effects": {"gravity": {}},
                             "garment": {"template": "tshirt", "params": {"resolution": resolution, "size": size}}})
        v = np.asarray(scene.garment_vertices, dtype=np.float64)
        f = np.asarray(scene.garment_faces, dtype=np.int64)
        pairs, _ = count_self_crossings.crossings(v, f)
        found[size] = len(pairs)
    assert found == {size: 0 for size in SIZES}, f"edge-face crossings by size ({resolution}): {found}"
