"""Damaged and hostile files that made the drape program crash, hang or read past an array (found by fuzzing
the command line, 2026-12-04): each is now refused with exit 2 and one line naming the file and the thing at
fault. The files are unsealed copies (a zero user block opens unchecked, docs/formats.md) edited with h5py, so
the damage gets past the checksum as a deliberate edit would."""
import shutil

import h5py
import numpy as np

from conftest import SOURCE, run_drape

POSED_MODEL = SOURCE / "models" / "tshirt-coarse-posed-human.h5"
POSED_SHARD = SOURCE / "datasets" / "posespace2000-human" / "shard-00-of-40.h5"


def unsealed_copy(source, target):
    shutil.copyfile(source, target)
    with open(target, "r+b") as f:
        f.write(b"\0" * 512)
    return target


def test_a_stored_body_that_cannot_be_made_is_refused_naming_the_sample(tmp_path):
    # The bodies are rebuilt from their stored shape in parallel: an error there ended the program
    # ("terminate called without an active exception", exit 134).
    data = unsealed_copy(POSED_SHARD, tmp_path / "nan_height.h5")
    with h5py.File(data, "r+") as f:
        f["bodies/params"][:, 0] = np.nan
    for command in (["eval", "--model", POSED_MODEL, "--data", data],
                    ["render", "--model", POSED_MODEL, "--data", data, "--sample", "0", "--simulated",
                     "--out", tmp_path / "r.svg"]):
        _, err = run_drape(*command, expect=2)
        assert str(data) in err and "sample" in err and "nan" in err, err
    data = unsealed_copy(POSED_SHARD, tmp_path / "bent_elbow.h5")
    with h5py.File(data, "r+") as f:
        f["bodies/pose"][:, :] = 1000.0
    _, err = run_drape("eval", "--model", POSED_MODEL, "--data", data, expect=2)
    assert str(data) in err and "outside its range of motion" in err, err


def test_a_model_with_a_damaged_domain_is_refused_when_loaded(tmp_path):
    # An index past the body in /domain/descriptor_vertices was read without a check (a segmentation fault);
    # a range of NaN or upside down gave warnings about "nan..nan" and "2..1.5".
    cases = {
        "descriptor_index": ("domain/descriptor_vertices", lambda a: a.__setitem__(0, 10**6), "descriptor_vertices"),
        "negative_index": ("domain/descriptor_vertices", lambda a: a.__setitem__(0, -5), "descriptor_vertices"),
        "nan_range": ("domain/param_range", lambda a: a.__setitem__((0, slice(None)), np.nan), "param_range"),
        "upside_down": ("domain/param_range", lambda a: a.__setitem__(0, a[0, ::-1]), "param_range"),
    }
    for name, (path, damage, said) in cases.items():
        model = unsealed_copy(POSED_MODEL, tmp_path / f"{name}.h5")
        with h5py.File(model, "r+") as f:
            a = f[path][()]
            damage(a)
            f[path][...] = a
        _, err = run_drape("predict", "--model", model, "--bmi", "30", "--out", tmp_path / "x.obj", expect=2)
        assert str(model) in err and said in err and "damaged" in err, (name, err)


def test_a_recursive_yaml_alias_is_refused_in_every_reader(tmp_path):
    # `a: &x [*x]` is an endless tree: every walk of it overflowed the stack (exit 139, nothing said).
    alias = tmp_path / "alias.yaml"
    alias.write_text("a: &x [*x]\n")
    for command in (["simulate", alias], ["graph", "check", alias],
                    ["body", "--pose-file", alias, "--out", tmp_path / "b.obj"]):
        _, err = run_drape(*command, expect=2)
        assert f"{alias}:1" in err and "recursive alias" in err, err
