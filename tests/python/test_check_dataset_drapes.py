"""scripts/check_dataset_drapes.py on hand-made datasets: a sheet above a closed box is clean, one with a vertex
inside is not, body faces of another topology than the dataset's bodies are refused (not checked into nonsense),
and the body it makes itself is the recorded scene's (the human rig's for the human rig's drapes)."""
import importlib.util
import subprocess
import sys

import h5py
import numpy as np

from conftest import SOURCE

SCRIPT = SOURCE / "scripts" / "check_dataset_drapes.py"
spec = importlib.util.spec_from_file_location("check_dataset_drapes", SCRIPT)
check = importlib.util.module_from_spec(spec)
sys.path.insert(0, str(SOURCE / "scripts"))
spec.loader.exec_module(check)

# A closed unit box, outward-facing triangles.
BOX_V = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
BOX_F = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
# A two-triangle sheet 0.2 above the box's top.
SHEET_V = np.array([[0.1, 1.2, 0.1], [0.9, 1.2, 0.1], [0.9, 1.2, 0.9], [0.1, 1.2, 0.9]])
SHEET_F = np.array([[0, 1, 2], [0, 2, 3]])


def write_dataset(path, sheet, scene="", global_index=None, slim=False):
    with h5py.File(path, "w") as f:
        f["done"] = np.array([1], dtype=np.uint8)
        if not slim:
            f["bodies/vertices"] = BOX_V[None].astype(np.float32)
        if global_index is not None:
            f["stats/global_index"] = np.array([float(global_index)])
        f["garments/vertices"] = sheet[None].astype(np.float32)
        f["garments/faces"] = SHEET_F.astype(np.int32)
        f["stats/converged"] = np.array([1.0])
        f["stats/bmi"] = np.array([25.0])
        if scene:
            f.attrs["scene"] = scene


def write_obj(path, v, faces):
    with open(path, "w") as out:
        out.writelines(f"v {x} {y} {z}\n" for x, y, z in v)
        out.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)


def run(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True, text=True)


def test_a_sheet_outside_is_clean_and_one_through_the_body_is_not(tmp_path):
    faces = tmp_path / "box.obj"
    write_obj(faces, BOX_V, BOX_F)
    write_dataset(tmp_path / "out.h5", SHEET_V)
    r = run(tmp_path / "out.h5", "--body-faces", faces)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "1 of 1 drapes clean" in r.stdout
    inside = SHEET_V.copy()
    inside[2, 1] = 0.5   # one corner into the box: inside, and its edges through the top
    write_dataset(tmp_path / "in.h5", inside)
    r = run(tmp_path / "in.h5", "--body-faces", faces)
    assert r.returncode == 1
    assert "NOT CLEAN" in r.stdout and "p 25.00 %" in r.stdout and "0 of 1 drapes clean" in r.stdout
    assert "not clean: global index" not in r.stdout  # (a file without the generator's numbering)


def test_a_drape_not_clean_is_named_by_its_global_index_for_slim_drop(tmp_path):
    faces = tmp_path / "box.obj"
    write_obj(faces, BOX_V, BOX_F)
    inside = SHEET_V.copy()
    inside[2, 1] = 0.5
    write_dataset(tmp_path / "in.h5", inside, global_index=450)
    r = run(tmp_path / "in.h5", "--body-faces", faces, "--csv", tmp_path / "c.csv")
    assert r.returncode == 1
    assert f"not clean: global index 450 (`drape dataset slim {tmp_path / 'in.h5'} --out SLIM --drop 450`" in r.stdout
    header, row = (tmp_path / "c.csv").read_text().splitlines()
    assert dict(zip(header.split(","), row.split(",")))["global_index"] == "450"


def test_a_slim_file_is_refused_with_the_expand_that_makes_it_checkable(tmp_path):
    write_dataset(tmp_path / "slim.h5", SHEET_V, slim=True)
    faces = tmp_path / "box.obj"
    write_obj(faces, BOX_V, BOX_F)
    r = run(tmp_path / "slim.h5", "--body-faces", faces)
    assert r.returncode != 0
    assert "a slim dataset" in r.stderr and "drape dataset expand" in r.stderr


def test_faces_of_another_topology_are_refused(tmp_path):
    faces = tmp_path / "smaller.obj"
    write_obj(faces, BOX_V[:4], BOX_F[:2])   # faces of a 4-vertex mesh against 8-vertex bodies
    write_dataset(tmp_path / "d.h5", SHEET_V)
    r = run(tmp_path / "d.h5", "--body-faces", faces)
    assert r.returncode != 0
    assert "its bodies have 8 vertices, the body faces index 4" in r.stderr


def test_the_body_made_here_is_the_recorded_scenes(tmp_path):
    write_dataset(tmp_path / "human.h5", SHEET_V,
                  scene="description: x\nbody:\n  model: parametric\n  params: {rig: human}\n  shape: {bmi: 24}\n")
    assert check.scene_body_args(str(tmp_path / "human.h5")) == ["--model", "parametric", "--param", "rig=human"]
    write_dataset(tmp_path / "none.h5", SHEET_V)
    assert check.scene_body_args(str(tmp_path / "none.h5")) == []
