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


def test_a_body_mesh_in_another_vertex_order_or_mirrored_is_refused(tmp_path):
    # Only the vertex count was checked: a body whose vertices a tool re-indexed (the faces say so) was read
    # vertex by vertex as other parts of the body, and a mirrored one (inside out) was draped with warnings of a
    # negative BMI.
    from conftest import read_obj
    body = tmp_path / "body.obj"
    run_drape("body", "--bmi", 30, "--param", "rig=human", "--out", body)
    vertices, faces = read_obj(body)[:2]
    run_drape("predict", "--body", body, "--out", tmp_path / "x.obj")  # as made: draped
    order = np.random.default_rng(0).permutation(len(vertices))
    new_index = np.empty_like(order)
    new_index[order] = np.arange(len(order))
    shuffled = tmp_path / "shuffled.obj"
    write_obj(shuffled, vertices[order], new_index[faces])  # the same surface, re-indexed
    _, err = run_drape("predict", "--body", shuffled, "--out", tmp_path / "x.obj", expect=2)
    assert str(shuffled) in err and "not the body model's" in err, err
    mirrored = tmp_path / "mirrored.obj"
    write_obj(mirrored, vertices * np.array([-1.0, 1.0, 1.0]), faces)
    _, err = run_drape("predict", "--body", mirrored, "--out", tmp_path / "x.obj", expect=2)
    assert str(mirrored) in err and "mirrored or inside out" in err, err


def test_a_body_with_two_vertices_swapped_or_given_as_shuffled_points_is_refused(tmp_path):
    # The 9-in-10 edge rule lets two swapped vertices pass (their faces re-indexed with them: the same surface),
    # and a body given as points has no faces to test: read through the model's faces, both have edges that jump
    # across the body. The bodies of the model's space stretch an edge of its mean body under 5 times.
    from conftest import read_obj
    body = tmp_path / "body.obj"
    run_drape("body", "--bmi", 30, "--param", "rig=human", "--out", body)
    vertices, faces = read_obj(body)[:2]
    swap = np.arange(len(vertices))
    swap[[100, 5000]] = [5000, 100]  # a vertex of one end of the body and one of the other
    swapped = tmp_path / "swapped.obj"
    write_obj(swapped, vertices[swap], swap[faces])  # (swap is its own inverse)
    _, err = run_drape("predict", "--body", swapped, "--out", tmp_path / "x.obj", expect=2)
    assert str(swapped) in err and "not in the body model's order" in err, err
    points = tmp_path / "points.obj"
    write_obj(points, vertices, [])
    run_drape("predict", "--body", points, "--out", tmp_path / "x.obj")  # in the model's order: draped
    shuffled = tmp_path / "shuffled_points.obj"
    write_obj(shuffled, vertices[np.random.default_rng(0).permutation(len(vertices))], [])
    _, err = run_drape("predict", "--body", shuffled, "--out", tmp_path / "x.obj", expect=2)
    assert str(shuffled) in err and "not in the body model's order" in err, err


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        f.writelines(f"v {x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in vertices)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)


def test_a_plugins_own_parameter_check_names_the_file_and_line(tmp_path):
    # The plugin's message knew no file ("cnn1d: parameter 'channels' needs at least one layer").
    graph = tmp_path / "g.yaml"
    text = (SOURCE / "graphs" / "drape.yaml").read_text()
    assert "channels: [32, 64, 64]" in text
    graph.write_text(text.replace("channels: [32, 64, 64]", "channels: []", 1))
    line = next(i + 1 for i, l in enumerate(graph.read_text().splitlines()) if "channels: []" in l)
    _, err = run_drape("graph", "check", graph, "--resolution", "coarse", expect=2)
    assert "needs at least one layer" in err and f"{graph}:" in err, err
    assert abs(int(err.split(f"{graph}:")[1].split(":")[0]) - line) <= 3, err  # the node's line, beside the parameter


def test_an_empty_pose_on_the_command_line_is_refused(tmp_path):
    # --pose "" was read as the rest pose (the library keeps that for Python's pose=""): on a command line it is
    # more likely a shell variable that was never set, and the user would get an A-pose drape without a word.
    for command in (["body", "--pose", "", "--out", tmp_path / "b.obj"],
                    ["body", "--pose", "  ", "--out", tmp_path / "b.obj"],
                    ["predict", "--bmi", 30, "--pose", "", "--out", tmp_path / "x.obj"]):
        _, err = run_drape(*command, expect=2)
        assert "--pose is empty" in err, err
    assert not (tmp_path / "b.obj").exists() and not (tmp_path / "x.obj").exists()


def test_a_damaged_size_chart_names_the_model_file(tmp_path):
    # "the model's size_chart: not a size chart": which model's, the message did not say.
    model = unsealed_copy(SOURCE / "models" / "tshirt-coarse-human.h5", tmp_path / "chart.h5")
    with h5py.File(model, "r+") as f:
        assert "size_chart" in f["meta"].attrs
        f["meta"].attrs["size_chart"] = b"design=; x=abc"
    for command in (["model", "info", model], ["predict", "--model", model, "--bmi", 30, "--out", tmp_path / "x.obj"]):
        _, err = run_drape(*command, expect=2)
        assert f"{model}: /meta size_chart: not a size chart" in err, err


def test_a_negative_count_or_sample_is_refused_not_wrapped(tmp_path):
    # Read as unsigned, -1 became 18446744073709551615: a dataset of that many drapes, a sample past the end.
    _, err = run_drape("generate", SOURCE / "graphs" / "scenes" / "tshirt_coarse.yaml", "--count", "-1",
                       "--out", tmp_path / "g.h5", expect=2)
    assert "--count N (N >= 1)" in err, err
    assert not (tmp_path / "g.h5").exists()
    _, err = run_drape("render", "--data", POSED_SHARD, "--sample", "-1", "--simulated", "--out", tmp_path / "r.svg",
                       expect=2)
    assert "--sample -1: a sample index is 0 or more" in err, err
