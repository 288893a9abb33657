#pragma once
// Training a graph on a drape dataset (`drape train`): Adam on shuffled
// mini-batches, data-parallel over threads (data_parallel.hpp), the
// validation loss after every epoch, the best weights kept, early stopping.
//
// Files (layouts in docs/formats.md), both written atomically after every epoch:
//   <out>         the model: the best weights so far, the graph, the assets
//                 spec and the per-epoch history (what predict/eval read)
//   <out>.state   everything a resumed run needs: the current and the best
//                 weights, Adam's moments and step, the early-stopping
//                 counters, the history and the settings that must not change
// A killed run continues with the same command plus `resume`: the epoch it was
// in is run again from the state after the last finished epoch, and the result
// is identical to an uninterrupted run. The shuffle of epoch e is drawn from
// Rng::derive(seed, "epoch-e"), so the random state is (seed, epoch).
#include <drape/assets/assets.hpp>
#include <drape/training/ranks.hpp>
#include <drape/registry.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <iosfwd>
#include <memory>
#include <string>

namespace drape {

struct TrainOptions {
  std::filesystem::path graph;  // graph YAML
  std::filesystem::path data;   // dataset (drape generate)
  std::filesystem::path out;    // model file
  long epochs = 100;
  int batch = 8;
  double lr = 1e-3;
  // AdamW's decoupled weight decay: every step multiplies each weight by
  // (1 - lr * weight_decay) before Adam's update. 0: plain Adam, as before
  // the option. A regulariser for a model that fits its training drapes
  // closer than unseen bodies (docs/poses.md, "Weight decay").
  double weight_decay = 0.0;
  std::string schedule = "constant";  // or "cosine" (to 0 over `epochs`)
  std::uint64_t seed = 0;
  int threads = 1;
  int patience = 20;          // epochs without a better validation loss before stopping
  // What "better" means for the best epoch and early stopping: empty, the
  // weighted total of the losses; else one loss of the graph by its name,
  // unweighted (say v2v: a penetration term with a small margin can grow
  // while the drape gets closer, and would then choose an early epoch).
  std::string monitor;
  // Train on this fraction of the training split only (its first samples in
  // file order: the split is a seeded random permutation, so a random subset);
  // the validation split stays whole. The seed's "4k" model is fraction 0.25.
  double train_fraction = 1.0;
  // Start from the weights of this model file (drape train's --out of the same
  // graph: every weight by name and shape) instead of seeded random ones: a
  // shipped model fine-tuned on new drapes, or trained on for a second
  // schedule. Empty: random weights. Recorded in the state, so a resumed run
  // must give the same file.
  std::filesystem::path init;
  // With init: a weight the graph gives more input rows than the file's (a
  // graph that appends features, such as graphs/sizes/drape_grade.yaml's
  // grade) keeps the file's rows and starts the new ones at zero
  // (load_weights_widening), so training starts from the model in the file.
  bool init_widen = false;
  // With init: as init_widen, and a weight of another shape in the file
  // keeps its initialisation (load_weights_partial): a model moved to
  // another template of the garment (the human rig's; docs/bodies.md).
  bool init_partial = false;
  bool resume = false;        // continue from <out>.state when it exists
  bool force = false;         // start over even when <out> or <out>.state exists
  long max_epochs_this_run = 0;  // > 0: stop after that many epochs as if killed (tests)
  int eigen_k = 1000;         // eigenvectors in the assets (eigen_k; L_s of drape eval uses them)
  // A body model whose vertices the encoder reads (AssetsSpec::encoder_body:
  // the graph's resample_body node carries the dataset's bodies onto them);
  // empty: none.
  std::string encoder_body;
  std::filesystem::path cache_dir = default_cache_dir();  // of the assets (build_assets)
  // Prebuilt assets of the dataset's template (checked against it), e.g. for
  // several trainings in one process; null: built from the dataset's scene.
  std::shared_ptr<const Assets> assets;
  std::ostream* log = nullptr;       // one line per epoch; null: quiet
  // The processes training together (mpirun, drape/training/distributed.hpp): each
  // runs its part of every batch and validation batch; rank 0 alone logs,
  // shows the progress and writes <out> and <out>.state. null: this one alone.
  const Ranks* ranks = nullptr;
  std::ostream* progress = nullptr;  // the progress bar; null: none
};

struct TrainReport {
  long epochs_done = 0;      // in total, over all runs
  long epochs_this_run = 0;
  long best_epoch = 0;       // 1-based; 0 when no epoch finished
  double best_loss = 0;      // the monitored loss (validation, or training without a validation split; monitor)
  bool resumed = false;
  bool early_stopped = false;
  bool finished = false;     // the epochs are done or training stopped early
  double seconds = 0;        // this run
  int train_samples = 0, val_samples = 0;
};

// Throws ConfigError for bad settings, a dataset made for another template,
// an existing output without resume/force, or a state that belongs to other
// settings; Error when the loss stops being finite.
TrainReport train(const Registry& registry, const TrainOptions& options);

// The settings of `options` a model and its training state record in their
// metadata (lr, batch, seed, schedule, patience, monitor_loss, ...; those at
// their old defaults left out, as files made before them lack them), which a
// resume must match; the data's own fingerprints are added by train().
std::map<std::string, std::string> recorded_settings(const TrainOptions& options);

// "<out>.state"
std::filesystem::path training_state_path(const std::filesystem::path& out);

}  // namespace drape
