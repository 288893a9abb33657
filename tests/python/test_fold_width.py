"""scripts/fold_width.py, the fold-width measure of issue 54 (item 3), on synthetic sheets whose folds are
known: a one-triangle zig-zag is all crinkle, sine folds of 2-5 triangle heights have their width, a cylinder
its curvature and no crinkle. Numpy only, nothing from drape."""
import importlib.util
import math

import numpy as np

from conftest import SOURCE

SCRIPT = SOURCE / "scripts" / "fold_width.py"
spec = importlib.util.spec_from_file_location("fold_width", SCRIPT)
fold_width = importlib.util.module_from_spec(spec)
spec.loader.exec_module(fold_width)


def test_self_test_passes():
    assert fold_width.self_test()


def test_a_zig_zag_on_a_tilted_sheet_is_crinkled_and_a_wide_fold_is_not():
    x, f, h = fold_width.lattice(20, 22, s=0.02, rotate_deg=30.0)
    rows = np.round((x[:, 0] * math.sin(math.radians(30)) + x[:, 1] * math.cos(math.radians(30))) / h).astype(int)
    zig = x.copy()
    zig[:, 2] = np.where(rows % 2 == 0, 0.2 * h, -0.2 * h)
    r, *_ = fold_width.summary(zig, f)
    assert r["crinkled_share_of_bent"] > 0.9 and r["median"] < 1.5
    t = x[:, 0]
    wide = x.copy()
    wide[:, 2] = 0.02 * np.sin(2 * math.pi * t / (8 * h))   # half-wavelength 4 triangle heights
    r, *_ = fold_width.summary(wide, f)
    assert r["bent_faces"] > 0 and r["median"] > 3.5
