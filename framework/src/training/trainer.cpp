// `drape train`: epochs of Adam over shuffled mini-batches, validation, the best
// weights, early stopping, and atomic model and state files after every epoch.
#include <drape/training/data_parallel.hpp>
#include <drape/training/distributed.hpp>
#include <drape/io/dataset.hpp>
#include <drape/training/optimizer.hpp>
#include <drape/progress.hpp>
#include <drape/training/rng.hpp>
#include <drape/training/schedule.hpp>
#include <drape/assets/dataset_assets.hpp>
#include <drape/assets/weight_ties.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/io/write_failure.hpp>
#include <drape/training/model.hpp>
#include <drape/warnings.hpp>
#include <drape/training/trainer.hpp>
#include <drape/io/output_lock.hpp>
#include <drape/fnv1a.hpp>

#include "data_fingerprint.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <thread>

namespace fs = std::filesystem;

namespace drape {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Round-trips a double exactly through text (meta values are strings).
std::string exact(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}
std::string brief(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

double meta_number(const Checkpoint& c, const std::string& key, const fs::path& file) {
  const auto it = c.meta.find(key);
  if (it == c.meta.end()) throw ConfigError(file.string() + ": missing /meta attribute '" + key + "'");
  try {
    return std::stod(it->second);
  } catch (const std::exception&) {
    throw ConfigError(file.string() + ": /meta attribute '" + key + "' is not a number: '" + it->second + "'");
  }
}

// A copy of a graph's weights (the best so far), savable under a prefix.
class WeightCopy {
 public:
  explicit WeightCopy(const NamedWeights& from) {
    for (const auto& [name, w] : from) {
      names_.push_back(name);
      store_.push_back(Weight{w->value, Tensor()});
    }
  }
  void assign(const NamedWeights& from) {
    for (std::size_t i = 0; i < from.size(); ++i) store_[i].value.vec() = from[i].second->value.vec();
  }
  NamedWeights named(const std::string& prefix) {
    NamedWeights out;
    for (std::size_t i = 0; i < store_.size(); ++i) out.emplace_back(prefix + names_[i], &store_[i]);
    return out;
  }

 private:
  std::vector<std::string> names_;
  std::vector<Weight> store_;
};

NamedWeights prefixed(const NamedWeights& weights, const std::string& prefix) {
  NamedWeights out;
  for (const auto& [name, w] : weights) out.emplace_back(prefix + name, w);
  return out;
}


void check_options(const TrainOptions& o) {
  auto bad = [](const std::string& what) { throw ConfigError(what); };
  if (o.epochs < 1) bad("--epochs must be at least 1, got " + std::to_string(o.epochs));
  if (o.batch < 1) bad("--batch must be at least 1, got " + std::to_string(o.batch));
  // (Bounded above too: an outside check's --lr 1e300 and --weight-decay
  // 1e300 trained and wrote a model. Adam moves a weight by up to about lr a
  // step, and AdamW scales it by 1 - lr * weight_decay, which must not turn
  // its sign.)
  if (!(o.lr > 0) || !(o.lr <= 1)) bad("--lr must be a number in (0, 1] (Adam's step), got " + exact(o.lr));
  if (!(o.weight_decay >= 0) || !std::isfinite(o.weight_decay))
    bad("--weight-decay must be a number >= 0, got " + exact(o.weight_decay));
  if (o.lr * o.weight_decay > 1)
    bad("--weight-decay " + exact(o.weight_decay) + " with --lr " + exact(o.lr) + ": AdamW scales each weight by 1 - lr * "
        "weight_decay a step, below 0 here; give lr * weight_decay <= 1");
  if (o.patience < 1) bad("--patience must be at least 1, got " + std::to_string(o.patience));
  if (o.threads < 1) bad("--threads must be at least 1, got " + std::to_string(o.threads));
  if (o.eigen_k < 1) bad("--k must be at least 1, got " + std::to_string(o.eigen_k));
  if (!(o.train_fraction > 0 && o.train_fraction <= 1))
    bad("--fraction must be in (0, 1], got " + exact(o.train_fraction));
  if (o.schedule != "constant" && o.schedule != "cosine")
    bad("--schedule must be constant or cosine, got '" + o.schedule + "'");
}

// Per-epoch series (/history in the files); every series gets one value per epoch.
struct History {
  std::map<std::string, std::vector<double>> series;
  void add(const std::string& name, double value) { series[name].push_back(value); }
};

std::string terms_text(const LossValues& l) {
  if (l.terms.size() < 2) return "";
  std::string s = " [";
  for (const auto& [name, v] : l.terms) s += (s.size() > 2 ? ", " : "") + name + " " + brief(v);
  return s + "]";
}

// What the drapes are a simulation of: the description of the scene that made
// the dataset (with or without friction, which garment), so that a model says
// which ground truth it learnt. A stored scene that does not parse is a
// damaged dataset, reported like everywhere else that reads it.
std::string ground_truth_of(const DatasetLayout& layout, const fs::path& data) {
  if (layout.scene.empty()) return "";
  return parse_scene(layout.scene, data.string() + " (scene attribute)").description;
}


// An output or a state from an earlier run is continued (--resume) or
// replaced (--force), never overwritten by accident.
void check_earlier_run(const TrainOptions& o, const fs::path& state_path) {
  // Named by the file that is there: after a model was deleted its state may be left.
  if (!o.force && !o.resume && (fs::exists(o.out) || fs::exists(state_path)))
    throw ConfigError((fs::exists(o.out) ? o.out : state_path).string() +
                      " exists (from an earlier or interrupted training): pass --resume to continue it, or --force to "
                      "start over");
  // --force replaces an earlier training's model, never another kind of
  // file (an outside check's --force turned a dataset into a model).
  if (o.force) refuse_replacing_other_than_a_model(o.out, "--out");
  if (!o.force && o.resume && fs::exists(o.out) && !fs::exists(state_path)) {
    // The first epoch's model, written just before its first state (save):
    // a kill or a full disk between the two left a model no --resume would
    // continue, so a job array's retry failed for ever (an outside check).
    // Redone from the start it is the same run; any later model without its
    // state is another story, and kept.
    bool first_epoch = false;
    try {
      const Checkpoint earlier = read_checkpoint(o.out);
      const auto meta = [&](const char* key) { return earlier.meta.count(key) ? earlier.meta.at(key) : std::string(); };
      first_epoch = meta("kind") == kModelKind && meta("epoch") == "1";
    } catch (const std::exception&) {
    }
    if (!first_epoch)
      throw ConfigError(o.out.string() + " exists, but there is no " + state_path.filename().string() +
                        " to resume it from: --force to start over");
    warn(o.out.string() + " is the first epoch's model of a run stopped before its state was written: --resume "
                          "starts that run over");
  }
}

// The dataset's template (its assets) and the samples to train and validate on.
struct TrainingData {
  AssetsSpec assets_spec;
  std::shared_ptr<const Assets> assets;
  std::string ground_truth;
  std::string size_chart;  // the dataset's, when its drapes wear each body's own size (size_table.hpp)
  std::vector<std::size_t> train_idx, val_idx;
};

TrainingData load_training_data(const Registry& registry, const DatasetReader& reader, const TrainOptions& o) {
  const DatasetLayout& layout = reader.layout();
  TrainingData data;
  if (o.assets) {
    data.assets = o.assets;
    data.assets_spec = parse_assets_spec(data.assets->spec_text, "TrainOptions::assets");
    check_dataset_template(reader, o.data, *data.assets);
  } else {
    data.assets = assets_for_dataset(registry, reader, o.data, o.eigen_k, o.cache_dir, &data.assets_spec, o.encoder_body);
  }
  data.ground_truth = ground_truth_of(layout, o.data);
  if (const auto chart = layout.attributes.find("size_chart"); chart != layout.attributes.end())
    data.size_chart = chart->second;
  // An optimised dataset's drapes that are not results lie inside the body: left out.
  const std::vector<std::size_t> train_all = reader.training_indices(o.train_fraction), val_all = reader.indices(Split::Val);
  data.train_idx = optimizer_results(reader, train_all);
  data.val_idx = optimizer_results(reader, val_all);
  if (o.log && (data.train_idx.size() < train_all.size() || data.val_idx.size() < val_all.size()))
    *o.log << "left out " << train_all.size() - data.train_idx.size() << " training and "
           << val_all.size() - data.val_idx.size()
           << " validation drapes that drape optimize could not bring onto the true body (separated 0)\n";
  if (data.train_idx.empty()) throw ConfigError(o.data.string() + ": no training samples (split 0) are done");
  return data;
}

void check_trainable(Graph& graph, const fs::path& graph_file) {
  if (graph.weights().empty()) throw ConfigError(graph_file.string() + ": the graph has no learnable weights");
  if (graph.spec().nodes.end() == std::find_if(graph.spec().nodes.begin(), graph.spec().nodes.end(),
                                                [](const NodeSpec& n) { return n.is_loss && n.weight != 0.0; }))
    throw ConfigError(graph_file.string() + ": the graph has no losses to train with");
}

// A model started on other assets than its own: the shapes may all fit
// while the weights tied to the assets mean other things (weight_ties.hpp).
// Said, not refused: fine-tuning can relearn them, and a user may mean it.
void warn_of_other_assets(const Registry& registry, const TrainOptions& o, const TrainingData& data) {
  const Checkpoint init = read_checkpoint(o.init);
  const auto spec = init.meta.find("assets");
  if (spec == init.meta.end()) return;  // a plain checkpoint: nothing to compare with
  const AssetsSpec from = parse_assets_spec(spec->second, o.init.string() + ": /meta assets");
  if (from.yaml() == data.assets_spec.yaml()) return;
  const auto from_assets = build_assets(registry, from, o.cache_dir);
  const std::vector<std::string> differ = weight_ties_differ(*from_assets, *data.assets);
  if (differ.empty()) return;
  std::string text = "--init " + o.init.string() + " was trained on other assets, and what its weights are tied to differs here: ";
  for (std::size_t i = 0; i < differ.size(); ++i) text += (i ? "; " : "") + differ[i];
  warn(text + " (docs/training.md, \"From a model's weights\")");
}

// Every weight by name and shape, all or nothing (load_weights names the
// first that is missing or has another shape: a model of another graph).
void load_init_weights(const TrainOptions& o, DataParallelGraph& dp) {
  if (!fs::exists(o.init)) throw ConfigError("--init " + o.init.string() + ": no such file");
  refuse_training_state(read_checkpoint(o.init), o.init, "--init ");
  if (!o.init_widen && !o.init_partial) {
    load_weights(o.init, dp.graph());
  } else {
    const auto widened = o.init_partial ? load_weights_partial(o.init, dp.graph().weights())
                                        : load_weights_widening(o.init, dp.graph().weights());
    if (o.progress) {
      for (const auto& w : widened) {
        if (w.kept)
          *o.progress << "init: weight " << w.name << " is " << w.from.str() << " in the file, " << w.to.str()
                      << " in the graph: it keeps its initialisation\n";
        else if (w.from.rows == 0)
          *o.progress << "init: weight " << w.name << " " << w.to.str()
                      << " is new (not in the file): it keeps its initialisation\n";
        else
          *o.progress << "init: weight " << w.name << " widened from " << w.from.str() << " to " << w.to.str()
                      << " (the new input rows start at zero)\n";
      }
    }
  }
  dp.sync_weights();
}

LrSchedule lr_schedule(const TrainOptions& o) {
  LrSchedule schedule;
  schedule.base = o.lr;
  if (o.schedule == "cosine") {
    schedule.kind = LrSchedule::Kind::Cosine;
    schedule.total = o.epochs;
  }
  return schedule;
}

// What learns: the optimiser, the stopping rule, the best weights so far and
// the per-epoch history.
struct Learner {
  Adam adam;
  EarlyStopping stopper;
  LrSchedule schedule;
  WeightCopy best;
  History history;
};

// --monitor names one of the graph's losses.
void check_monitor(const GraphSpec& spec, const TrainOptions& o) {
  if (o.monitor.empty()) return;
  std::vector<std::string> losses;
  for (const NodeSpec& node : spec.nodes) {
    if (!node.is_loss) continue;
    if (node.name == o.monitor && node.weight == 0.0)
      throw ConfigError("--monitor " + o.monitor + ": its weight in " + o.graph.string() +
                        " is 0, which turns it off (a tiny weight keeps it measured)");
    losses.push_back(node.name);
  }
  if (std::find(losses.begin(), losses.end(), o.monitor) != losses.end()) return;
  std::string list;
  for (const std::string& name : losses) list += (list.empty() ? "" : ", ") + name;
  throw ConfigError("--monitor " + o.monitor + ": not a loss of " + o.graph.string() + " (its losses: " + list + ")" +
                    did_you_mean(o.monitor, losses));
}

// What a resumed run must share with the interrupted one.
std::map<std::string, std::string> resume_settings(const TrainOptions& o, const TrainingData& data,
                                                   const DatasetReader& reader, int ranks) {
  const DatasetLayout& layout = reader.layout();
  std::map<std::string, std::string> settings = recorded_settings(o);
  settings["training_data"] = training_data_fingerprint(reader, data.train_idx, data.val_idx);
  settings["assets"] = data.assets_spec.yaml();
  settings["dataset_template_hash"] = layout.template_hash;
  settings["train_samples"] = std::to_string(data.train_idx.size());
  settings["val_samples"] = std::to_string(data.val_idx.size());
  if (ranks > 1) settings["ranks"] = std::to_string(ranks);  // like threads, they change the sums' rounding
  return settings;
}

// Every rank of an MPI run trains one run: the same data, settings, graph
// and epochs, and the same earlier state to resume from. Ranks given other
// --batch or --epochs paired a loss gather with a gradient gather (Open
// MPI's MPI_ERR_TRUNCATE, a corrupted heap, or a hang); another --seed,
// --lr or --data trained a model of neither, recorded as rank 0's; and a
// rank that could not see <out>.state (a node's own disk) started afresh
// while rank 0 resumed, then hung (an outside check). Compared before the
// first collective of the training, each named; every rank refuses alike.
void check_ranks_agree(const Ranks& ranks, const std::map<std::string, std::string>& settings, const TrainOptions& o,
                       const GraphSpec& graph, const fs::path& state_path) {
  const auto setting = [&](const char* key) {
    const auto it = settings.find(key);
    return it == settings.end() ? std::string() : it->second;
  };
  std::error_code ec;
  const std::vector<std::pair<std::string, std::string>> items{
      {"--data (the drapes trained and validated on)", setting("training_data") + setting("assets")},
      {"--seed", setting("seed")},
      {"--batch", setting("batch")},
      {"--threads", setting("threads")},
      {"--lr, --schedule or --weight-decay", setting("lr") + " " + setting("schedule") + " " + setting("weight_decay")},
      {"--epochs", std::to_string(o.epochs) + " " + std::to_string(o.max_epochs_this_run)},
      {"--patience or --monitor", setting("patience") + " " + setting("monitor_loss")},
      {"the graph", graph.text},
      {"--init", setting("init") + setting("init_widen") + setting("init_partial")},
      {"--resume or --force", std::string(o.resume ? "resume" : "") + (o.force ? "force" : "")},
      {"the earlier run's state " + state_path.filename().string() +
           " (seen by some ranks only: <out> must be on a file system every rank shares, docs/cluster.md)",
       fs::exists(state_path, ec) ? "there" : "absent"}};
  const std::size_t n = items.size();
  std::vector<double> mine(n), all(n * static_cast<std::size_t>(ranks.size()));
  // (A 64-bit hash in a double's bits: all_gather moves bytes, not values.)
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint64_t h = Fnv1a().text(items[k].second).value();
    std::memcpy(&mine[k], &h, sizeof h);
  }
  ranks.all_gather(reinterpret_cast<const std::uint8_t*>(mine.data()), n * sizeof(double),
                   reinterpret_cast<std::uint8_t*>(all.data()));
  for (int r = 1; r < ranks.size(); ++r)
    for (std::size_t k = 0; k < n; ++k)
      if (std::memcmp(&all[static_cast<std::size_t>(r) * n + k], &all[k], sizeof(double)) != 0)
        throw ConfigError("the ranks of this MPI run were not given the same training: rank " + std::to_string(r) +
                          " differs from rank 0 in " + items[k].first + "; every rank must run the same command");
}

// --force: the earlier run's files go.
void start_over(const TrainOptions& o, const fs::path& state_path, int rank, int ranks) {
  if (ranks > 1) o.ranks->barrier();  // every rank has looked at the files before rank 0 removes them
  if (rank == 0) {
    fs::remove(state_path);
    fs::remove(o.out);
  }
  if (ranks > 1) o.ranks->barrier();
}

// Where the epochs stand: read back when resuming, written after every epoch.
struct Progress {
  long epochs_done = 0;
  std::string status = "training";
  double seconds_before = 0;
};

// A state file resumes only the run it was written by: the same settings,
// ranks and graph.
void check_resumable(const Checkpoint& st, const fs::path& state_path, const std::map<std::string, std::string>& settings,
                     int ranks, const GraphSpec& graph_spec, const fs::path& graph_file) {
  if (st.meta.count("kind") == 0 || st.meta.at("kind") != kTrainingStateKind)
    throw ConfigError(state_path.string() + ": not a drape training state");
  // The ranks first: an MPI run's state resumed by one process with two
  // threads was refused as "threads 1 ... threads 2", and only the next try
  // named the ranks (an outside check). Recorded by multi-rank runs only
  // (absent: one process).
  const auto had_ranks = st.meta.find("ranks");
  const std::string was_ranks = had_ranks == st.meta.end() ? "1" : had_ranks->second;
  if (was_ranks != std::to_string(ranks))
    throw ResumeRefused(state_path.string() + ": cannot resume: the interrupted run had ranks " + was_ranks +
                      ", this one has ranks " + std::to_string(ranks) +
                      " (rerun with the same mpirun -np, or --force to start over)");
  for (const auto& [key, value] : settings) {
    const auto it = st.meta.find(key);
    // A state written before the fingerprint (2026-12-06) resumes on the split sizes as it did.
    if (key == "training_data" && it == st.meta.end()) continue;
    if (key == "training_data" && it->second != value)
      throw ResumeRefused(state_path.string() + ": cannot resume: the interrupted run learnt from other drapes" +
                        (st.meta.count("dataset") ? " (" + st.meta.at("dataset") + ")" : std::string()) +
                        " than --data gives now (fingerprint of its training and validation drapes " + it->second +
                        " then, " + value + " now); give the same dataset, or --force to start over");
    const std::string was = it == st.meta.end() ? "(none)" : it->second;
    // A cosine schedule's rate depends on the epochs planned: one cannot be
    // continued for more (it was refused as an "interrupted run" with other
    // settings, of a finished one; an outside check).
    if (key == "epochs" && was != value)
      throw ResumeRefused(state_path.string() + ": cannot continue: its cosine schedule was planned for " + was +
                        " epochs, and its learning rate at each epoch depends on that total, so it cannot be extended to " +
                        value + " (a constant schedule can be; --force starts over, or --init " +
                        (state_path.parent_path() / state_path.stem()).string() + " starts a new cycle from its weights)");
    if (was != value)
      throw ResumeRefused(state_path.string() + ": cannot resume: the interrupted run had " + key + " " + was +
                        ", this one has " + key + " " + value + " (rerun with the same settings, or --force to start over)");
  }
  // Settings a run records only when given: one the interrupted run had and
  // this one lacks is a change too.
  for (const char* key : {"init", "init_widen", "init_partial", "monitor_loss", "weight_decay"})
    if (st.meta.count(key) && !settings.count(key))
      throw ResumeRefused(state_path.string() + ": cannot resume: the interrupted run had " + key + " " +
                        st.meta.at(key) + ", this one has none (rerun with the same settings, or --force to start over)");
  if (st.graph != graph_spec.text)
    throw ResumeRefused(state_path.string() + ": cannot resume: the interrupted run trained another graph than " +
                      graph_file.string() + " (or --force to start over)");
}

// Continues the interrupted run of the state file: its weights (current and
// best), Adam's moments, the stopping rule, the history and the epoch count.
void resume(const fs::path& state_path, const std::map<std::string, std::string>& settings, int ranks,
            const GraphSpec& graph_spec, const TrainOptions& o, DataParallelGraph& dp, Learner& learner,
            Progress& progress, TrainReport& report) {
  const Checkpoint st = read_checkpoint(state_path);
  check_resumable(st, state_path, settings, ranks, graph_spec, o.graph);
  NamedWeights all = prefixed(dp.graph().weights(), "current/");
  for (const auto& w : learner.best.named("best/")) all.push_back(w);
  load_weights(state_path, all);
  if (!st.optimizer) throw ConfigError(state_path.string() + ": no optimiser state");
  learner.adam.set_state(*st.optimizer);
  std::map<std::string, double> es;
  for (const auto& [key, value] : st.meta)
    if (key.rfind("early_stopping.", 0) == 0) es[key.substr(15)] = meta_number(st, key, state_path);
  learner.stopper.set_state(es);
  learner.history.series = st.history;
  progress.epochs_done = static_cast<long>(meta_number(st, "epoch", state_path));
  report.best_epoch = static_cast<long>(meta_number(st, "best_epoch", state_path));
  report.best_loss = meta_number(st, "best_loss", state_path);
  progress.seconds_before = meta_number(st, "seconds", state_path);
  progress.status = st.meta.count("status") ? st.meta.at("status") : "training";
  if (progress.status == "finished" && progress.epochs_done < o.epochs) progress.status = "training";  // more epochs than before
  dp.sync_weights();
  report.resumed = true;
}

// Everything one training run works with once it is set up: what the epochs,
// the files written after each and the log lines read.
struct Run {
  const TrainOptions& o;
  int rank, ranks;
  Clock::time_point run_start;
  fs::path state_path;
  const DatasetReader& reader;
  const TrainingData& data;
  const GraphSpec& graph_spec;
  const std::string& output;
  const std::map<std::string, std::string>& settings;
  DataParallelGraph& dp;
  Learner& learner;
  Progress& progress;
  TrainReport& report;
};

// The model (the best weights) and the state to resume from, after every epoch.
void save(const Run& run) {
  const TrainOptions& o = run.o;
  if (run.rank != 0) return;  // every rank holds the same weights and state
  std::map<std::string, std::string> meta = run.settings;
  meta["assets_hash"] = run.data.assets->hash;
  meta["output"] = run.output;
  // Its file name only: a folder is where one person kept it, and a shipped
  // model would print an author's home to everyone (`drape model info`).
  meta["dataset"] = dataset_name(o.data);
  if (!run.data.ground_truth.empty()) meta["ground_truth"] = run.data.ground_truth;
  // What predict chooses a body's size by (--garment-size auto).
  if (!run.data.size_chart.empty()) meta["size_chart"] = run.data.size_chart;
  meta["epochs"] = std::to_string(o.epochs);
  meta["epoch"] = std::to_string(run.progress.epochs_done);
  meta["best_epoch"] = std::to_string(run.report.best_epoch);
  meta["best_loss"] = exact(run.report.best_loss);
  meta["monitor"] = std::string(run.data.val_idx.empty() ? "train_loss" : "val_loss") + (o.monitor.empty() ? "" : "_" + o.monitor);
  meta["status"] = run.progress.status;
  meta["seconds"] = exact(run.progress.seconds_before + since(run.run_start));
  meta["drape_version"] = "0.1.0";
  Learner& learner = run.learner;
  Checkpoint model{run.graph_spec.text, meta, std::nullopt, learner.history.series};
  model.meta["kind"] = kModelKind;
  save_checkpoint(o.out, learner.best.named(""), model);
  Checkpoint state{run.graph_spec.text, meta, learner.adam.state(), learner.history.series};
  for (const auto& [key, value] : run.settings) state.meta[key] = value;
  state.meta["kind"] = kTrainingStateKind;
  for (const auto& [key, value] : learner.stopper.state()) state.meta["early_stopping." + key] = exact(value);
  NamedWeights all = prefixed(run.dp.graph().weights(), "current/");
  for (const auto& w : learner.best.named("best/")) all.push_back(w);
  // The model first: a kill between the two writes leaves the state one
  // epoch behind, and the resumed run redoes that epoch identically.
  save_checkpoint(run.state_path, all, state);
}

// The run's first log lines: what trains on what, and whether anything is left to do.
void announce(const Run& run, bool nothing_to_do) {
  const TrainOptions& o = run.o;
  const TrainReport& report = run.report;
  const long epochs_done = run.progress.epochs_done;
  const int ng = run.data.assets->garment->mesh.num_vertices(), nb = run.data.assets->body.num_vertices();
  std::size_t weight_count = 0;
  for (const auto& [name, w] : run.dp.graph().weights()) weight_count += w->value.size();
  *o.log << (report.resumed ? "resuming " : "training ") << o.out.string() << ": " << run.graph_spec.file << " on "
         << o.data.string() << " (" << run.data.train_idx.size() << " train, " << run.data.val_idx.size() << " val samples; "
         << ng << " garment, " << nb << " body vertices), " << weight_count << " learnable weights, batch "
         << o.batch << ", " << o.threads << " thread" << (o.threads > 1 ? "s" : "")
         << (run.ranks > 1 ? (" on each of " + std::to_string(run.ranks) + " ranks") : std::string()) << ", lr "
         << brief(o.lr) << " (" << o.schedule << ")"
         << (o.weight_decay != 0.0 ? ", weight decay " + brief(o.weight_decay) : std::string()) << ", seed " << o.seed;
  if (report.resumed) *o.log << ", " << epochs_done << (epochs_done == 1 ? " epoch done" : " epochs done");
  if (!o.monitor.empty()) *o.log << "; the best epoch by its " << o.monitor << " loss";
  *o.log << "\n";
  if (run.data.val_idx.empty()) *o.log << "no validation samples: the training loss picks the best epoch and stops early\n";
  if (nothing_to_do)
    *o.log << "nothing to do: " << (report.early_stopped ? "training stopped early" : "all epochs are done") << " at epoch "
           << epochs_done << " (best epoch " << report.best_epoch << ")\n";
  o.log->flush();
}

// One epoch's Adam steps over the shuffled training samples, batch by batch.
LossValues train_epoch(const Run& run, DistributedGraph& distributed, ProgressBar* bar, long e, double lr) {
  const TrainOptions& o = run.o;
  const std::vector<std::size_t>& train_idx = run.data.train_idx;
  const std::size_t batch = static_cast<std::size_t>(o.batch);
  const auto order = Rng(Rng::derive(o.seed, "epoch-" + std::to_string(e))).permutation(train_idx.size());
  LossValues train_loss;
  for (std::size_t first = 0; first < order.size(); first += batch) {
    std::vector<std::size_t> indices;
    for (std::size_t k = first; k < std::min(order.size(), first + batch); ++k) indices.push_back(train_idx[order[k]]);
    const LossValues l = distributed.gradients(indices);
    if (!std::isfinite(l.total)) {
      // Which loss, and whether a step was ever taken: a loss plugin that
      // returned NaN at the first batch was told to try a smaller --lr, and
      // that the output kept an epoch that was never written (an outside check).
      std::string which;
      for (const auto& [name, value] : l.terms)
        if (!std::isfinite(value)) which += (which.empty() ? "" : ", ") + name + " " + brief(value);
      const bool first_step = e == 0 && first == 0 && run.progress.epochs_done == 0;
      std::error_code ec;
      throw Error("the training loss is " + brief(l.total) + " in epoch " + std::to_string(e + 1) +
                  (which.empty() ? "" : " (" + which + ")") +
                  (first_step ? " at the first batch, before any step: the losses or the data give it, not the learning rate"
                              : " (try a smaller --lr)") +
                  "; " +
                  (fs::exists(o.out, ec) ? o.out.string() + " keeps the last finished epoch"
                                         : "no epoch finished, so nothing was written to " + o.out.string()));
    }
    {
      const OmpThreadsScope all(o.threads);  // Adam is element-wise: threads do not change its result
      run.learner.adam.step(lr);
    }
    run.dp.sync_weights();
    train_loss.merge(l);
    if (bar) {
      bar->set_status("epoch " + std::to_string(e + 1) + "/" + std::to_string(o.epochs) + " loss " + brief(train_loss.total) +
                      (run.report.best_epoch ? ", best val " + brief(run.report.best_loss) : ""));
      bar->advance();
    }
  }
  return train_loss;
}

LossValues validate(const Run& run, DistributedGraph& distributed) {
  const std::vector<std::size_t>& val_idx = run.data.val_idx;
  const std::size_t batch = static_cast<std::size_t>(run.o.batch);
  LossValues val_loss;
  for (std::size_t first = 0; first < val_idx.size(); first += batch) {
    const std::vector<std::size_t> indices(val_idx.begin() + static_cast<long>(first),
                                           val_idx.begin() + static_cast<long>(std::min(val_idx.size(), first + batch)));
    val_loss.merge(distributed.losses(indices));
  }
  return val_loss;
}

// The losses of one finished epoch.
struct EpochResult {
  double lr;
  LossValues train_loss, val_loss;
  double seconds;
  bool stop;
};

void record_history(const Run& run, const EpochResult& r) {
  History& history = run.learner.history;
  history.add("epoch", double(run.progress.epochs_done));
  history.add("train_loss", r.train_loss.total);
  history.add("val_loss", run.data.val_idx.empty() ? NAN : r.val_loss.total);
  history.add("lr", r.lr);
  history.add("seconds", r.seconds);
  for (const auto& [name, v] : r.train_loss.terms) history.add("train_loss_" + name, v);
  for (const auto& [name, v] : r.val_loss.terms) history.add("val_loss_" + name, v);
}

void log_epoch(const Run& run, const EpochResult& r, bool bar_on_terminal) {
  const TrainOptions& o = run.o;
  if (bar_on_terminal) *o.progress << "\r\033[K" << std::flush;
  *o.log << "epoch " << run.progress.epochs_done << "/" << o.epochs << "  train " << brief(r.train_loss.total)
         << terms_text(r.train_loss);
  if (!run.data.val_idx.empty()) *o.log << "  val " << brief(r.val_loss.total) << terms_text(r.val_loss);
  *o.log << "  lr " << brief(r.lr) << "  " << ProgressBar::format_duration(r.seconds)
         << (run.learner.stopper.improved() ? "  (best)" : "") << (r.stop ? "  -- stopping early" : "") << "\n";
  o.log->flush();
}

// One epoch: train, validate, keep the best weights, decide whether to stop,
// then record, save and log it.
void run_epoch(Run& run, DistributedGraph& distributed, ProgressBar* bar, bool bar_on_terminal) {
  const TrainOptions& o = run.o;
  Progress& progress = run.progress;
  TrainReport& report = run.report;
  const auto epoch_start = Clock::now();
  const long e = progress.epochs_done;
  EpochResult r;
  r.lr = run.learner.schedule.at(e);
  r.train_loss = train_epoch(run, distributed, bar, e, r.lr);
  r.val_loss = validate(run, distributed);
  // Each rank computed the data-only closest points of the samples it met;
  // from now on every rank has them all.
  if (run.ranks > 1) share_surface_cache(*o.ranks);
  const LossValues& judged = run.data.val_idx.empty() ? r.train_loss : r.val_loss;
  const double monitored = o.monitor.empty() ? judged.total : judged.terms.at(o.monitor);
  if (!std::isfinite(monitored))
    throw Error("the validation loss" + (o.monitor.empty() ? std::string() : " " + o.monitor) + " is " +
                brief(monitored) + " after epoch " + std::to_string(e + 1));
  r.stop = run.learner.stopper.update(monitored);
  if (run.learner.stopper.improved()) {
    run.learner.best.assign(run.dp.graph().weights());
    report.best_epoch = e + 1;
    report.best_loss = monitored;
  }
  ++progress.epochs_done;
  ++report.epochs_this_run;
  progress.status = r.stop ? "early stopped" : progress.epochs_done >= o.epochs ? "finished" : "training";
  r.seconds = since(epoch_start);
  record_history(run, r);
  const DeferredStop together;  // the model, its state and the epoch's line: all or none
  save(run);
  if (o.log) log_epoch(run, r, bar_on_terminal);
}

// The epochs left: until all are done, training stops early,
// or this run's share of them (max_epochs_this_run) is used up.
void run_epochs(Run& run) {
  const TrainOptions& o = run.o;
  const std::size_t steps_per_epoch =
      (run.data.train_idx.size() + static_cast<std::size_t>(o.batch) - 1) / static_cast<std::size_t>(o.batch);
  std::unique_ptr<ProgressBar> bar;
  ProgressBar::Options bar_options;
  bar_options.start = static_cast<std::size_t>(run.progress.epochs_done) * steps_per_epoch;
  if (o.progress)
    bar = std::make_unique<ProgressBar>("train", static_cast<std::size_t>(o.epochs) * steps_per_epoch, *o.progress,
                                        bar_options);
  const bool bar_on_terminal = o.progress == &std::cerr && ::isatty(STDERR_FILENO) == 1;

  const DatasetReader& reader = run.reader;
  Graph& graph = run.dp.graph();
  DistributedGraph distributed(run.dp, o.ranks, [&](const std::vector<std::size_t>& indices) {
    return read_samples(reader, indices, graph, true);
  });
  const OmpThreadsScope one_thread(1);  // the parallelism is over samples (DataParallelGraph)
  while (run.progress.epochs_done < o.epochs && run.progress.status == "training") {
    if (o.max_epochs_this_run > 0 && run.report.epochs_this_run >= o.max_epochs_this_run) break;
    run_epoch(run, distributed, bar.get(), bar_on_terminal);
  }
  if (bar) bar->finish();
}

}  // namespace

fs::path training_state_path(const fs::path& out) { return fs::path(out.string() + ".state"); }

TrainReport train(const Registry& registry, const TrainOptions& given) {
  // Ranks of an MPI run: every rank trains, rank 0 alone talks and writes files.
  const int rank = given.ranks ? given.ranks->rank() : 0, ranks = given.ranks ? given.ranks->size() : 1;
  TrainOptions o = given;
  if (rank != 0) o.log = o.progress = nullptr;
  check_options(o);
  const auto run_start = Clock::now();
  TrainReport report;
  const fs::path state_path = training_state_path(o.out);
  check_earlier_run(o, state_path);

  // The dataset and the template it was made for.
  const DatasetReader reader(o.data);
  const TrainingData data = load_training_data(registry, reader, o);
  report.train_samples = static_cast<int>(data.train_idx.size());
  report.val_samples = static_cast<int>(data.val_idx.size());

  // The graph, its replicas and the optimiser.
  const GraphSpec graph_spec = parse_graph_file(o.graph);
  check_graph_inputs(graph_spec);
  check_monitor(graph_spec, o);
  GraphOptions graph_options;
  graph_options.dims = graph_dims(*data.assets, reader.layout().body_params);
  graph_options.assets = data.assets.get();
  graph_options.seed = o.seed;
  DataParallelGraph dp(graph_spec, registry, graph_options, o.threads);
  Graph& graph = dp.graph();
  check_trainable(graph, o.graph);
  // Posed drapes and a graph that reads no pose: the model would learn every
  // pose as if the body stood at rest (an outside check trained one silently,
  // and its `model info` listed the poses predict then refused).
  if (rank == 0 && !reader.layout().pose_angles.empty()) {
    if (!reads_pose(graph.input_names()))
      warn(fs::path(o.data).string() + " holds drapes on posed bodies (" + std::to_string(reader.layout().pose_angles.size()) +
           " joint angles a sample) and the graph " + fs::path(o.graph).string() + " takes no pose (no input pose, unposed_body or "
           "joint_transforms): the model learns each drape as if its body stood at rest and drapes the A-pose only; "
           "graphs of posed drapes are in graphs/poses/ (docs/poses.md)");
  }
  const std::string output = garment_output(graph);
  if ((o.init_widen || o.init_partial) && o.init.empty())
    throw ConfigError(std::string(o.init_partial ? "--init-partial" : "--init-widen") + " needs --init (the model to start from)");
  if (!o.init.empty()) {
    load_init_weights(o, dp);
    if (rank == 0) warn_of_other_assets(registry, o, data);
  }
  Learner learner{Adam(graph.weights(), AdamOptions{.weight_decay = o.weight_decay}), EarlyStopping({o.patience, 0.0}),
                  lr_schedule(o), WeightCopy(graph.weights()), History()};
  const std::map<std::string, std::string> settings = resume_settings(o, data, reader, ranks);
  if (ranks > 1) check_ranks_agree(*o.ranks, settings, o, graph_spec, state_path);

  // Start over, or continue.
  if (o.force) start_over(o, state_path, rank, ranks);
  Progress progress;
  if (o.resume && fs::exists(state_path))
    resume(state_path, settings, ranks, graph_spec, o, dp, learner, progress, report);
  report.epochs_done = progress.epochs_done;
  report.early_stopped = progress.status == "early stopped";

  Run run{o, rank, ranks, run_start, state_path, reader, data, graph_spec, output, settings, dp, learner, progress, report};
  const bool nothing_to_do = report.early_stopped || progress.epochs_done >= o.epochs;
  if (o.log) announce(run, nothing_to_do);
  if (nothing_to_do) {
    report.finished = true;
    report.seconds = since(run_start);
    return report;
  }
  run_epochs(run);
  report.epochs_done = progress.epochs_done;
  report.early_stopped = progress.status == "early stopped";
  report.finished = progress.status != "training";
  report.seconds = since(run_start);
  return report;
}

std::map<std::string, std::string> recorded_settings(const TrainOptions& o) {
  std::map<std::string, std::string> settings{{"seed", std::to_string(o.seed)},
                                              {"batch", std::to_string(o.batch)},
                                              {"threads", std::to_string(o.threads)},
                                              {"lr", exact(o.lr)},
                                              {"schedule", o.schedule},
                                              {"patience", std::to_string(o.patience)}};
  if (!o.monitor.empty()) settings["monitor_loss"] = o.monitor;  // absent: the total, as before the option
  if (o.weight_decay != 0.0) settings["weight_decay"] = exact(o.weight_decay);  // absent: 0, as before the option
  if (o.train_fraction != 1.0) settings["train_fraction"] = exact(o.train_fraction);  // absent: 1, as before it was recorded
  if (o.schedule == "cosine") settings["epochs"] = std::to_string(o.epochs);
  if (!o.init.empty()) settings["init"] = o.init.string();
  if (o.init_widen) settings["init_widen"] = "1";
  if (o.init_partial) settings["init_partial"] = "1";
  return settings;
}

}  // namespace drape
