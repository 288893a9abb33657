#include <drape/experiment/experiment.hpp>

#include "../yaml_util.hpp"

#include <drape/graph.hpp>

#include <algorithm>
#include <cmath>

namespace drape {
namespace fs = std::filesystem;

namespace {

// Why a column does not stand beside the seed's number (ExperimentColumn::not_as_the_seed).
std::string unnormalised_sum(const char* equation) {
  return std::string("the seed's eq. ") + equation +
         " is a sum whose normalisation it does not state, and its tables' magnitudes fit neither that sum over this "
         "shirt's elements nor the per-element mean reported here";
}
const char* const kEnergyUnits =
    "the seed does not state the units of its energies (its simulated L_p is 1e-4); only ratios between rows compare";

}  // namespace

const std::vector<ExperimentColumn>& experiment_columns() {
  // ExperimentColumn keeps a pointer to its reason: these live as long as the table.
  static const std::string laplacian_sum = unnormalised_sum("6.12"), spectral_sum = unnormalised_sum("6.13"),
                           deformation_sum = unnormalised_sum("6.10");
  static const std::vector<ExperimentColumn> columns = {
      {"ME", "ME", "cm", "mean distance to the simulated garment, test split"},
      {"L_l", "L_l", "cm", "Laplacian difference, four resolutions",
       laplacian_sum.c_str()},
      {"L_e", "L_e", "%", "relative edge length error"},
      {"L_s", "L_s", "m", "spectral coefficient error",
       spectral_sum.c_str()},
      {"L_d", "L_d", "", "deformation gradient error",
       deformation_sum.c_str()},
      {"p", "p", "%", "garment vertices inside the body"},
      {"L_st", "L_st", "J", "stretching energy", kEnergyUnits},
      {"L_b", "L_b", "J", "bending energy", kEnergyUnits},
      {"L_g", "L_g", "J", "gravitational energy", kEnergyUnits},
      {"L_c", "L_c", "J", "collision (penetration) energy", kEnergyUnits},
      {"L_p", "L_p", "J", "potential: the sum of the scene's energies", kEnergyUnits},
      {"train_h", "training", "h", "wall time of the training on the threads used"},
      {"e2e_h", "end-to-end", "core-h", "simulation + training + optimisation + retraining, in core-hours"},
      {"infer", "inference", "", "time per body on one core: ms for a network, s for optimisation and simulation"},
  };
  return columns;
}

const ExperimentDataset& ExperimentSpec::dataset(const std::string& key) const {
  std::vector<std::string> keys;
  for (const auto& d : datasets) {
    if (d.key == key) return d;
    keys.push_back(d.key);
  }
  throw ConfigError(file.string() + ": no dataset '" + key + "'" + did_you_mean(key, keys) +
                    (keys.empty() ? std::string(" (it lists none)") : " (its datasets: " + yaml::joined(keys) + ")"));
}

const ExperimentRow& ExperimentSpec::row(const std::string& row_name) const {
  for (const auto& r : rows)
    if (r.name == row_name) return r;
  throw ConfigError(file.string() + ": no row '" + row_name + "'");
}

namespace {

struct Reader {
  std::string file;
  fs::path dir;

  SourceLocation at(const YAML::Node& n) const { return yaml::at(file, n); }
  std::string text(const YAML::Node& n, const std::string& what) const { return yaml::scalar(file, n, what); }

  template <class T>
  T number(const YAML::Node& n, const std::string& what) const {
    const std::string s = text(n, what);
    try {
      return n.as<T>();
    } catch (const YAML::Exception&) {
      throw ConfigError(at(n), what + " must be a number, got '" + s + "'");
    }
  }

  // A path relative to the experiment file that must exist.
  fs::path path(const YAML::Node& n, const std::string& what) const {
    const fs::path p = dir / text(n, what);
    if (!fs::exists(p)) {
      // The files beside the one named, for a misspelt name (g/enk.yaml for g/enc.yaml).
      std::vector<std::string> beside;
      std::error_code ec;
      for (const auto& entry : fs::directory_iterator(p.parent_path().empty() ? "." : p.parent_path(), ec))
        if (entry.is_regular_file(ec)) beside.push_back(entry.path().filename().string());
      throw ConfigError(at(n), what + ": no file " + p.string() + did_you_mean(p.filename().string(), beside));
    }
    return p.lexically_normal();
  }

  ExperimentTraining training(const YAML::Node& n, ExperimentTraining t, const std::string& owner) const {
    yaml::check_keys(file, n, {"epochs", "batch", "lr", "schedule", "patience", "seed", "monitor"}, owner);
    if (n["epochs"]) t.epochs = number<long>(n["epochs"], owner + ".epochs");
    if (n["batch"]) t.batch = number<int>(n["batch"], owner + ".batch");
    if (n["lr"]) t.lr = number<double>(n["lr"], owner + ".lr");
    if (n["schedule"]) t.schedule = text(n["schedule"], owner + ".schedule");
    if (n["patience"]) t.patience = number<int>(n["patience"], owner + ".patience");
    if (n["seed"]) t.seed = number<std::uint64_t>(n["seed"], owner + ".seed");
    if (n["monitor"]) t.monitor = text(n["monitor"], owner + ".monitor"), t.monitor_where = at(n["monitor"]);
    if (t.epochs < 1 || t.batch < 1 || !(t.lr > 0) || t.patience < 1)
      throw ConfigError(at(n), owner + ": epochs, batch, lr and patience must be positive");
    if (t.schedule != "constant" && t.schedule != "cosine")
      throw ConfigError(at(n["schedule"]), owner + ".schedule must be constant or cosine, got '" + t.schedule + "'");
    return t;
  }
};

std::vector<std::string> column_names() {
  std::vector<std::string> names;
  for (const auto& c : experiment_columns()) names.push_back(c.name);
  return names;
}

void check_column(const Reader& r, const YAML::Node& n, const std::string& name, const std::string& owner) {
  const auto names = column_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw ConfigError(r.at(n), owner + ": unknown column '" + name + "'" + did_you_mean(name, names) +
                                   " (known: " + yaml::joined(names) + ")");
}

// One row of the experiment file: its name and kind, then what its kind
// takes (train, optimize, evaluate or simulation), then what all rows may give.
class RowParser {
 public:
  RowParser(const Reader& reader, const YAML::Node& node, const ExperimentSpec& spec_so_far)
      : r(reader), n(node), spec(spec_so_far) {}

  ExperimentRow parse() {
    row.where = r.at(n);
    yaml::check_keys(r.file, n,
                     {"name", "train", "optimize", "simulation", "evaluate", "set", "data", "test", "where", "fraction",
                      "on_optimized", "physics", "scene", "iterations", "training", "seed"},
                     "row");
    name_and_kind();
    if (n["train"]) {
      train_row();
    } else if (n["optimize"]) {
      optimize_row();
    } else if (n["evaluate"]) {
      evaluate_row();
    } else {
      simulation_row();
    }
    common_settings();
    check_monitor();
    return row;
  }

 private:
  void name_and_kind() {
    if (!n["name"]) throw ConfigError(r.at(n), "row: 'name' is required");
    row.name = r.text(n["name"], "row name");
    owner = "row '" + row.name + "'";
    for (const auto& other : spec.rows)
      if (other.name == row.name) throw ConfigError(r.at(n["name"]), owner + " is defined twice");
    const int kinds = (n["train"] ? 1 : 0) + (n["optimize"] ? 1 : 0) + (n["simulation"] ? 1 : 0) + (n["evaluate"] ? 1 : 0);
    if (kinds != 1)
      throw ConfigError(r.at(n), owner + ": give exactly one of train (a graph), optimize (a row), evaluate (a row) and "
                                         "simulation (a dataset)");
    if (n["set"] && !n["evaluate"]) throw ConfigError(r.at(n["set"]), owner + ": 'set' goes with evaluate");
    if (n["where"]) {
      if (n["optimize"] || n["simulation"]) throw ConfigError(r.at(n["where"]), owner + ": 'where' goes with train and evaluate");
      row.test_where = r.text(n["where"], owner + ".where");
      if (row.test_where.find('=') == std::string::npos) throw ConfigError(r.at(n["where"]), owner + ".where must be STAT=VALUE");
    }
  }

  std::string dataset_key(const char* key) const {
    const std::string k = r.text(n[key], owner + "." + key);
    std::vector<std::string> keys;
    for (const auto& d : spec.datasets) keys.push_back(d.key);
    if (std::find(keys.begin(), keys.end(), k) == keys.end())
      throw ConfigError(r.at(n[key]), owner + "." + key + ": no dataset '" + k + "'" + did_you_mean(k, keys) +
                                           " (datasets: " + yaml::joined(keys) + ")");
    return k;
  }

  std::string earlier_train_row(const char* key) const {
    const std::string k = r.text(n[key], owner + "." + key);
    std::vector<std::string> names;
    for (const auto& other : spec.rows)
      if (other.kind == ExperimentRowKind::Train) names.push_back(other.name);
    if (std::find(names.begin(), names.end(), k) == names.end())
      throw ConfigError(r.at(n[key]), owner + "." + key + ": no earlier training row '" + k + "'" + did_you_mean(k, names) +
                                           (names.empty() ? "" : " (training rows so far: " + yaml::joined(names) + ")"));
    return k;
  }

  void refuse(std::initializer_list<const char*> keys, const char* kind) const {
    for (const char* k : keys)
      if (n[k]) throw ConfigError(r.at(n[k]), owner + ": '" + k + "' does not apply to " + kind);
  }

  void train_row() {
    row.kind = ExperimentRowKind::Train;
    row.graph = r.path(n["train"], owner + ".train");
    row.data = n["data"] ? dataset_key("data") : spec.datasets.front().key;
    row.test = n["test"] ? dataset_key("test") : row.data;
    if (n["fraction"]) {
      row.fraction = r.number<double>(n["fraction"], owner + ".fraction");
      if (!(row.fraction > 0 && row.fraction <= 1)) throw ConfigError(r.at(n["fraction"]), owner + ".fraction must be in (0, 1]");
    }
    if (n["on_optimized"]) {
      row.on_optimized = earlier_train_row("on_optimized");
      if (!n["scene"]) throw ConfigError(r.at(n), owner + ": on_optimized needs the scene whose energy is minimised (scene:)");
      if (n["data"]) throw ConfigError(r.at(n["data"]), owner + ": on_optimized rows train on the optimised data, not on 'data'");
      row.data = spec.row(row.on_optimized).data;
      if (!n["test"]) row.test = row.data;
    }
    if (n["physics"]) row.physics = r.path(n["physics"], owner + ".physics");
  }

  // A training row's monitor names one of its graph's losses, checked here
  // so that --dry-run sees it: at the run, the row stopped with "--monitor
  // v2vv: not a loss of ..." after the rows before it had trained, naming
  // neither this file nor the line (an outside check).
  void check_monitor() const {
    const ExperimentTraining& t = row.training;
    if (row.kind != ExperimentRowKind::Train || t.monitor.empty()) return;
    std::vector<std::string> losses;
    for (const NodeSpec& node : parse_graph_file(row.graph).nodes)
      if (node.is_loss && node.weight != 0.0) losses.push_back(node.name);
    if (std::find(losses.begin(), losses.end(), t.monitor) == losses.end())
      throw ConfigError(t.monitor_where, owner + ": monitor '" + t.monitor + "' is no loss of " + row.graph.string() +
                                             " (its losses of nonzero weight: " + yaml::joined(losses) + ")" +
                                             did_you_mean(t.monitor, losses));
  }

  void optimize_row() {
    row.kind = ExperimentRowKind::Optimize;
    row.source = earlier_train_row("optimize");
    if (!n["scene"]) throw ConfigError(r.at(n), owner + ": optimize needs the scene whose energy is minimised (scene:)");
    row.test = spec.row(row.source).test;
    refuse({"data", "fraction", "physics", "training"}, "an optimize row");
  }

  void evaluate_row() {
    row.kind = ExperimentRowKind::Evaluate;
    row.source = earlier_train_row("evaluate");
    row.test = n["test"] ? dataset_key("test") : spec.row(row.source).test;
    row.physics = spec.row(row.source).physics;
    if (!n["set"] && !n["where"] && !n["test"])
      throw ConfigError(r.at(n), owner + ": evaluate changes something about the row it evaluates: set, test or where");
    if (n["set"] && (!n["set"].IsMap() || n["set"].size() == 0))
      throw ConfigError(r.at(n["set"]), owner + ": set must map node.param to values");
    if (n["set"]) for (const auto& kv : n["set"]) {
      const std::string key = kv.first.as<std::string>();
      const auto dot = key.find('.');
      if (dot == std::string::npos || dot == 0 || dot + 1 == key.size())
        throw ConfigError(r.at(kv.first), owner + ".set: '" + key + "' is not node.param");
      row.set[key] = r.text(kv.second, owner + ".set." + key);
    }
    refuse({"data", "fraction", "physics", "training", "scene", "iterations", "on_optimized"}, "an evaluate row");
  }

  void simulation_row() {
    row.kind = ExperimentRowKind::Simulation;
    row.data = dataset_key("simulation");
    row.test = row.data;
    refuse({"data", "test", "fraction", "physics", "training", "scene", "iterations", "on_optimized"}, "a simulation row");
  }

  // scene, iterations, training and the seed's numbers.
  void common_settings() {
    if (n["scene"]) {
      if (row.kind == ExperimentRowKind::Train && row.on_optimized.empty())
        throw ConfigError(r.at(n["scene"]), owner + ": 'scene' is for optimize and on_optimized rows (use physics: to measure energies)");
      row.scene = r.path(n["scene"], owner + ".scene");
    }
    if (n["iterations"]) {
      row.iterations = r.number<int>(n["iterations"], owner + ".iterations");
      if (row.iterations < 0) throw ConfigError(r.at(n["iterations"]), owner + ".iterations must be >= 0");
    }
    row.training = n["training"] ? r.training(n["training"], spec.training, owner + ".training") : spec.training;
    if (n["seed"]) {
      if (!n["seed"].IsMap()) throw ConfigError(r.at(n["seed"]), owner + ".seed must map columns to the seed's numbers");
      for (const auto& kv : n["seed"]) {
        const std::string column = kv.first.as<std::string>();
        check_column(r, kv.first, column, owner + ".seed");
        row.seed_values[column] = r.number<double>(kv.second, owner + ".seed." + column);
      }
    }
  }

  const Reader& r;
  const YAML::Node& n;
  const ExperimentSpec& spec;
  ExperimentRow row;
  std::string owner;  // "row 'NAME'", for messages
};

ExperimentRow parse_row(const Reader& r, const YAML::Node& n, const ExperimentSpec& spec) {
  return RowParser(r, n, spec).parse();
}

}  // namespace

ExperimentSpec parse_experiment_file(const fs::path& file) {
  const YAML::Node root = yaml::load_file(file);
  const Reader r{file.string(), file.parent_path()};
  ExperimentSpec spec;
  spec.file = file;
  yaml::check_file_kind(r.file, root, "experiment");
  yaml::check_keys(r.file, root, {"name", "title", "note", "datasets", "training", "columns", "rows"}, "experiment");
  for (const char* key : {"name", "datasets", "columns", "rows"})
    if (!root[key]) throw ConfigError(r.at(root), std::string("experiment: '") + key + "' is required");
  spec.name = r.text(root["name"], "name");
  if (spec.name.empty() || spec.name.find_first_of("/\\ ") != std::string::npos)
    throw ConfigError(r.at(root["name"]), "name must be a non-empty word (it names the run's folder)");
  if (root["title"]) spec.title = r.text(root["title"], "title");
  if (root["note"]) spec.note = r.text(root["note"], "note");

  if (!root["datasets"].IsMap() || root["datasets"].size() == 0)
    throw ConfigError(r.at(root["datasets"]), "datasets must map names to {scene, count, bmi, seed}");
  for (const auto& kv : root["datasets"]) {
    ExperimentDataset d;
    d.key = kv.first.as<std::string>();
    d.where = r.at(kv.first);
    const std::string owner = "dataset '" + d.key + "'";
    yaml::check_keys(r.file, kv.second, {"scene", "count", "bmi", "seed", "merge"}, owner);
    if (kv.second["merge"]) {
      if (!kv.second["merge"].IsSequence() || kv.second["merge"].size() < 2)
        throw ConfigError(r.at(kv.second["merge"]), owner + ".merge must list two or more datasets defined above it");
      for (const auto& m : kv.second["merge"]) {
        const std::string key = r.text(m, owner + ".merge");
        if (std::none_of(spec.datasets.begin(), spec.datasets.end(), [&](const ExperimentDataset& e) { return e.key == key; }))
          throw ConfigError(r.at(m), owner + ".merge: no dataset '" + key + "' above it");
        d.merge.push_back(key);
      }
      for (const char* k : {"scene", "count", "bmi", "seed"})
        if (kv.second[k]) throw ConfigError(r.at(kv.second[k]), owner + ": a merged dataset takes its samples from its parts, not '" + k + "'");
      spec.datasets.push_back(d);
      continue;
    }
    if (!kv.second["scene"] || !kv.second["count"]) throw ConfigError(d.where, owner + ": scene and count are required");
    d.scene = r.path(kv.second["scene"], owner + ".scene");
    d.count = r.number<long>(kv.second["count"], owner + ".count");
    if (d.count < 10) throw ConfigError(r.at(kv.second["count"]), owner + ".count must be at least 10 (an 8:1:1 split)");
    if (kv.second["bmi"]) d.bmi = r.text(kv.second["bmi"], owner + ".bmi");  // (checked as generate reads it: cmd_experiment.cpp)
    if (kv.second["seed"]) d.seed = r.number<std::uint64_t>(kv.second["seed"], owner + ".seed");
    spec.datasets.push_back(d);
  }
  if (root["training"]) spec.training = r.training(root["training"], spec.training, "training");

  if (!root["columns"].IsSequence() || root["columns"].size() == 0)
    throw ConfigError(r.at(root["columns"]), "columns must be a list, e.g. [ME, L_l, L_e, L_s, L_d, p]");
  for (const auto& c : root["columns"]) {
    const std::string name = r.text(c, "a column");
    check_column(r, c, name, "columns");
    spec.columns.push_back(name);
  }
  if (!root["rows"].IsSequence() || root["rows"].size() == 0) throw ConfigError(r.at(root["rows"]), "rows must be a list");
  for (const auto& n : root["rows"]) spec.rows.push_back(parse_row(r, n, spec));
  for (const auto& row : spec.rows)
    for (const auto& [column, value] : row.seed_values)
      if (std::find(spec.columns.begin(), spec.columns.end(), column) == spec.columns.end())
        throw ConfigError(row.where, "row '" + row.name + "': the seed's " + column + " is given but " + column +
                                         " is not among the columns");
  return spec;
}

}  // namespace drape
