"""Shipped files by name from any folder (drape/io/shipped_files.hpp): the drape program and the module find
graphs/..., models/... from a temporary folder through $DRAPE_DATA_DIR, the installed share/drape or, for this
build tree, the source tree; a file that is nowhere is refused naming where drape looked."""
import os
import subprocess

import pytest

import drape
from conftest import COARSE, DRAPE, SOURCE


def drape_in(cwd, *args, env=None, expect=0):
    p = subprocess.run([str(DRAPE), *map(str, args)], capture_output=True, text=True, timeout=300, cwd=cwd,
                       env={**os.environ, **(env or {})})
    assert p.returncode in (expect if isinstance(expect, tuple) else (expect,)), f"drape {' '.join(map(str, args))} exited {p.returncode}:\n{p.stdout}\n{p.stderr}"
    return p.stdout, p.stderr


def test_model_info_by_name_from_elsewhere(tmp_path):
    out, _ = drape_in(tmp_path, "model", "info", "models/tshirt-coarse.h5")
    assert out.splitlines()[0] == str(SOURCE / "models" / "tshirt-coarse.h5")
    assert "domain" in out


def test_simulate_a_scene_of_the_data_dir(tmp_path):
    # A cheap scene (one settle step from the dressed state) under $DRAPE_DATA_DIR, named as a shipped one.
    data = tmp_path / "data"
    (data / "graphs" / "scenes").mkdir(parents=True)
    (data / "graphs" / "scenes" / "tiny.yaml").write_text(
        f"base: {COARSE}\neffects: {{barrier: null}}\nsolver: {{morph_steps: 0, settle_steps: 1, max_newton_iterations: 8, linear_solver: eigen}}\n")
    work = tmp_path / "work"
    work.mkdir()
    # One step does not settle it: exit 1 with the drape written all the same.
    out, _ = drape_in(work, "simulate", "graphs/scenes/tiny.yaml", "--out", "g.obj", "--threads", 1,
                      env={"DRAPE_DATA_DIR": str(data), "OMP_WAIT_POLICY": "passive"}, expect=(0, 1))
    assert f"simulating {data / 'graphs' / 'scenes' / 'tiny.yaml'}:" in out
    assert (work / "g.obj").stat().st_size > 0 and "wrote g.obj" in out


def test_simulate_finds_the_shipped_scene(tmp_path):
    # Simulating the shipped scene takes ~20 s: a body file that is not there stops drape once the scene is
    # found and built, which is what this checks (the refusal names the body, not the scene).
    _, err = drape_in(tmp_path, "simulate", "graphs/scenes/tshirt_coarse.yaml", "--body", "absent.obj", expect=2)
    assert "absent.obj" in err and "tshirt_coarse.yaml" not in err


def test_a_missing_file_names_where_it_looked(tmp_path):
    _, err = drape_in(tmp_path, "simulate", "graphs/scenes/nope.yaml", env={"DRAPE_DATA_DIR": str(tmp_path)},
                      expect=2)
    assert "graphs/scenes/nope.yaml: no such file (looked in " in err
    for where in (str(tmp_path), str(SOURCE)):
        assert where in err
    _, err = drape_in(tmp_path, "model", "info", "models/nope.h5", expect=2)
    assert "models/nope.h5: no such file (looked in " in err and str(SOURCE) in err


def test_the_module_finds_shipped_files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert drape.find_file("graphs/scenes/tshirt_coarse.yaml") == str(SOURCE / "graphs" / "scenes" / "tshirt_coarse.yaml")
    assert str(SOURCE) in drape.data_dirs()
    scene = drape.Scene("graphs/scenes/tshirt_coarse.yaml")
    assert "gravity" in scene.effects
    based = drape.Scene({"base": "graphs/scenes/tshirt_coarse.yaml", "effects": {"barrier": None}})
    assert "barrier" not in based.effects
    assert drape.Model.load("models/tshirt-coarse.h5").file == str(SOURCE / "models" / "tshirt-coarse.h5")
    (tmp_path / "graphs").mkdir()  # a file of that name in the current folder wins
    (tmp_path / "graphs" / "mine.yaml").write_text("x: 1\n")
    assert drape.find_file("graphs/mine.yaml") == "graphs/mine.yaml"
    with pytest.raises(drape.ConfigError, match=r"graphs/none\.yaml: no such file \(looked in .*"):
        drape.find_file("graphs/none.yaml")
