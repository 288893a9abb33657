// Checkpoints: weights, graph YAML, metadata and optimiser state in one HDF5 file.
#include <drape/io/atomic_file.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/graph.hpp>
#include <drape/io/h5.hpp>

#include <algorithm>
#include <set>

namespace fs = std::filesystem;

namespace drape {

namespace {

constexpr const char* kFormat = "drape checkpoint 1";

h5::Dims matrix_dims(const Tensor& t) {
  return {static_cast<std::size_t>(t.rows()), static_cast<std::size_t>(t.cols())};
}

void write_matrix(h5::File& file, const std::string& dataset, const Tensor& t) {
  if (t.batch() != 1) throw Error(file.path().string() + ": " + dataset + " has batch " + std::to_string(t.batch()) + ", expected 1");
  file.write(dataset, matrix_dims(t), t.data());
}

Tensor read_matrix(const h5::File& file, const std::string& dataset) {
  const h5::Dims d = file.shape(dataset);
  if (d.size() != 2)
    throw ConfigError(file.path().string() + ": " + h5::normalize(dataset) + " has shape " + h5::to_string(d) + ", expected [rows, cols]");
  // Integers would be read as floats without a word (an outside check's
  // weights rewritten as int32 loaded as zeros and predicted, exit 0).
  if (const h5::DType type = file.dtype(dataset); type != h5::DType::F32 && type != h5::DType::F64)
    throw ConfigError(file.path().string() + ": " + h5::normalize(dataset) + " holds " + h5::to_string(type) +
                      "; a weight is a floating-point number (float32, as drape writes it)");
  Tensor t(1, static_cast<int>(d[0]), static_cast<int>(d[1]));
  file.read(dataset, d, t.data());
  return t;
}

void check_format(const h5::File& file) {
  const auto format = file.string_attribute("/", "format");
  if (!format || *format != kFormat)
    throw ConfigError(file.path().string() + ": not a drape checkpoint (format attribute '" + format.value_or("") +
                      "', expected '" + kFormat + "')");
}

}  // namespace

void save_checkpoint(const fs::path& path, const NamedWeights& weights, const Checkpoint& checkpoint) {
  write_atomically(path, [&](const fs::path& tmp) {
    h5::File file = h5::File::create(tmp);
    file.set_attribute("/", "format", kFormat);
    file.set_attribute("/", "graph", checkpoint.graph);
    file.create_group("/weights");
    for (const auto& [name, w] : weights) write_matrix(file, "/weights/" + name, w->value);
    file.create_group("/meta");
    for (const auto& [key, value] : checkpoint.meta) file.set_attribute("/meta", key, value);
    if (checkpoint.optimizer) {
      const OptimizerState& s = *checkpoint.optimizer;
      file.create_group("/optimizer");
      for (const auto& [name, t] : s.tensors) write_matrix(file, "/optimizer/" + name, t);
      file.set_attribute("/optimizer", "type", s.type);
      for (const auto& [key, value] : s.scalars) file.set_attribute("/optimizer", key, value);
    }
    if (!checkpoint.history.empty()) {
      file.create_group("/history");
      for (const auto& [name, values] : checkpoint.history) file.write("/history/" + name, values);
    }
    file.flush(true);
    file.close();
  });
}

void save_checkpoint(const fs::path& path, Graph& graph, const std::map<std::string, std::string>& meta, const Optimizer* optimizer) {
  Checkpoint c;
  c.graph = graph.spec().text;
  c.meta = meta;
  if (optimizer) c.optimizer = optimizer->state();
  save_checkpoint(path, graph.weights(), c);
}

void refuse_training_state(const Checkpoint& checkpoint, const fs::path& file, const std::string& option) {
  const auto kind = checkpoint.meta.find("kind");
  if (kind == checkpoint.meta.end() || kind->second != kTrainingStateKind) return;
  // (<out>.state is written beside <out>.)
  const fs::path model = file.extension() == ".state" ? fs::path(file).replace_extension() : file;
  throw ConfigError(option + file.string() + ": is drape train's training state (what --resume continues from), not a "
                    "model: give the model it was written beside (" + model.string() + ")");
}

Checkpoint read_checkpoint(const fs::path& path) {
  const h5::File file = h5::File::open(path);
  check_format(file);
  Checkpoint c;
  c.graph = file.require_string_attribute("/", "graph");
  if (file.is_group("/meta"))
    for (const auto& key : file.attribute_names("/meta")) c.meta[key] = file.require_string_attribute("/meta", key);
  if (file.is_group("/optimizer")) {
    OptimizerState s;
    s.type = file.require_string_attribute("/optimizer", "type");
    for (const auto& key : file.attribute_names("/optimizer"))
      if (key != "type") s.scalars[key] = file.number_attribute("/optimizer", key).value();
    for (const auto& name : file.datasets_below("/optimizer")) s.tensors[name] = read_matrix(file, "/optimizer/" + name);
    c.optimizer = std::move(s);
  }
  if (file.is_group("/history"))
    for (const auto& name : file.datasets_below("/history")) c.history[name] = file.read<double>("/history/" + name);
  return c;
}

namespace {

// How a weight whose shape differs from the file's is loaded.
enum class OtherShape {
  refused,       // load_weights: shapes must match
  rows_added,    // load_weights_widening: more rows take the file's first, zeros after; a weight the file lacks keeps its initialisation
  kept_initial,  // load_weights_partial: as rows_added, and any other shape keeps its initialisation
};

// load_weights, load_weights_widening and load_weights_partial: every weight
// by name, all or nothing; what was not loaded as it is listed in `changed`.
void load_named_weights(const fs::path& path, const NamedWeights& weights, bool allow_extra, OtherShape rule,
                        std::vector<WidenedWeight>& changed) {
  const bool widening = rule != OtherShape::refused;
  const h5::File file = h5::File::open(path);
  check_format(file);
  std::set<std::string> in_file;
  if (widening && file.is_group("/weights"))
    for (const auto& name : file.datasets_below("/weights")) in_file.insert(name);
  // New weights are for a graph that adds to the file's, not one that shares
  // nothing with it (another graph's file would otherwise start a training
  // from scratch without a word).
  if (widening && std::none_of(weights.begin(), weights.end(), [&](const auto& w) { return in_file.count(w.first) > 0; }))
    throw ConfigError(path.string() + ": none of the graph's weights is in the file (was it saved from another graph?)");
  std::vector<Tensor> loaded;
  std::set<std::string> wanted;
  for (const auto& [name, w] : weights) {
    if (widening && !in_file.count(name)) {
      // A node the file's graph did not have (a branch added to it): it keeps
      // its own initialisation (a linear node with init: zero starts as nothing).
      changed.push_back({name, Shape{0, 0}, w->value.shape()});
      loaded.push_back(w->value);
      continue;
    }
    Tensor t = read_matrix(file, "/weights/" + name);
    // A NaN weight (a file edited by hand, a training that diverged) would
    // come out as a non-finite garment, far from where it came in.
    if (!t.vec().allFinite())
      throw ConfigError(path.string() + ": weight " + name + " holds a value that is not a finite number (NaN or inf): "
                        "the file is damaged, or came from a training that diverged");
    const Shape from = t.shape(), to = w->value.shape();
    const bool grows = widening && from.cols == to.cols && from.rows < to.rows;
    if (from != to && !grows && rule == OtherShape::kept_initial) {
      changed.push_back({name, from, to, true});
      loaded.push_back(w->value);
      wanted.insert(name);
      continue;
    }
    if (from != to && !grows)
      throw ConfigError(path.string() + ": weight " + name + " is " + from.str() + " in the file, the graph has " + to.str() +
                        (widening && from.cols != to.cols ? " (only rows, the inputs, may be added)" : ""));
    if (grows) {
      Tensor grown(1, to.rows, to.cols, 0.0f);
      grown.mat(0).topRows(from.rows) = t.mat(0);
      changed.push_back({name, from, to});
      t = std::move(grown);
    }
    loaded.push_back(std::move(t));
    wanted.insert(name);
  }
  if (!allow_extra && file.is_group("/weights"))
    for (const auto& name : file.datasets_below("/weights"))
      if (!wanted.count(name))
        throw ConfigError(path.string() + ": weight " + name + " in the file is not in the graph (was it saved from another graph?)");
  // Copied into the existing storage: nodes may hold views of their weights.
  for (std::size_t i = 0; i < weights.size(); ++i) weights[i].second->value.vec() = loaded[i].vec();
}

}  // namespace

void load_weights(const fs::path& path, const NamedWeights& weights, bool allow_extra) {
  std::vector<WidenedWeight> none;  // nothing differs: a difference is refused
  load_named_weights(path, weights, allow_extra, OtherShape::refused, none);
}

void load_weights(const fs::path& path, Graph& graph, bool allow_extra) { load_weights(path, graph.weights(), allow_extra); }

std::vector<WidenedWeight> load_weights_widening(const fs::path& path, const NamedWeights& weights) {
  std::vector<WidenedWeight> widened;
  load_named_weights(path, weights, false, OtherShape::rows_added, widened);
  return widened;
}

std::vector<WidenedWeight> load_weights_partial(const fs::path& path, const NamedWeights& weights) {
  std::vector<WidenedWeight> changed;
  load_named_weights(path, weights, false, OtherShape::kept_initial, changed);
  return changed;
}

}  // namespace drape
