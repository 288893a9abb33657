"""Shards of one garment made before and after sizes were added to its chart merge into one chart (the sizes
of either, smallest first), and so do they when read as one dataset (a glob pattern) for training; shards whose
charts disagree on a size they share are refused, naming the size. The charts are rewritten with h5py, as a
shard made by an older drape would carry them."""
import shutil

import drape
import h5py

from conftest import SOURCE, penalty_scene, run_drape


def size_auto_shard(tmp_path):
    scene = penalty_scene(tmp_path / "penalty.yaml")
    auto = tmp_path / "auto.yaml"
    auto.write_text(f"base: {scene}\ngarment: {{params: {{size: auto}}}}\n")
    out = tmp_path / "new.h5"
    run_drape("generate", auto, "--count", 4, "--bmi", "12:40", "--seed", 3, "--threads", 1, "--out", out, expect=(0, 1))
    return out


def chart_of(path):
    with h5py.File(path, "r") as f:
        return f.attrs["size_chart"].decode() if isinstance(f.attrs["size_chart"], bytes) else f.attrs["size_chart"]


def set_chart(path, text):
    with h5py.File(path, "r+") as f:
        f.attrs["size_chart"] = text.encode()
    raw = bytearray(path.read_bytes())
    raw[:512] = bytes(512)  # unsealed, as h5py leaves a file it wrote (drape reads such a file unchecked)
    path.write_bytes(bytes(raw))


def sizes_of(text):
    return [item.split("=")[0].strip() for item in text.split(";")[2].split(",")]


def without_small_sizes(new, old):
    """`old`: a copy of shard `new` whose chart is the same without the sizes below small."""
    head, design_ease, sizes = chart_of(new).split(";")
    kept = [s for s in sizes.split(",") if s.split("=")[0].strip() not in ("3xsmall", "2xsmall", "xsmall")]
    shutil.copy(new, old)
    set_chart(old, ";".join([head, design_ease, ",".join(kept)]))


def test_a_chart_without_the_small_sizes_joins_the_full_one(tmp_path):
    new = size_auto_shard(tmp_path)
    full = chart_of(new)
    assert sizes_of(full)[:4] == ["3xsmall", "2xsmall", "xsmall", "small"]
    old = tmp_path / "old.h5"
    without_small_sizes(new, old)  # the same garment's chart as it was before the sizes below small
    merged = tmp_path / "merged.h5"
    run_drape("dataset", "merge", "--mixed-sizes", "--out", merged, old, new)
    assert chart_of(merged) == full
    run_drape("dataset", "merge", "--mixed-sizes", "--force", "--out", merged, new, old)
    assert chart_of(merged) == full


def test_shards_of_one_auto_scene_merge_and_expand_to_the_joined_chart(tmp_path):
    # Shards of one `size: auto` scene need no --mixed-sizes; their charts are joined all the same (the
    # first one's used to be kept), and so are they when slim shards are expanded.
    new = size_auto_shard(tmp_path)
    full = chart_of(new)
    old = tmp_path / "old.h5"
    without_small_sizes(new, old)
    merged = tmp_path / "merged.h5"
    run_drape("dataset", "merge", "--out", merged, old, new)
    assert chart_of(merged) == full
    slims = []
    for shard in (old, new):
        slims.append(tmp_path / ("slim-" + shard.name))
        run_drape("dataset", "slim", shard, "--out", slims[-1])
    assert sizes_of(chart_of(slims[0]))[0] == "small"
    expanded = tmp_path / "expanded.h5"
    run_drape("dataset", "expand", "--out", expanded, *slims)
    assert chart_of(expanded) == full


def test_a_model_trained_on_both_as_one_pattern_knows_every_size(tmp_path):
    new = size_auto_shard(tmp_path)
    (tmp_path / "old").mkdir()
    without_small_sizes(new, tmp_path / "old" / "a.h5")
    model = tmp_path / "m.h5"
    # The old shard first: the chart the model keeps used to be the first file's.
    pattern = str(tmp_path / "{old/a,new}.h5")
    run_drape("train", SOURCE / "graphs" / "sizes" / "drape_grade.yaml", "--data", pattern,
              "--out", model, "--epochs", 1, "--k", 16, "-q")
    info, _ = run_drape("model", "info", model)
    assert "3xsmall" in info and "6xlarge" in info, info
    # The pattern is what the model records as its data, and what model info
    # shows, whole: its last component alone was "new}.h5", its file name
    # (an alternative with a folder in it) "a,new}.h5".
    assert "{old/a,new}.h5" in info.split("dataset", 1)[1].splitlines()[0], info
    # (Its domain counts samples and distinct bodies: the old shard holds the
    # new one's bodies less the small sizes, so they differ here.)
    assert info.split("domain:", 1)[1].splitlines()[0].endswith(" from " + pattern), info
    assert drape.dataset_name(pattern) == pattern and drape.dataset_name(str(new)) == "new.h5"


def test_charts_that_differ_on_a_shared_size_are_refused(tmp_path):
    new = size_auto_shard(tmp_path)
    full = chart_of(new)
    other = tmp_path / "other.h5"
    shutil.copy(new, other)
    head, design_ease, sizes = full.split(";")
    items = [s.strip().split("=") for s in sizes.split(",")]
    moved = [f"{name}={float(girth) + 0.01 if name == 'large' else girth}" for name, girth in items]
    set_chart(other, ";".join([head, design_ease, " " + ", ".join(moved)]))  # large 1 cm wider
    merged = tmp_path / "merged.h5"
    _, err = run_drape("dataset", "merge", "--mixed-sizes", "--out", merged, new, other, expect=2)
    assert "size charts differ in size large" in err
    assert not merged.exists()


def test_bench_accuracy_time_drapes_a_body_of_an_older_chart_in_todays_size(tmp_path):
    """A test body simulated in another size than the scene's tailor's rule gives it today (a thin body of the
    shards made before the sizes below small was stored in the small): the bench simulates its references
    today, so every method drapes it in today's size and says so; it used to stop at that body with "the
    garment's grade is ... but the scene dresses this body in ..."."""
    data = size_auto_shard(tmp_path)
    with h5py.File(data, "r") as f:
        test = [i for i, s in enumerate(f["split"][:]) if s == 2]
    assert test, "the tiny shard has no test body"
    with h5py.File(data, "r+") as f:
        grades = f["stats"]["garment_grade"][:]
        grades[test[0]] += 0.1  # another size than the rule's
        f["stats"]["garment_grade"][:] = grades
    raw = bytearray(data.read_bytes())
    raw[:512] = bytes(512)  # unsealed, as h5py leaves a file it wrote
    data.write_bytes(bytes(raw))
    model = tmp_path / "m.h5"
    run_drape("train", SOURCE / "graphs" / "sizes" / "drape_grade.yaml", "--data", data, "--out", model,
              "--epochs", 1, "--k", 16, "-q")
    out, _ = run_drape("bench", "accuracy-time", "--data", data, "--model", model, "--bodies", 1, "--budgets", "1:1",
                       "--iterations", 1, "--spectral-k", 0, "--reference-settle", 1)
    assert "1 of 1 test bodies were simulated in another size than the scene chooses today" in out, out
    assert "| network |" in out and "| network + 1 optimisation iterations |" in out, out
