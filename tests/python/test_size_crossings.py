"""Every T-shirt size as drape dresses it (on its fit body, docs/garments.md "Sizes") is clear of itself, by the
independent count of scripts/count_self_crossings.py (numpy, no code shared with drape): the rest garments of
drape.assets, which dress them as a scene does, at the coarse and the default resolution."""
import os
import sys

import numpy as np
import pytest

import drape
from conftest import SOURCE

sys.path.insert(0, str(SOURCE / "scripts"))
import count_self_crossings  # noqa: E402

SIZES = ["small", "regular", "large", "xlarge", "2xlarge", "3xlarge", "4xlarge", "5xlarge", "6xlarge"]


@pytest.mark.parametrize("resolution", ["coarse", "default"])
def test_every_size_rests_clear_of_itself(resolution, tmp_path):
    found = {}
    for size in SIZES:
        a = drape.assets(resolution=resolution, size=size, eigen_k=10, levels=1, cache_dir=str(tmp_path))
        v = np.asarray(a._a.garment_vertices, dtype=np.float64)
        f = np.asarray(a._a.garment_faces, dtype=np.int64)
        pairs, _ = count_self_crossings.crossings(v, f)
        found[size] = len(pairs)
    assert found == {size: 0 for size in SIZES}, f"edge-face crossings by size ({resolution}): {found}"
