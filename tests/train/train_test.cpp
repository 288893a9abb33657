// drape::train on tiny datasets: the loss falls, a seed reproduces the weights
// bit for bit, an interrupted run resumed gives the uninterrupted result,
// early stopping, and the refusals (existing output, other settings, another template).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <drape/io/checkpoint.hpp>
#include <drape/io/h5.hpp>

#include "train_test_util.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

// The largest |weight| of a checkpoint.
float largest_weight(const fs::path& file) {
  float largest = 0;
  for (const auto& [name, w] : test::weights_of(file))
    for (const float x : w) largest = std::max(largest, std::abs(x));
  return largest;
}

// The history without the wall-clock column.
std::map<std::string, std::vector<double>> history_of(const fs::path& file) {
  auto h = read_checkpoint(file).history;
  h.erase("seconds");
  return h;
}

struct TinyData {
  test::TempDir dir;
  fs::path data = dir / "data.h5";
  TinyData(int n = 16, int n_train = 12, int n_val = 4) { test::write_tiny_dataset(data, n, n_train, n_val); }
};

}  // namespace

TEST_CASE("training mlp_baseline reduces the loss and writes a loadable model", "[train]") {
  TinyData d;
  auto o = test::tiny_training(d.data, d.dir / "model.h5");
  o.epochs = 12;
  const TrainReport r = train(test::plugins(), o);
  CHECK(r.epochs_done == 12);
  CHECK(r.epochs_this_run == 12);
  CHECK(r.finished);
  CHECK(r.train_samples == 12);
  CHECK(r.val_samples == 4);

  const Checkpoint c = read_checkpoint(o.out);
  const auto& train_loss = c.history.at("train_loss");
  const auto& val_loss = c.history.at("val_loss");
  REQUIRE(train_loss.size() == 12);
  REQUIRE(val_loss.size() == 12);
  INFO("train loss " << train_loss.front() << " -> " << train_loss.back() << ", val " << val_loss.front() << " -> "
                     << val_loss.back());
  CHECK(train_loss.back() < 0.5 * train_loss.front());
  CHECK(val_loss.back() < 0.5 * val_loss.front());
  CHECK(c.history.count("train_loss_l2"));
  CHECK(c.history.count("val_loss_edge"));
  CHECK(c.meta.at("kind") == "drape model");
  CHECK(c.meta.at("status") == "finished");
  // Which simulation it learnt: the description of the scene that made the data.
  CHECK(c.meta.at("ground_truth") == "tiny training scene");
  CHECK(std::stol(c.meta.at("best_epoch")) == r.best_epoch);
  // The best epoch is the one with the lowest validation loss.
  const auto best = std::min_element(val_loss.begin(), val_loss.end());
  CHECK(r.best_epoch == best - val_loss.begin() + 1);
  CHECK(r.best_loss == Approx(*best).epsilon(1e-12));

  // The untrained graph (same seed) on the validation split: training must have beaten it.
  const DatasetReader reader(d.data);
  SampleBatch batch;
  batch.body = reader.body_vertices(reader.indices(Split::Val));
  batch.target = reader.garment_vertices(reader.indices(Split::Val));
  GraphOptions options;
  options.dims = graph_dims(*test::tiny_assets(), reader.layout().body_params);
  options.assets = test::tiny_assets().get();
  options.seed = o.seed;
  Graph untrained(parse_graph_file(o.graph), test::plugins(), options);
  untrained.forward(graph_inputs(untrained, batch, true));
  INFO("untrained validation loss " << untrained.loss());
  CHECK(r.best_loss < 0.5 * untrained.loss());

  // predict/eval read it back: same graph, assets from the spec in /meta, the best weights.
  Model m = Model::load(test::plugins(), o.out, test::assets_cache());
  CHECK(m.output() == "garment");
  CHECK_FALSE(m.assets_changed());
  batch.target = Tensor();
  const Tensor predicted = m.predict(batch);
  const Tensor truth = reader.garment_vertices(reader.indices(Split::Val));
  const double error = (predicted.vec() - truth.vec()).squaredNorm() / double(predicted.rows()) / predicted.batch();
  // The l2 term of the best epoch's validation loss is this mean squared distance.
  CHECK(error == Approx(c.history.at("val_loss_l2")[static_cast<std::size_t>(r.best_epoch - 1)]).epsilon(1e-3));
}

TEST_CASE("a training fraction trains on the first part of the training split only", "[train]") {
  TinyData d;
  auto o = test::tiny_training(d.data, d.dir / "quarter.h5");
  o.epochs = 2;
  o.train_fraction = 0.25;
  const TrainReport r = train(test::plugins(), o);
  CHECK(r.train_samples == 3);  // ceil(0.25 * 12)
  CHECK(r.val_samples == 4);    // the validation split stays whole
  // Resuming with another fraction is another run: refused.
  o.resume = true;
  o.train_fraction = 0.5;
  CHECK_THROWS_WITH(train(test::plugins(), o), Catch::Contains("had train_fraction 0.25, this one has train_fraction 0.5"));
  o.train_fraction = 0.0;
  CHECK_THROWS_WITH(train(test::plugins(), o), Catch::Contains("--fraction must be in (0, 1]"));
}

TEST_CASE("a loss that is NaN at the first batch is named and nothing is written", "[train]") {
  // A user's loss plugin returning NaN was told "try a smaller --lr; m.h5
  // keeps the last finished epoch": no step had been taken, no file written,
  // and the loss was not named (an outside check).
  TinyData d;
  std::string graph = test::read_file(test::baseline_graph());
  const std::size_t at = graph.find("losses:\n");
  REQUIRE(at != std::string::npos);
  graph.insert(at + 8, "  nan_loss: 1.0\n");
  std::ofstream(d.dir / "nan.yaml") << graph;
  auto o = test::tiny_training(d.data, d.dir / "nan.h5");
  o.graph = d.dir / "nan.yaml";
  static Registry* registry = [] {  // kept loaded for the run, as test::plugins()
    auto* r = new Registry;
    r->load_path({test::plugin_dir().string()});
    r->load_file(test::binary_dir() / "test-fixtures/nan_loss/libdrape_plugin_nan_loss.so");
    return r;
  }();
  CHECK_THROWS_WITH(train(*registry, o), Catch::Contains("the training loss is nan in epoch 1 (nan_loss nan) at the first batch, "
                                                         "before any step") &&
                                             Catch::Contains("no epoch finished, so nothing was written") &&
                                             !Catch::Contains("--lr"));
  CHECK_FALSE(fs::exists(d.dir / "nan.h5"));
}

TEST_CASE("a seed reproduces the weights bit for bit and another seed does not", "[train]") {
  TinyData d;
  auto o = test::tiny_training(d.data, d.dir / "a.h5");
  o.epochs = 3;
  train(test::plugins(), o);
  o.out = d.dir / "b.h5";
  train(test::plugins(), o);
  o.out = d.dir / "c.h5";
  o.seed = 6;
  train(test::plugins(), o);
  CHECK(test::weights_of(d.dir / "a.h5") == test::weights_of(d.dir / "b.h5"));
  CHECK(test::weights_of(d.dir / "a.h5.state") == test::weights_of(d.dir / "b.h5.state"));
  CHECK(history_of(d.dir / "a.h5") == history_of(d.dir / "b.h5"));
  CHECK(test::weights_of(d.dir / "a.h5") != test::weights_of(d.dir / "c.h5"));
}

TEST_CASE("an interrupted training resumed gives the uninterrupted result", "[train]") {
  TinyData d;
  auto o = test::tiny_training(d.data, d.dir / "whole.h5");
  o.epochs = 5;
  const TrainReport whole = train(test::plugins(), o);
  REQUIRE(whole.finished);

  o.out = d.dir / "parts.h5";
  o.max_epochs_this_run = 2;
  const TrainReport first = train(test::plugins(), o);
  CHECK(first.epochs_done == 2);
  CHECK_FALSE(first.finished);
  CHECK(read_checkpoint(o.out).meta.at("status") == "training");
  o.resume = true;
  const TrainReport second = train(test::plugins(), o);
  CHECK(second.resumed);
  CHECK(second.epochs_done == 4);
  o.max_epochs_this_run = 0;
  const TrainReport third = train(test::plugins(), o);
  CHECK(third.epochs_done == 5);
  CHECK(third.epochs_this_run == 1);
  CHECK(third.finished);
  CHECK(third.best_epoch == whole.best_epoch);
  CHECK(third.best_loss == whole.best_loss);

  CHECK(test::weights_of(d.dir / "whole.h5") == test::weights_of(d.dir / "parts.h5"));
  CHECK(test::weights_of(d.dir / "whole.h5.state") == test::weights_of(d.dir / "parts.h5.state"));
  CHECK(history_of(d.dir / "whole.h5") == history_of(d.dir / "parts.h5"));
  const auto adam_whole = read_checkpoint(d.dir / "whole.h5.state").optimizer;
  const auto adam_parts = read_checkpoint(d.dir / "parts.h5.state").optimizer;
  REQUIRE(adam_whole);
  REQUIRE(adam_parts);
  CHECK(adam_whole->scalars == adam_parts->scalars);

  // Resuming a finished run does nothing.
  const TrainReport again = train(test::plugins(), o);
  CHECK(again.epochs_this_run == 0);
  CHECK(again.finished);

  // Resuming with more epochs continues it, as if it had been asked for them from the start.
  o.epochs = 7;
  CHECK(train(test::plugins(), o).epochs_this_run == 2);
  auto longer = test::tiny_training(d.data, d.dir / "longer.h5");
  longer.epochs = 7;
  train(test::plugins(), longer);
  CHECK(test::weights_of(d.dir / "longer.h5") == test::weights_of(d.dir / "parts.h5"));
  CHECK(history_of(d.dir / "longer.h5") == history_of(d.dir / "parts.h5"));
}

TEST_CASE("training stops early after `patience` epochs without a better validation loss", "[train]") {
  TinyData d;
  auto o = test::tiny_training(d.data, d.dir / "model.h5");
  o.epochs = 40;
  o.patience = 2;
  o.lr = 0.05;  // far too large: the validation loss soon stops improving
  const TrainReport r = train(test::plugins(), o);
  REQUIRE(r.early_stopped);
  CHECK(r.epochs_done == r.best_epoch + 2);
  CHECK(r.epochs_done < 40);
  const Checkpoint c = read_checkpoint(o.out);
  CHECK(c.meta.at("status") == "early stopped");
  CHECK(c.history.at("val_loss").size() == static_cast<std::size_t>(r.epochs_done));
  // The model keeps the best epoch's weights; the state has them and the last ones.
  const auto model = test::weights_of(o.out);
  const auto state = test::weights_of(training_state_path(o.out));
  bool last_differs = false;
  for (const auto& [name, w] : model) {
    CHECK(state.at("best/" + name) == w);
    last_differs = last_differs || state.at("current/" + name) != w;
  }
  CHECK(last_differs);
}

TEST_CASE("train with a monitor: one loss by name chooses the best epoch, and a name not among the graph's losses is refused",
          "[train]") {
  TinyData d;
  // The baseline graph with the L2 loss measured but hardly trained on
  // (weight 1e-9): the total is the edge loss, which does not see where the
  // garment is, so the L2 loss goes its own way.
  std::string text = test::read_file(test::baseline_graph());
  const std::size_t at = text.find("l2: 1.0");
  REQUIRE(at != std::string::npos);
  text.replace(at, 7, "l2: 1e-9");
  const fs::path graph = d.dir / "graph.yaml";
  std::ofstream(graph) << text;
  auto o = test::tiny_training(d.data, d.dir / "model.h5");
  o.graph = graph;
  o.epochs = 10;
  o.lr = 0.05;
  o.monitor = "l2";
  const TrainReport r = train(test::plugins(), o);
  const Checkpoint c = read_checkpoint(o.out);
  const auto& l2 = c.history.at("val_loss_l2");
  const auto& total = c.history.at("val_loss");
  REQUIRE(l2.size() == 10);
  // The best epoch is where the L2 loss is least, not where the total is.
  const long by_l2 = 1 + static_cast<long>(std::min_element(l2.begin(), l2.end()) - l2.begin());
  const long by_total = 1 + static_cast<long>(std::min_element(total.begin(), total.end()) - total.begin());
  INFO("best by l2 " << by_l2 << ", by the total " << by_total);
  REQUIRE(by_l2 != by_total);  // else this run could not tell them apart
  CHECK(r.best_epoch == by_l2);
  CHECK(r.best_loss == l2[static_cast<std::size_t>(by_l2 - 1)]);
  CHECK(c.meta.at("monitor") == "val_loss_l2");
  // The model holds that epoch's weights: a second run cut after that epoch
  // has them as its current ones (a seed reproduces a run bit for bit).
  auto o2 = test::tiny_training(d.data, d.dir / "model2.h5");
  o2.graph = graph;
  o2.epochs = 10;
  o2.lr = 0.05;
  o2.max_epochs_this_run = by_l2;
  train(test::plugins(), o2);
  const auto cut = test::weights_of(training_state_path(o2.out));
  for (const auto& [name, w] : test::weights_of(o.out)) CHECK(cut.at("current/" + name) == w);

  // A run resumes only with the same monitor.
  auto o3 = o;
  o3.epochs = 12;
  o3.resume = true;
  o3.monitor = "";
  CHECK_THROWS_WITH(train(test::plugins(), o3), Catch::Contains("monitor_loss"));

  auto bad = test::tiny_training(d.data, d.dir / "bad.h5");
  bad.monitor = "edges";
  CHECK_THROWS_WITH(train(test::plugins(), bad),
                    Catch::Contains("--monitor edges: not a loss of") && Catch::Contains("its losses: l2, edge") &&
                        Catch::Contains("did you mean 'edge'"));
  // A loss of weight 0 is not built, so it cannot be watched.
  std::ofstream(d.dir / "off.yaml") << text.replace(text.find("l2: 1e-9"), 8, "l2: 0");
  bad.graph = d.dir / "off.yaml";
  bad.monitor = "l2";
  CHECK_THROWS_WITH(train(test::plugins(), bad), Catch::Contains("is 0, which turns it off"));
}

TEST_CASE("train refuses to overwrite, resumes only with the same settings, and checks the template", "[train]") {
  TinyData d;
  auto o = test::tiny_training(d.data, d.dir / "model.h5");
  o.epochs = 2;
  o.max_epochs_this_run = 1;
  train(test::plugins(), o);
  o.max_epochs_this_run = 0;
  CHECK_THROWS_WITH(train(test::plugins(), o), Catch::Contains("exists") && Catch::Contains("--resume"));
  o.resume = true;
  o.batch = 3;
  CHECK_THROWS_WITH(train(test::plugins(), o), Catch::Contains("batch 4") && Catch::Contains("batch 3"));
  o.batch = 4;
  o.threads = 1;
  CHECK_THROWS_WITH(train(test::plugins(), o), Catch::Contains("threads 2"));
  o.threads = 2;
  // Other drapes with the same split sizes (another shard of one set): refused by the drapes' fingerprint, not let
  // through by the counts; the same drapes in a copy of the file resume.
  test::write_tiny_dataset(d.dir / "other.h5", 16, 12, 4, 11);
  auto other_data = o;
  other_data.data = d.dir / "other.h5";
  CHECK_THROWS_WITH(train(test::plugins(), other_data),
                    Catch::Contains("learnt from other drapes (data.h5)") && Catch::Contains("--force to start over"));
  fs::copy_file(d.data, d.dir / "copy.h5");
  auto copied = o;
  copied.data = d.dir / "copy.h5";
  copied.max_epochs_this_run = 0;
  CHECK(train(test::plugins(), copied).epochs_done == 2);
  o.resume = false;
  o.force = true;
  CHECK(train(test::plugins(), o).epochs_this_run == 2);  // started over
  fs::remove(training_state_path(o.out));
  o.force = false;
  o.resume = true;
  CHECK_THROWS_WITH(train(test::plugins(), o), Catch::Contains("no model.h5.state to resume it from"));
  // The first epoch's model without its state (a kill between the two
  // writes): --resume starts that run over, to the same model as a run never
  // stopped; a later epoch's model without its state is still refused (above).
  auto first = test::tiny_training(d.data, d.dir / "first.h5");
  first.epochs = 2;
  first.max_epochs_this_run = 1;
  train(test::plugins(), first);
  fs::remove(training_state_path(first.out));
  first.max_epochs_this_run = 0;
  first.resume = true;
  CHECK(train(test::plugins(), first).epochs_done == 2);
  auto whole = test::tiny_training(d.data, d.dir / "whole.h5");
  whole.epochs = 2;
  train(test::plugins(), whole);
  CHECK(fs::exists(training_state_path(first.out)));
  CHECK(read_checkpoint(first.out).meta.at("epoch") == "2");
  CHECK(read_checkpoint(first.out).meta.at("best_loss") == read_checkpoint(whole.out).meta.at("best_loss"));

  // A dataset whose template hash differs from the scene's template.
  test::TempDir other;
  DatasetLayout layout = DatasetReader(d.data).layout();
  layout.template_hash = "0123456789abcdef";
  layout.created.clear();
  {
    DatasetWriter w(other / "data.h5", layout);
    const DatasetReader r(d.data);
    for (std::size_t i = 0; i < layout.samples; ++i) w.write(i, r.sample(i));
    w.finish();
  }
  auto bad = test::tiny_training(other / "data.h5", other / "model.h5");
  CHECK_THROWS_WITH(train(test::plugins(), bad), Catch::Contains("made for template 0123456789abcdef"));

  // Bad settings are configuration errors.
  bad = test::tiny_training(d.data, other / "m.h5");
  bad.lr = -1;
  CHECK_THROWS_AS(train(test::plugins(), bad), ConfigError);
  // Nonsense above too (an outside check's 1e300 trained and wrote a model), and a decay that turns weights' signs.
  bad.lr = 1e300;
  CHECK_THROWS_WITH(train(test::plugins(), bad), Catch::Contains("--lr must be a number in (0, 1]"));
  bad.lr = 1e-3;
  bad.weight_decay = 2e3;
  CHECK_THROWS_WITH(train(test::plugins(), bad), Catch::Contains("1 - lr * weight_decay"));
  bad.weight_decay = 0;
  bad.schedule = "linear";
  CHECK_THROWS_WITH(train(test::plugins(), bad), Catch::Contains("constant or cosine"));
}

TEST_CASE("a training starts from a model file's weights (init), refuses another graph's, and resumes only from the same file", "[train]") {
  TinyData d;
  auto a = test::tiny_training(d.data, d.dir / "a.h5");
  train(test::plugins(), a);
  const auto a_history = history_of(d.dir / "a.h5");
  const double a_best = *std::min_element(a_history.at("val_loss").begin(), a_history.at("val_loss").end());

  // A learning rate too small to move the weights: the first validation loss
  // is the one of the weights it started from.
  auto b = test::tiny_training(d.data, d.dir / "b.h5");
  b.epochs = 1;
  b.lr = 1e-12;
  b.init = d.dir / "a.h5";
  train(test::plugins(), b);
  CHECK(history_of(d.dir / "b.h5").at("val_loss").at(0) == Approx(a_best).epsilon(1e-5));
  // drape model info names the start model and the settings to train it again.
  std::string info;
  REQUIRE(test::run(test::drape_command("model info " + (d.dir / "b.h5").string()), info) == 0);
  CHECK_THAT(info, Catch::Contains("init           " + (d.dir / "a.h5").string() + " (the model it started from"));
  CHECK_THAT(info, Catch::Contains("training       seed " + std::to_string(b.seed) + ", batch " + std::to_string(b.batch)) &&
                       Catch::Contains("lr 1e-12") && Catch::Contains("patience " + std::to_string(b.patience)));
  REQUIRE(test::run(test::drape_command("model info " + (d.dir / "a.h5").string()), info) == 0);
  CHECK(info.find("init ") == std::string::npos);
  auto scratch = b;
  scratch.init.clear();
  scratch.out = d.dir / "scratch.h5";
  train(test::plugins(), scratch);
  CHECK(history_of(d.dir / "scratch.h5").at("val_loss").at(0) > 1.5 * a_best);

  // A resumed run started from another file (or from none) is refused.
  auto resumed = b;
  resumed.epochs = 2;
  resumed.resume = true;
  resumed.init = d.dir / "scratch.h5";
  CHECK_THROWS_WITH(train(test::plugins(), resumed), Catch::Contains("init"));
  resumed.init = b.init;
  CHECK(train(test::plugins(), resumed).epochs_done == 2);

  // Another graph's weights (a wider encoder), and a missing file.
  std::ofstream(d.dir / "wider.yaml")
      << "base: " << test::baseline_graph().string() << "\n"
      << "nodes:\n  encoder: { type: cnn1d, in: shape, params: { channels: [16, 32, 96], kernel: 5, stride: 4 } }\n";
  auto other = test::tiny_training(d.data, d.dir / "other.h5");
  other.graph = d.dir / "wider.yaml";
  other.init = d.dir / "a.h5";
  CHECK_THROWS_WITH(train(test::plugins(), other), Catch::Contains("a.h5") && Catch::Contains("encoder"));
  other.init = d.dir / "missing.h5";
  CHECK_THROWS_WITH(train(test::plugins(), other), Catch::Contains("missing.h5: no such file"));
}

TEST_CASE("training on optimised drapes leaves out the ones that are not results (separated 0)", "[train]") {
  TinyData d;  // 12 training and 4 validation samples
  const DatasetReader truth(d.data);
  std::vector<std::size_t> all(16);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::vector<double> separated(16, 1.0);
  separated[0] = separated[3] = separated[13] = 0.0;  // two training drapes, one validation drape
  test::write_shifted_drapes(d.dir / "optimized.h5", truth, all, std::vector<double>(16, 0.0), -1, separated);
  auto o = test::tiny_training(d.dir / "optimized.h5", d.dir / "model.h5");
  o.epochs = 1;
  std::ostringstream log;
  o.log = &log;
  const TrainReport r = train(test::plugins(), o);
  CHECK(r.train_samples == 10);
  CHECK(r.val_samples == 3);
  CHECK_THAT(log.str(), Catch::Contains("left out 2 training and 1 validation drapes"));
  // The same drapes all marked results are all trained on.
  test::write_shifted_drapes(d.dir / "all.h5", truth, all, std::vector<double>(16, 0.0));
  o.data = d.dir / "all.h5";
  o.out = d.dir / "all-model.h5";
  CHECK(train(test::plugins(), o).train_samples == 12);
}

TEST_CASE("train --weight-decay: AdamW's decay reaches the weights, is recorded, and a resume must share it", "[train]") {
  TinyData d;
  // With lr * weight_decay = 1 each step first scales every weight to 0
  // (AdamW: w <- w - lr * wd * w), so what is left is that step's Adam update
  // alone. By Cauchy-Schwarz on Adam's two moving averages, |m| / sqrt(v) <=
  // (1 - b1) / sqrt(1 - b2) / sqrt(1 - b1^2 / b2) = 7.27 for b1 0.9, b2
  // 0.999, and bias correction keeps it below that: every weight of the model
  // lies within 7.3 lr of zero. Without the decay they do not.
  auto plain = test::tiny_training(d.data, d.dir / "plain.h5");
  plain.epochs = 2;
  train(test::plugins(), plain);
  auto decayed = plain;
  decayed.out = d.dir / "decayed.h5";
  decayed.weight_decay = 1.0 / plain.lr;
  train(test::plugins(), decayed);
  const double bound = 7.3 * plain.lr;
  const float plain_max = largest_weight(plain.out), decayed_max = largest_weight(decayed.out);
  INFO("largest |weight| without decay " << plain_max << ", with " << decayed_max << ", bound " << bound);
  CHECK(decayed_max <= bound);
  CHECK(plain_max > 10 * bound);  // else the bound would not tell the two apart
  CHECK(std::stod(read_checkpoint(decayed.out).meta.at("weight_decay")) == decayed.weight_decay);
  CHECK(read_checkpoint(plain.out).meta.count("weight_decay") == 0);

  // A run resumes only with the same decay.
  auto resumed = decayed;
  resumed.epochs = 3;
  resumed.resume = true;
  resumed.weight_decay = 0.0;
  CHECK_THROWS_WITH(train(test::plugins(), resumed), Catch::Contains("had weight_decay 333.3"));
  resumed.weight_decay = 1.0;
  CHECK_THROWS_WITH(train(test::plugins(), resumed), Catch::Contains("this one has weight_decay 1"));
  auto plain_resumed = plain;
  plain_resumed.epochs = 3;
  plain_resumed.resume = true;
  plain_resumed.weight_decay = 0.5;
  CHECK_THROWS_WITH(train(test::plugins(), plain_resumed), Catch::Contains("had weight_decay (none)"));
  resumed.weight_decay = decayed.weight_decay;
  CHECK(train(test::plugins(), resumed).epochs_done == 3);

  auto bad = test::tiny_training(d.data, d.dir / "bad.h5");
  bad.weight_decay = -0.1;
  CHECK_THROWS_WITH(train(test::plugins(), bad), Catch::Contains("--weight-decay must be a number >= 0"));
}
