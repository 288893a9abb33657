#pragma once
// Model checkpoints (layout in docs/formats.md):
//   /weights/<node>/<weight>      f32 [rows, cols]   every learnable weight
//   root attribute `graph`        the resolved graph YAML (GraphSpec::text)
//   root attribute `format`       "drape checkpoint 1"
//   /meta                         string attributes (epoch, seed, best_val_loss, ...)
//   /optimizer/<slot>/<weight>    f32 [rows, cols]   optional optimiser state,
//                                 attributes `type` and the scalars (step, ...)
//   /history/<name>               f64 [n]            optional series (per-epoch losses, ...)
// Written atomically (temporary file + rename): a save that fails or is killed
// leaves the previous checkpoint untouched.
#include <drape/training/optimizer.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace drape {

class Graph;

struct Checkpoint {
  std::string graph;                        // YAML text
  std::map<std::string, std::string> meta;  // string key/values
  std::optional<OptimizerState> optimizer;
  std::map<std::string, std::vector<double>> history;  // /history/<name>, e.g. per-epoch losses
};

void save_checkpoint(const std::filesystem::path& path, const NamedWeights& weights, const Checkpoint& checkpoint);
// The graph's weights and YAML text, the given metadata and optionally the optimiser's state.
void save_checkpoint(const std::filesystem::path& path, Graph& graph, const std::map<std::string, std::string>& meta,
                     const Optimizer* optimizer = nullptr);

// Everything but the weights.
Checkpoint read_checkpoint(const std::filesystem::path& path);

// /meta kind of drape train's two outputs: the model (--out) and the state it
// resumes from (<out>.state).
inline constexpr const char* kModelKind = "drape model";
inline constexpr const char* kTrainingStateKind = "drape training state";

// ConfigError when `checkpoint` (read from `file`, given as `option`) is a
// training state: one given as --model or --init failed with "missing
// dataset /weights/encoder/conv0_b".
void refuse_training_state(const Checkpoint& checkpoint, const std::filesystem::path& file, const std::string& option);

// Fills every weight from the file, all or nothing. ConfigError naming the
// weight that is missing ("model.h5: missing dataset /weights/encoder/w"), has
// another shape, or (unless allow_extra) is in the file but not in `weights`.
void load_weights(const std::filesystem::path& path, const NamedWeights& weights, bool allow_extra = false);
void load_weights(const std::filesystem::path& path, Graph& graph, bool allow_extra = false);

// A weight of the file given more rows (inputs) by the graph, or (from
// [0, 0]) a weight the file lacks, or (kept) one of another shape left at
// the graph's initialisation (load_weights_partial).
struct WidenedWeight {
  std::string name;
  Shape from, to;
  bool kept = false;
};
// As load_weights, but a graph weight [r + k, c] takes the file's [r, c] as its
// first r rows and zeros after them: a graph that appends k input features
// (a concat after the old ones, such as the garment's grade on the encoded
// features) starts as exactly the model in the file, the new inputs with no
// effect until training gives them one. Columns (outputs) must match. A graph
// weight the file lacks (a node added to the graph, such as a branch whose
// last layer starts at zero: linear's init: zero) keeps the value the graph
// gave it. Returns the weights so widened or new; all or nothing, and a
// weight in the file that the graph lacks is still an error.
std::vector<WidenedWeight> load_weights_widening(const std::filesystem::path& path, const NamedWeights& weights);
// As load_weights_widening, and a weight whose shape in the file is neither
// the graph's nor fewer rows of it keeps the graph's initialisation (kept):
// a model of one template moved to another of the same garment, whose
// hierarchy levels have a few edges more or fewer (the human rig's template
// against the mannequin's: 4 of 35 weights, 4,088 of 842,301 values, the
// multi-scale decoder's per-edge aggregation at levels 1 and 2). A weight
// of the same shape is taken as it is, though on another template's
// hierarchy it weighs other edges: a start for training, not a model.
std::vector<WidenedWeight> load_weights_partial(const std::filesystem::path& path, const NamedWeights& weights);

}  // namespace drape
