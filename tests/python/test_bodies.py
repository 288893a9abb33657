"""drape.body and drape.BodyModel against the drape program's bodies, and their errors."""
import sys

import numpy as np
import pytest

import drape
from conftest import SOURCE, read_obj, run_drape


def test_body_matches_the_program(tmp_path):
    out = tmp_path / "body.obj"
    run_drape("body", "--bmi", 38, "--height", 1.80, "--sex", 0, "--out", out)
    v_cli, f_cli = read_obj(out)
    v, f = drape.body(bmi=38, height=1.80, sex=0)
    assert v.dtype == np.float64 and v.shape == v_cli.shape and f.dtype == np.int32
    np.testing.assert_allclose(v, v_cli, atol=2e-6)  # the OBJ holds 6 decimals
    np.testing.assert_array_equal(f, f_cli)


def mesh_bmi(v, f):
    """BMI from the closed mesh's volume (divergence theorem) at 985 kg/m^3 over its height squared, computed
    here independently of drape."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
    height = v[:, 1].max() - v[:, 1].min()
    return volume * 985 / height**2


def test_a_posed_body_matches_the_program(tmp_path):
    # drape.body(pose=...) is drape body --pose (pose= was read as a girth named "pose").
    out = tmp_path / "posed.obj"
    run_drape("body", "--bmi", 30, "--pose", "shoulder_abduction=40,left_elbow_flexion=30", "--out", out)
    v_cli, _ = read_obj(out)
    v, _ = drape.body(bmi=30, pose={"shoulder_abduction": 40, "left_elbow_flexion": 30})
    np.testing.assert_allclose(v, v_cli, atol=1e-12)
    assert np.abs(v - drape.body(bmi=30)[0]).max() > 0.1  # the arms moved
    with pytest.raises(ValueError, match="pass through itself"):
        drape.body(bmi=60, sex=0, pose="shoulder_abduction=0")
    model = drape.Model.load(str(SOURCE / "models" / "tshirt-coarse-posed.h5"))
    with pytest.raises(ValueError, match="makes the body at rest"):
        model.body(bmi=30, pose="shoulder_abduction=40")


def test_girths_are_held_while_the_bmi_is_reached(tmp_path):
    model = drape.BodyModel("parametric")
    assert set(model.proportions) == {"chest", "waist", "belly", "hips", "arms", "thighs"}
    run_drape("body", "--bmi", 30, "--girth", "chest=0.12", "--girth", "hips=-0.1", "--out", tmp_path / "b.obj")
    v_cli, _ = read_obj(tmp_path / "b.obj")
    v, f = drape.body(bmi=30, chest=0.12, hips=-0.1)
    np.testing.assert_allclose(v, v_cli, atol=2e-6)
    plain, _ = drape.body(bmi=30)
    assert mesh_bmi(v, f) == pytest.approx(30, abs=0.1) and mesh_bmi(plain, f) == pytest.approx(30, abs=0.1)
    shape = model.solve(bmi=30, chest=0.12, hips=-0.1)
    assert shape[model.shape_names.index("chest")] == pytest.approx(0.12)
    np.testing.assert_array_equal(model.vertices(shape), v)
    # A wider chest at the same BMI: the vertices at chest height spread further from the body's axis.
    y = plain[:, 1]
    band = (y > 0.70 * y.max()) & (y < 0.75 * y.max())
    radius = lambda v: np.hypot(v[band, 0] - v[band, 0].mean(), v[band, 2] - v[band, 2].mean()).mean()
    assert radius(drape.body(bmi=30, chest=0.15)[0]) > radius(plain) * 1.02


def test_errors_carry_the_programs_messages(tmp_path):
    _, err = run_drape("body", "--bmi", 80, "--out", tmp_path / "b.obj", expect=2)
    with pytest.raises(drape.ConfigError) as e:
        drape.body(bmi=80)
    assert isinstance(e.value, ValueError) and isinstance(e.value, drape.Error)
    assert str(e.value) in err and "\n" not in str(e.value)
    _, err = run_drape("body", "--bmi", 30, "--girth", "chst=0.1", "--out", tmp_path / "b.obj", expect=2)
    with pytest.raises(drape.ConfigError) as e:
        drape.body(bmi=30, chst=0.1)
    assert str(e.value) in err and "chest" in str(e.value)
    with pytest.raises(ValueError, match="chest: expected a number"):
        drape.body(bmi=30, chest="wide")
    with pytest.raises(drape.ConfigError, match="unknown|no plugin|did you mean"):
        drape.BodyModel("parametrik")
    with pytest.raises(ValueError, match=r"shape: expected a float array of shape \[9\]"):
        drape.BodyModel().vertices(np.zeros(3))


def test_plugins_are_listed():
    kinds = {p["name"]: p["kind"] for p in drape.plugins()}
    assert kinds["parametric"] == "body" and kinds["stretching"] == "energy" and kinds["tshirt"] == "garment"
    assert drape.plugin_search_path()


@pytest.mark.parametrize("sex", [0, 1])
@pytest.mark.parametrize("height", [1.5, 2.0])
def test_heavy_corners_keep_human_proportions(sex, height):
    """Issue 21's report: at BMI 65 a woman's hips were 1.20 times her shoulders and her ankles thinner than
    her wrists would be on a person (1.24 times the wrist girth; MakeHuman 1.26-1.48 over BMI 20-39). Measured
    on the mesh alone by scripts/figures/body_proportions.py (slices and tape girths, no drape code)."""
    sys.path.insert(0, str(SOURCE / "scripts" / "figures"))
    from body_proportions import measure

    v, f = drape.body(bmi=65, height=height, sex=sex)
    m = measure(np.asarray(v, dtype=np.float64), np.asarray(f))
    assert m["hip/sh"] <= 1.15, m
    assert 1.35 <= m["ank/wr"] <= 2.0, m


def test_a_body_that_passes_through_itself_is_named(tmp_path):
    """Girths that clash (broad arms on a BMI 10 torso: sample 1018 of the 2,000-drape run) make upper arms
    that cross the torso in the armpits; drape body writes the body asked for, and says so."""
    clash = ["--girth", "arms=0.110223", "--girth", "belly=0.0659977", "--girth", "chest=-0.0387222",
             "--girth", "hips=0.125589", "--girth", "thighs=0.0889141", "--girth", "waist=0.00915949"]
    _, err = run_drape("body", "--bmi", 10.2426, "--height", 1.77352, "--sex", 1, *clash, "--out", tmp_path / "b.obj")
    assert "passes through itself" in err and "girths clash" in err
    _, err = run_drape("body", "--bmi", 10.2426, "--height", 1.77352, "--sex", 1, "--out", tmp_path / "plain.obj")
    assert "passes through itself" not in err


def test_unpose_reads_the_pose_off_a_posed_mesh(tmp_path):
    # A body posed and turned by the drape program; BodyModel.unpose gives back the angles it was posed by and the
    # body at rest (drape.body's, turned the same way).
    human = drape.BodyModel("parametric", {"rig": "human"})
    pose = {"left_shoulder_abduction": 65, "right_elbow_flexion": 55, "neck_twist": -20, "left_knee_flexion": 30}
    run_drape("body", "--param", "rig=human", "--bmi", "44", "--sex", "0", "--height", "1.6", "--pose",
              ",".join(f"{k}={v}" for k, v in pose.items()), "--out", tmp_path / "posed.obj")
    posed, _ = read_obj(tmp_path / "posed.obj")
    t = np.radians(-70.0)
    turn = np.array([[np.cos(t), 0, np.sin(t)], [0, 1, 0], [-np.sin(t), 0, np.cos(t)]])
    shift = np.array([0.5, 0.0, -2.0])
    read = human.unpose(posed @ turn.T + shift)
    for angle, degrees in pose.items():
        assert abs(read["pose"][angle] - degrees) < 0.5, angle
    assert abs(read["pose"]["right_knee_flexion"]) < 0.5
    rest, _ = drape.body(bmi=44, sex=0.0, height=1.6, params={"rig": "human"})
    assert np.abs(read["rest"] - (rest @ turn.T + shift)).max() < 1e-3
    assert read["fit_rms"] < 1e-3 and read["reposed_error"] < 1e-3
    assert any("faces -70.0 degrees" in n for n in read["notes"])
    with pytest.raises(ValueError, match=r"\[N, 3\] \(N = 6904\)"):
        human.unpose(posed[:100])


def test_unpose_finds_the_arm_a_fit_from_rest_misses():
    # Held-out posed drapes (seed 2): body 3's left arm, near the horizontal, was read from rest with its rotation at
    # the end of its range (2.3 mm rms, 11 mm at most from the mesh), body 34's right arm as another set of angles
    # outside the sampling ranges (both fixed by fitting the arm again from the middle of the sampling ranges), and
    # body 2's right arm (87.6, 52.2, 11.6) as 92.4, -11.7, -52.5, which turn the arm the same to 0.05 mm (fixed by
    # choosing, among the sets that turn the bone the same, the one within the sampling ranges).
    d = drape.Dataset(str(SOURCE / "datasets" / "posespace-human-heldout" / "seed2-50.h5"))
    human = drape.BodyModel("parametric", {"rig": "human"})
    for i in (2, 3, 34):
        s = d[i]
        truth = dict(zip(d.layout["pose_angles"], map(float, s["pose"])))
        read = human.unpose(np.asarray(s["body"], dtype=np.float64))
        assert read["fit_max"] < 1e-3, i
        worst = max(abs(read["pose"][k] - v) for k, v in truth.items())
        assert worst < 1.5, (i, worst)


def test_vertices_of_a_strided_shape_are_those_of_its_values():
    """A view (every other element, reversed) is read as its values: it was read as contiguous memory, a
    different body for shape[::2] and memory before the buffer for shape[::-1]."""
    model = drape.BodyModel("parametric")
    shape = model.solve(bmi=30)
    wide = np.zeros(2 * shape.size)
    wide[::2] = shape
    np.testing.assert_array_equal(model.vertices(wide[::2]), model.vertices(shape))
    backwards = shape[::-1].copy()
    np.testing.assert_array_equal(model.vertices(backwards[::-1]), model.vertices(shape))
