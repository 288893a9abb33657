"""drape.body and drape.BodyModel against the drape program's bodies, and their errors."""
import numpy as np
import pytest

import drape
from conftest import read_obj, run_drape


def test_body_matches_the_program(tmp_path):
    out = tmp_path / "body.obj"
    run_drape("body", "--bmi", 38, "--height", 1.80, "--sex", 0, "--out", out)
    v_cli, f_cli = read_obj(out)
    v, f = drape.body(bmi=38, height=1.80, sex=0)
    assert v.dtype == np.float64 and v.shape == v_cli.shape and f.dtype == np.int32
    np.testing.assert_allclose(v, v_cli, atol=2e-6)  # the OBJ holds 6 decimals
    np.testing.assert_array_equal(f, f_cli)


def test_girths_set_named_shape_parameters():
    model = drape.BodyModel("parametric")
    assert "chest" in model.shape_names and "thighs" in model.shape_names
    plain = model.solve(bmi=30)
    wide = model.solve(bmi=30, chest=0.3)
    i = model.shape_names.index("chest")
    assert wide[i] == pytest.approx(0.3)
    others = [k for k in range(len(plain)) if k != i]
    np.testing.assert_array_equal(wide[others], plain[others])
    v_plain, v_wide = model.vertices(plain), model.vertices(wide)
    # A wider chest: the vertices at chest height spread further from the body's vertical axis.
    y = v_plain[:, 1]
    band = (y > 0.70 * y.max()) & (y < 0.75 * y.max())
    radius = lambda v: np.hypot(v[band, 0] - v[band, 0].mean(), v[band, 2] - v[band, 2].mean()).mean()
    assert radius(v_wide) > radius(v_plain) * 1.05
    np.testing.assert_array_equal(drape.body(bmi=30, chest=0.3)[0], v_wide)


def test_errors_carry_the_programs_messages(tmp_path):
    _, err = run_drape("body", "--bmi", 80, "--out", tmp_path / "b.obj", expect=2)
    with pytest.raises(drape.ConfigError) as e:
        drape.body(bmi=80)
    assert isinstance(e.value, ValueError) and isinstance(e.value, drape.Error)
    assert str(e.value) in err and "\n" not in str(e.value)
    with pytest.raises(ValueError, match="no shape parameter 'chst'; did you mean 'chest'"):
        drape.body(bmi=30, chst=0.2)
    with pytest.raises(drape.ConfigError, match="unknown|no plugin|did you mean"):
        drape.BodyModel("parametrik")
    with pytest.raises(ValueError, match=r"shape: expected a float array of shape \[9\]"):
        drape.BodyModel().vertices(np.zeros(3))


def test_plugins_are_listed():
    kinds = {p["name"]: p["kind"] for p in drape.plugins()}
    assert kinds["parametric"] == "body" and kinds["stretching"] == "energy" and kinds["tshirt"] == "garment"
    assert drape.plugin_search_path()
