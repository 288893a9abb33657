"""drape train --encoder-body (docs/bodies.md, "One encoder for both rigs"): a model of the human rig whose encoder
reads the body resampled onto the mannequin's vertices (the resample_body node), trained, saved, loaded and used on
human-rig bodies; the losses and the push-out keep the real body."""
import numpy as np
import pytest

import drape
from conftest import SOURCE, run_drape

HUMAN_SHARD = SOURCE / "datasets" / "bodyspace2000-human" / "shard-00-of-40.h5"

GRAPH = """
inputs:
  body: [body_vertices, 3]
  target: [garment_vertices, 3]
nodes:
  shape: { type: resample_body, in: body }
  encoder: { type: cnn1d, in: shape, params: { channels: [4], kernel: 5, stride: 8, activation: tanh } }
  gathered: { type: gather, in: encoder.features }
  decoder: { type: mlp, in: gathered, params: { widths: [8], activation: tanh } }
  garment: { type: add_template, in: decoder }
outputs: { garment: garment }
losses:
  v2v: 1.0
"""


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("encoder_body")
    graph = tmp / "g.yaml"
    graph.write_text(GRAPH)
    out = tmp / "m.h5"
    run_drape("train", graph, "--data", HUMAN_SHARD, "--out", out, "--epochs", 1, "--k", 8, "--threads", 1,
              "--encoder-body", "parametric", "--quiet")
    return out


def test_the_model_reads_human_bodies_through_the_mannequins_vertices(model):
    m = drape.Model.load(str(model))
    human, _ = drape.body(30, 1.7, 0, params={"rig": "human"})
    mannequin, _ = drape.body(30, 1.7, 0)
    assert np.asarray(m.assets.body_vertices).shape == human.shape  # the real body: losses, push-out
    corr = np.asarray(m.assets.correspondence)
    assert corr.max() < len(mannequin) < len(human)  # the garment reads the encoder's (mannequin's) rows
    g = m.predict(human.astype(np.float32), check=False)
    assert g.shape == (991, 3) and np.isfinite(g).all()
    with pytest.raises(Exception, match=str(len(human))):
        m.predict(mannequin.astype(np.float32), check=False)
    info, _ = run_drape("model", "info", model)
    assert "encoder body   parametric" in info


def test_the_shipped_human_graph_trains_from_every_weight_of_the_mannequin_model(tmp_path):
    """graphs/human/drape_grade_v2v1000_post_resampled.yaml from models/tshirt-coarse.h5 with plain --init: every
    weight has its shape (the mannequin's hierarchy, the full eigenbasis), one epoch on a tenth of a shard."""
    out = tmp_path / "h.h5"
    stdout, err = run_drape("train", SOURCE / "graphs" / "human" / "drape_grade_v2v1000_post_resampled.yaml", "--data",
                            HUMAN_SHARD, "--out", out, "--epochs", 1, "--fraction", 0.1, "--threads", 1,
                            "--encoder-body", "parametric", "--init", SOURCE / "models" / "tshirt-coarse.h5", "--quiet")
    assert "keeps its initialisation" not in stdout + err
    # ... and what they are tied to is the mannequin model's: its correspondences, hierarchy and eigenvectors.
    assert "was trained on other assets" not in stdout + err
    m = drape.Model.load(str(out))
    human, _ = drape.body(45, 1.8, 1, params={"rig": "human"})
    g = m.predict(human.astype(np.float32), garment_size=1.5, check=False)
    assert g.shape == (991, 3) and np.isfinite(g).all()


def test_without_the_encoder_body_the_graph_is_refused(tmp_path):
    graph = tmp_path / "g.yaml"
    graph.write_text(GRAPH)
    _, err = run_drape("train", graph, "--data", HUMAN_SHARD, "--out", tmp_path / "m.h5", "--epochs", 1, "--k", 8,
                       "--threads", 1, "--quiet", expect=2)
    assert "--encoder-body" in err


def test_a_start_on_other_assets_is_said(tmp_path):
    """The mannequin model started on the human rig's own assets (--init-partial, no encoder body): the weights
    load where their shapes allow, and the warning says what they are tied to that differs."""
    _, err = run_drape("train", SOURCE / "graphs" / "sizes" / "drape_grade_v2v1000_post.yaml", "--data", HUMAN_SHARD,
                       "--out", tmp_path / "p.h5", "--epochs", 1, "--fraction", 0.1, "--threads", 1, "--init-partial",
                       "--init", SOURCE / "models" / "tshirt-coarse.h5", "--quiet")
    assert "was trained on other assets" in err
    assert "the correspondences index 6490 body points there and 6904 here" in err
    assert "eigenvectors are others" in err


POSED_HUMAN_SHARD = SOURCE / "datasets" / "posespace2000-human" / "shard-00-of-40.h5"


def test_the_posed_human_graph_trains_from_every_weight_of_the_mannequin_posed_model(tmp_path):
    """graphs/human/drape_posed_v2v1000_post_resampled.yaml (the shipped posed graph, its encoder reading the rest
    body resampled) from models/tshirt-coarse-posed.h5 with plain --init, on the human rig's posed drapes: every
    weight has its shape; the model poses the garment with the human rig's skeleton."""
    out = tmp_path / "ph.h5"
    stdout, err = run_drape("train", SOURCE / "graphs" / "human" / "drape_posed_v2v1000_post_resampled.yaml", "--data",
                            POSED_HUMAN_SHARD, "--out", out, "--epochs", 1, "--fraction", 0.1, "--threads", 1,
                            "--encoder-body", "parametric", "--init", SOURCE / "models" / "tshirt-coarse-posed.h5",
                            "--quiet")
    assert "keeps its initialisation" not in stdout + err
    assert "was trained on other assets" not in stdout + err
    m = drape.Model.load(str(out))
    human, _ = drape.body(30, 1.7, 0, params={"rig": "human"})
    rest = m.predict(human.astype(np.float32), garment_size=1.2, check=False)
    raised = m.predict(human.astype(np.float32), garment_size=1.2, check=False, pose={"shoulder_abduction": 90})
    assert rest.shape == raised.shape == (991, 3) and np.isfinite(raised).all()
    # The sleeves go up with the arms: their vertices (beyond 19 cm from the middle at rest) rise by centimetres.
    sleeves = np.abs(rest[:, 0] - rest[:, 0].mean()) > 0.19
    assert sleeves.sum() > 100
    assert raised[sleeves, 1].mean() > rest[sleeves, 1].mean() + 0.03


@pytest.mark.parametrize("name", ["transfer48", "fine_encoder"])
def test_a_widened_posed_graph_starts_as_the_model_it_widens(tmp_path, name):
    """The capacity experiments of docs/poses.md ("More capacity on the human rig"): the shipped posed graph with
    inputs added (a wider decoder input, a second encoder), started with --init-widen from a model of the graph
    without them. Every weight that reads the new features starts at zero, so before any step the widened model
    predicts what the model it widens predicts; training at a learning rate of 1e-30 changes no weight. (The start
    is the mannequin's posed model, whose weights the plain human graph takes as they are; both trained here the
    same way, so the two predictions differ only by what the widening adds.)"""
    start = SOURCE / "models" / "tshirt-coarse-posed.h5"
    common = ["--data", POSED_HUMAN_SHARD, "--epochs", 1, "--fraction", 0.05, "--lr", 1e-30, "--threads", 1,
              "--encoder-body", "parametric", "--init", start]
    plain, wide = tmp_path / "plain.h5", tmp_path / "wide.h5"
    run_drape("train", SOURCE / "graphs" / "human" / "drape_posed_v2v1000_post_resampled.yaml", "--out", plain,
              *common, "--quiet")
    stdout, err = run_drape("train", SOURCE / "graphs" / "human" / f"drape_posed_v2v1000_post_resampled_{name}.yaml",
                            "--out", wide, *common, "--init-widen")
    assert "the new input rows start at zero" in stdout + err
    # ...and the new weights are really in the graph (not a graph equal to the plain one).
    assert "is new (not in the file)" in stdout + err
    body, _ = drape.body(45, 1.65, 1, params={"rig": "human"})
    pose = {"shoulder_abduction": 60, "elbow_flexion": 40, "spine_twist": 10}
    a = drape.Model.load(str(wide)).predict(body.astype(np.float32), garment_size=1.4, check=False, pose=pose)
    b = drape.Model.load(str(plain)).predict(body.astype(np.float32), garment_size=1.4, check=False, pose=pose)
    assert a.shape == b.shape == (991, 3) and np.isfinite(a).all()
    assert np.abs(a - b).max() < 1e-5


def test_the_shipped_posed_model_is_of_the_wide_graph(tmp_path):
    """models/tshirt-coarse-posed-human.h5 holds the decoder input 48 wide (docs/poses.md): the graph of L_V2V it was
    trained with until the thirty-first session takes every weight of its shape with plain --init (its graph since,
    L_V2V replaced by the mean vertex distance: test_the_posed_graph_trained_on_the_metric below)."""
    stdout, err = run_drape("train", SOURCE / "graphs" / "human" / "drape_posed_v2v1000_post_resampled_transfer48_margin1mm.yaml",
                            "--data", POSED_HUMAN_SHARD, "--out", tmp_path / "m.h5", "--epochs", 1, "--fraction", 0.05,
                            "--threads", 1, "--encoder-body", "parametric", "--init",
                            SOURCE / "models" / "tshirt-coarse-posed-human.h5", "--monitor", "v2v", "--quiet")
    assert "keeps its initialisation" not in stdout + err
    # The shipped model's own graph has the 1 mm margin, its training chose the best epoch by the validation ME, and
    # its push-out clears 5 mm since the thirty-second session (docs/poses.md, "All of seed 6").
    info, _ = run_drape("model", "info", SOURCE / "models" / "tshirt-coarse-posed-human.h5")
    assert "best epoch by the validation vertex_distance loss" in info and "within 5.0 mm" in info, info
    assert "mirror average" in info, info


def test_the_posed_graph_trained_on_the_metric(tmp_path):
    """graphs/human/drape_posed_v2v1000_post_resampled_transfer48_margin1mm_distance.yaml (L_V2V replaced by the mean
    vertex distance, docs/poses.md, "Training on the metric") starts from the shipped posed model with every weight of
    its shape, chooses its best epoch by the validation ME, and its loss is the mean distance it reports."""
    stdout, err = run_drape("train", SOURCE / "graphs" / "human" / "drape_posed_v2v1000_post_resampled_transfer48_margin1mm_distance.yaml",
                            "--data", POSED_HUMAN_SHARD, "--out", tmp_path / "m.h5", "--epochs", 1, "--fraction", 0.05,
                            "--threads", 1, "--encoder-body", "parametric", "--init",
                            SOURCE / "models" / "tshirt-coarse-posed-human.h5", "--monitor", "vertex_distance", "--lr", 1e-6)
    text = stdout + err
    assert "keeps its initialisation" not in text
    assert "the best epoch by its vertex_distance loss" in text, text
    assert "v2v" not in text.split("epoch 1/1", 1)[1].split("\n", 1)[0], text  # the loss is replaced, not added
    # At lr 1e-6 the weights barely move: the validation loss is the shipped model's ME on those bodies (in m, the
    # network alone), a centimetre or two.
    val = float(text.split("vertex_distance ")[-1].split("]")[0])
    assert 0.005 < val < 0.03, text
