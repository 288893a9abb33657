#include "experiment_runner.hpp"

#include "../command.hpp"
#include "../sample_ranges.hpp"

#include <drape/fnv1a.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/graph.hpp>
#include <drape/io/dataset.hpp>
#include <drape/training/evaluation.hpp>
#include <drape/training/model.hpp>
#include <drape/registry.hpp>
#include <drape/training/rng.hpp>
#include <drape/io/output_lock.hpp>
#include <drape/scene/scene.hpp>
#include <drape/services/dataset_generation.hpp>
#include <drape/services/dataset_optimization.hpp>
#include <drape/services/model_evaluation.hpp>
#include <drape/progress.hpp>
#include <drape/services/model_training.hpp>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

namespace drape::cli {
namespace fs = std::filesystem;

namespace {

std::string slug(const std::string& name) {
  std::string s;
  for (char c : name) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_';
    const char out = keep ? static_cast<char>(std::tolower(static_cast<unsigned char>(c))) : '_';
    if (out == '_' && !s.empty() && s.back() == '_') continue;
    s += out;
  }
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s.empty() ? "row" : s;
}

// Eight hex digits of a stable hash (Rng::derive: FNV-1a, the same on every machine and run).
std::string hex8(const std::string& text) {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(Rng::derive(0, text)));
  return std::string(b, 8);
}

std::string exact(double v) {
  std::ostringstream o;
  o.precision(17);
  o << v;
  return o.str();
}

// What an output was made from, by content: each input file (each file of
// a dataset pattern) by name and an FNV-1a of its bytes, one per line. File
// times alone said a model trained on another dataset was up to date (the
// shipped datasets are older than any model), and the table took its
// metrics under the new data's name (an outside check).
// The FNV-1a of a file's bytes, read once per run while its size and time
// stay the same: a row checks its dataset before and after training, and
// every row of an experiment shares the same datasets (hundreds of MB).
std::string file_digest(const fs::path& file) {
  struct Known {
    std::uintmax_t size;
    fs::file_time_type time;
    std::string digest;
  };
  static std::map<std::string, Known> known;
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  const fs::file_time_type time = fs::last_write_time(file, ec);
  const std::string key = fs::absolute(file, ec).string();
  if (const auto it = known.find(key); it != known.end() && it->second.size == size && it->second.time == time)
    return it->second.digest;
  Fnv1a f;
  std::ifstream bytes(file, std::ios::binary);
  std::vector<char> buffer(1 << 20);
  while (bytes) {
    bytes.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    f.bytes(buffer.data(), static_cast<std::size_t>(bytes.gcount()));
  }
  return (known[key] = Known{size, time, f.hex()}).digest;
}

std::string inputs_identity(const std::vector<fs::path>& inputs) {
  std::string out;
  for (const auto& in : inputs) {
    std::error_code ec;
    const std::vector<fs::path> files = fs::exists(in, ec) ? std::vector<fs::path>{in} : dataset_files(in);
    for (const fs::path& file : files) out += file.filename().string() + " " + file_digest(file) + "\n";
  }
  return out;
}

// Beside each output, what it was made from (inputs_identity).
fs::path stamp_file(const fs::path& out) { return fs::path(out.string() + ".inputs"); }

void stamp(const fs::path& out, const std::vector<fs::path>& inputs) {
  if (fs::exists(out)) write_text_atomically(stamp_file(out), inputs_identity(inputs));
}

// An output is up to date when it exists and was made from these inputs as
// they are now (its stamp); an output of an earlier drape without a stamp
// when it is newer than every input.
bool up_to_date(const fs::path& out, const std::vector<fs::path>& inputs) {
  if (!fs::exists(out)) return false;
  if (fs::exists(stamp_file(out))) {
    std::ifstream in(stamp_file(out));
    const std::string recorded((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return recorded == inputs_identity(inputs);
  }
  for (const auto& in : inputs)
    if (fs::exists(in) && fs::last_write_time(in) > fs::last_write_time(out)) return false;
  return true;
}

// A stamp that exists and names other inputs: the output was made from
// something else (not merely before the stamps).
bool made_from_other(const fs::path& out, const std::vector<fs::path>& inputs) {
  return fs::exists(out) && fs::exists(stamp_file(out)) && !up_to_date(out, inputs);
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / double(v.size());
}

double sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

// The energy columns and p from a dataset's statistics (a simulation or an optimisation).
void physics_columns(const DatasetReader& r, const std::vector<std::size_t>& indices, std::map<std::string, double>& out) {
  const std::pair<const char*, const char*> energies[] = {{"L_st", "energy_stretching"}, {"L_b", "energy_bending"},
                                                          {"L_g", "energy_gravity"},     {"L_c", "energy_collision"},
                                                          {"L_p", "energy_total"}};
  for (const auto& [column, stat] : energies)
    if (r.layout().has_stat(stat)) out[column] = mean(r.stat(stat, indices));
  if (r.layout().has_stat("penetration")) out["p"] = 100.0 * mean(r.stat("penetration", indices));
}

class Runner {
 public:
  Runner(const ExperimentSpec& spec, const ExperimentOptions& options)
      : spec_(spec), o_(options), work_(experiment_work_dir(spec, options)) {}

  ExperimentTable run() {
    if (!o_.dry_run) {
      fs::create_directories(work_);
      fs::create_directories(o_.data_dir);
    }
    ExperimentTable table;
    table.title = spec_.title.empty() ? spec_.name : spec_.title;
    table.note = spec_.note;
    table.columns = spec_.columns;
    for (const auto& d : spec_.datasets) dataset(d.key);
    for (const auto& row : spec_.rows) {
      std::printf("\n== %s: row '%s'\n", spec_.name.c_str(), row.name.c_str());
      std::fflush(stdout);
      ExperimentTableRow out = this->row(row);
      table.rows.push_back(out);
      table.seed.push_back(row.seed_values);
    }
    table.setup = setup_text();
    return table;
  }

 private:
  // Prints the `drape <args>` that does a step, so that it can be repeated by
  // hand; false on a dry run (then nothing runs).
  bool announce(const std::vector<std::string>& args) const {
    std::printf("$ %s\n", command_line(args).c_str());
    std::fflush(stdout);
    return !o_.dry_run;
  }
  // Quoted where a shell would read it otherwise (a dataset pattern's `*`
  // expanded to several files, and the line pasted did not run).
  static std::string command_line(const std::vector<std::string>& args) {
    std::string line = "drape";
    for (const auto& a : args) line += " " + shell_word(a);
    return line;
  }

  // A dataset of the experiment file, made by the generator's service.
  void generate(const ExperimentDataset& d, long count, const fs::path& file) {
    if (!announce({"generate", d.scene.string(), "--count", std::to_string(count), "--bmi", d.bmi, "--seed",
                   std::to_string(d.seed), "--threads", threads(), "--out", file.string()}))
      return;
    GenerateRequest request;
    request.count = static_cast<std::size_t>(count);
    request.bmi = parse_range("bmi", d.bmi);
    request.seed = d.seed;
    request.threads = o_.threads;
    GenerateObserver observer;
    observer.progress = &std::cerr;
    const GenerateSummary done = generate_dataset(registry(), load_scene(d.scene), request, file.string(), observer);
    std::printf("wrote %s: %zu samples; %d not settled\n", file.c_str(), done.samples, done.not_settled);
  }

  static const Registry& registry() { return Registry::load_default({}); }

  long scaled(long count) const { return std::max(10L, std::lround(double(count) * o_.scale)); }
  std::string threads() const { return std::to_string(o_.threads); }

  const fs::path& dataset(const std::string& key) {
    const auto known = datasets_.find(key);
    if (known != datasets_.end()) return known->second;
    const ExperimentDataset& d = spec_.dataset(key);
    const auto given = o_.data_files.find(key);
    if (given != o_.data_files.end()) {
      std::printf("dataset '%s': using %s as given\n", key.c_str(), given->second.c_str());
      return datasets_[key] = given->second;
    }
    if (!d.merge.empty()) {
      std::vector<std::string> args = {"dataset", "merge", "--mixed-sizes", "--out"};
      std::string identity;
      std::vector<std::string> parts;
      for (const auto& part : d.merge) {
        parts.push_back(dataset(part).string());
        identity += parts.back() + "|";
      }
      const fs::path file = o_.data_dir / (key + "-" + hex8(identity) + ".h5");
      if (fs::exists(file)) {
        std::printf("dataset '%s': reusing %s\n", key.c_str(), file.c_str());
      } else {
        args.push_back(file.string());
        args.insert(args.end(), parts.begin(), parts.end());
        if (announce(args)) {
          std::vector<fs::path> shards(parts.begin(), parts.end());
          const OutputLock lock(file, "drape dataset merge");
          merge_datasets(shards, file, /*require_complete=*/true, /*mixed_sizes=*/true);
        }
      }
      return datasets_[key] = file;
    }
    const long count = scaled(d.count);
    const std::string identity = load_scene(d.scene).yaml() + "|" + std::to_string(count) + "|" + d.bmi + "|" +
                                 std::to_string(d.seed);
    const fs::path file = o_.data_dir / (key + "-" + std::to_string(count) + "-" + hex8(identity) + ".h5");
    if (fs::exists(file))
      std::printf("dataset '%s': reusing %s\n", key.c_str(), file.c_str());
    else
      generate(d, count, file);
    return datasets_[key] = file;
  }

  fs::path model_file(const ExperimentRow& row) const { return work_ / (slug(row.name) + ".h5"); }

  // Trains (or resumes, or finds finished) the model of a training row.
  fs::path train(const ExperimentRow& row) {
    const fs::path model = model_file(row);
    if (trained_.count(row.name)) return model;
    fs::path data = dataset(row.data);
    if (!row.on_optimized.empty()) data = optimized_training_data(row);
    const ExperimentTraining& t = row.training;
    TrainOptions o;
    o.graph = row.graph;
    o.data = data;
    o.out = model;
    o.epochs = o_.epochs > 0 ? o_.epochs : t.epochs;
    o.batch = t.batch;
    o.lr = t.lr;
    o.schedule = t.schedule;
    o.patience = t.patience;
    o.monitor = t.monitor;
    o.seed = t.seed;
    o.train_fraction = row.fraction;
    o.threads = o_.threads;
    o.resume = true;
    o.log = &std::cout;
    o.progress = &std::cerr;
    const std::optional<Checkpoint> earlier = fs::exists(model) ? std::optional(read_checkpoint(model)) : std::nullopt;
    // A model trained with other settings than the row's now is no model of
    // this row: a changed lr, batch, seed or patience was "trained already"
    // while the table's heading named the new value (an outside check).
    const std::string changed = earlier ? changed_settings(*earlier, o) : "";
    if (changed.empty() && finished_training(model, earlier, row.graph, data, o.epochs)) {
      std::printf("model %s: trained already\n", model.c_str());
      trained_.insert(row.name);
      return model;
    }
    // A model of another graph (edited since), finished or not, is no run to
    // resume: drape train --resume refused it, and the row stopped there.
    // Nor is one trained on other data (its stamp), or with other settings.
    const bool edited = earlier && earlier->graph != parse_graph_file(row.graph).text;
    const bool other_data = !edited && made_from_other(model, {data});
    const bool other_settings = !edited && !other_data && !changed.empty();
    if (edited) std::printf("model %s: %s was edited since it was trained: trained again\n", model.c_str(), row.graph.c_str());
    if (other_data)
      std::printf("model %s: trained on other data than %s: trained again\n", model.c_str(), data.c_str());
    if (other_settings) std::printf("model %s: trained with %s: trained again\n", model.c_str(), changed.c_str());
    o.force = edited || other_data || other_settings;
    std::vector<std::string> args{"train", row.graph.string(), "--data", data.string(), "--out", model.string(), "--epochs",
                                  std::to_string(o.epochs), "--batch", std::to_string(t.batch), "--lr", exact(t.lr), "--schedule",
                                  t.schedule, "--patience", std::to_string(t.patience), "--seed", std::to_string(t.seed),
                                  "--fraction", exact(row.fraction), "--threads", threads()};
    if (!t.monitor.empty()) args.insert(args.end(), {"--monitor", t.monitor});
    // (drape train takes one of them: the line printed is one a user can run.)
    args.push_back(o.force ? "--force" : "--resume");
    if (announce(args)) {
      // The stamp goes first: a run killed while training again would leave
      // the old one, and the next run with the old data would resume the
      // half-trained model of the new (an outside check).
      std::error_code ec;
      fs::remove(stamp_file(model), ec);
      try {
        train_model(registry(), o);
      } catch (const ResumeRefused& e) {
        // An interrupted training of other data or settings than the row's
        // now (its state says which): the row is trained again, as drape
        // experiment has no --force to say so (it stopped with "--force to
        // start over").
        if (o.force) throw;
        std::printf("model %s: its earlier training cannot be resumed (%s): trained again\n", model.c_str(), e.what());
        o.force = true;
        train_model(registry(), o);
      }
      stamp(model, {data});
    }
    trained_.insert(row.name);
    return model;
  }

  // A model whose training ended (all epochs, or stopped early) on this data;
  // anything else goes back to drape train --resume, which checks the settings.
  // The settings a model records (drape train's recorded_settings) that
  // differ from those the row trains with, in words ("lr 0.001 where the row
  // now gives 0.005, ..."); "" when none does. Threads are not compared: they
  // change the sums' rounding only, and a rerun may be given another --threads.
  static std::string changed_settings(const Checkpoint& c, const TrainOptions& o) {
    std::map<std::string, std::string> now = recorded_settings(o);
    // Every key a model may record: those of options with each optional setting given.
    TrainOptions every = o;
    every.monitor = "m", every.weight_decay = 1, every.train_fraction = 0.5, every.schedule = "cosine", every.init = "i";
    every.init_widen = every.init_partial = true;
    std::string out;
    for (const auto& [key, unused] : recorded_settings(every)) {
      // (Epochs are finished_training's: every model records its planned
      // epochs, and with a constant schedule more of them resume.)
      if (key == "threads" || key == "epochs") continue;
      const auto was = c.meta.find(key);
      const auto is = now.find(key);
      const std::string before = was == c.meta.end() ? "" : was->second, after = is == now.end() ? "" : is->second;
      if (before != after)
        out += std::string(out.empty() ? "" : ", ") + key + " " + shown(before) + " where the row now gives " + shown(after);
    }
    return out;
  }
  // Compared exactly, shown short (0.005, not 0.0050000000000000001).
  static std::string shown(const std::string& value) {
    if (value.empty()) return "(none)";
    if (value.find_first_of(".eE") == std::string::npos) return value;  // a count or seed, as written
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (end == value.c_str() || *end != '\0') return value;
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
  }

  // `earlier`: the model file's checkpoint, read once by the caller (none: no file).
  static bool finished_training(const fs::path& model, const std::optional<Checkpoint>& earlier, const fs::path& graph,
                                const fs::path& data, long epochs) {
    if (!earlier || !up_to_date(model, {data})) return false;
    if (earlier->graph != parse_graph_file(graph).text) return false;  // the graph was edited since
    const auto status = earlier->meta.find("status");
    const auto planned = earlier->meta.find("epochs");
    return status != earlier->meta.end() && (status->second == "finished" || status->second == "early stopped") &&
           planned != earlier->meta.end() && planned->second == std::to_string(epochs);
  }

  // The source row's model optimised on every train and validation body: the seed's retraining data.
  fs::path optimized_training_data(const ExperimentRow& row) {
    const ExperimentRow& source = spec_.row(row.on_optimized);
    const fs::path model = train(source);
    const fs::path out = work_ / (slug(source.name) + ".optimized-" + std::to_string(row.iterations) + ".h5");
    optimize(model, row.scene, dataset(source.data), "train,val", row.iterations, out);
    return out;
  }

  void optimize(const fs::path& model, const fs::path& scene, const fs::path& data, const std::string& split,
                int iterations, const fs::path& out) {
    if (up_to_date(out, {model, data})) return;
    if (!o_.dry_run && fs::exists(out)) fs::remove(out);  // made from an older model
    if (!announce({"optimize", "--model", model.string(), "--scene", scene.string(), "--data", data.string(), "--split",
                   split, "--iters", std::to_string(iterations), "--threads", threads(), "--out", out.string()}))
      return;
    OptimizeDatasetOptions o;
    o.model = model;
    o.data = data;
    o.out = out;
    o.scene_file = scene;
    o.split = split;
    o.threads = o_.threads;
    o.optimization.iterations = iterations;
    std::size_t n = 0;
    try {
      n = optimize_dataset(registry(), o);
    } catch (const ResumeRefused& e) {
      // A partial file of an earlier model (the row trained again since it
      // was killed): begun again, as experiment has no way to say so (it
      // stopped with "delete it to start over", an outside check).
      const fs::path partial = out.string() + ".partial";
      std::printf("%s: made from another model or data than now (%s): begun again\n", partial.c_str(), e.what());
      fs::remove(partial);
      n = optimize_dataset(registry(), o);
    }
    std::printf("wrote %s: %zu samples optimised in this run\n", out.c_str(), n);
    stamp(out, {model, data});
  }

  // The model's metrics on the test split, written to `report` by the evaluation service.
  void evaluate(const ExperimentRow& row, const fs::path& model, const fs::path& test, const Model::ParamOverrides& overrides,
                const fs::path& report) {
    std::vector<std::string> args = {"eval", "--model", model.string(), "--data", test.string(), "--split", "test"};
    for (const auto& [key, value] : row.set) args.insert(args.end(), {"--set", key + "=" + value});
    if (!row.test_where.empty()) args.insert(args.end(), {"--where", row.test_where});
    args.insert(args.end(), {"--out", report.string()});
    if (!announce(args)) return;
    Model m = Model::load(registry(), model, overrides);
    const DatasetReader data(test);
    EvaluationRequest request;
    request.data_file = test;
    request.where = row.test_where;
    ProgressBar bar("eval", selected_samples(data, nullptr, request).size(), std::cerr);
    const ModelEvaluation result = evaluate_on_dataset(m, data, nullptr, request, &bar);
    bar.finish();
    write_evaluation_report(report, model.string(), "", test.string(), request.split, result);
    std::printf("wrote %s\n", report.c_str());
  }

  // Core-hours behind a trained model: the simulations it learnt from, its
  // training, and for a retrained model its source and the optimisation.
  double core_hours(const ExperimentRow& row) {
    const Checkpoint c = read_checkpoint(model_file(row));
    const double threads_used = c.meta.count("threads") ? std::stod(c.meta.at("threads")) : 1.0;
    double seconds = std::stod(c.meta.at("seconds")) * threads_used;
    if (row.on_optimized.empty()) {
      const DatasetReader r(dataset(row.data));
      std::vector<std::size_t> used = r.indices(Split::Train);
      used.resize(static_cast<std::size_t>(std::ceil(row.fraction * double(used.size()))));
      const auto val = r.indices(Split::Val);
      used.insert(used.end(), val.begin(), val.end());
      if (r.layout().has_stat("seconds")) seconds += sum(r.stat("seconds", used));
      return seconds / 3600.0;
    }
    const ExperimentRow& source = spec_.row(row.on_optimized);
    const DatasetReader opt(optimized_training_data(row));
    seconds += sum(opt.stat("seconds", opt.indices()));
    return seconds / 3600.0 + core_hours(source);
  }

  // Milliseconds per body of the model's forward pass on one core (best of 20), cached next to the model.
  double inference_ms(const ExperimentRow& row, const fs::path& model, const Model::ParamOverrides& overrides = {}) {
    const fs::path cache = work_ / (slug(row.name) + ".infer-ms.txt");
    if (up_to_date(cache, {model})) {
      double ms = 0;
      std::ifstream(cache) >> ms;
      if (ms > 0) return ms;
    }
    Model m = Model::load(Registry::load_default({}), model, overrides);
    const DatasetReader r(dataset(row.test));
    const double best = prediction_ms(m, read_samples(r, {r.indices(Split::Test).front()}, m.graph(), false));
    std::ofstream(cache) << exact(best) << "\n";
    stamp(cache, {model});
    return best;
  }

  bool wants(const std::string& column) const {
    return std::find(spec_.columns.begin(), spec_.columns.end(), column) != spec_.columns.end();
  }

  ExperimentTableRow row(const ExperimentRow& row) {
    ExperimentTableRow out;
    out.name = row.name;
    if (row.kind == ExperimentRowKind::Simulation) {
      const fs::path data = dataset(row.data);
      out.provenance = data.string() + " (test split)";
      if (o_.dry_run) return out;
      const DatasetReader r(data);
      const auto test = r.indices(Split::Test);
      physics_columns(r, test, out.values);
      out.values["e2e_h"] = 0;
      if (r.layout().has_stat("seconds")) out.values["infer"] = mean(r.stat("seconds", test));
      out.infer_unit = "s";
      return out;
    }
    if (row.kind == ExperimentRowKind::Optimize) {
      const ExperimentRow& source = spec_.row(row.source);
      const fs::path model = train(source);
      const fs::path out_file = work_ / (slug(row.name) + ".opt.h5");
      optimize(model, row.scene, dataset(source.test), "test", row.iterations, out_file);
      out.provenance = out_file.string();
      if (o_.dry_run) return out;
      const DatasetReader r(out_file);
      // The drapes the optimiser could not bring onto the true body (separated
      // 0) lie inside it: they are counted in the row's name, not averaged in.
      const std::vector<std::size_t> all = r.indices(), results = optimizer_results(r, all);
      if (results.size() < all.size())
        out.name += " (" + std::to_string(all.size() - results.size()) + " of " + std::to_string(all.size()) + " not results)";
      physics_columns(r, results, out.values);
      out.values["infer"] = mean(r.stat("seconds", all));
      out.infer_unit = "s";
      if (wants("e2e_h")) out.values["e2e_h"] = core_hours(source);
      return out;
    }
    const ExperimentRow& trained = row.kind == ExperimentRowKind::Evaluate ? spec_.row(row.source) : row;
    const fs::path model = train(trained);
    const fs::path test = dataset(row.test);
    const fs::path eval = work_ / (slug(row.name) + ".eval.json");
    out.provenance = model.string();
    Model::ParamOverrides overrides;
    for (const auto& [key, value] : row.set) {
      overrides[key.substr(0, key.find('.'))][key.substr(key.find('.') + 1)] = value;
      out.provenance += " with " + key + "=" + value;
    }
    if (!up_to_date(eval, {model, test})) {
      evaluate(row, model, test, overrides, eval);
      // (Not on a dry run: nothing ran, and the old report stamped with the
      // new inputs was taken as current by the next real run, an outside check.)
      if (!o_.dry_run) stamp(eval, {model, test});
    }
    fs::path physics;
    if (!row.physics.empty() && row.kind == ExperimentRowKind::Train) {
      physics = work_ / (slug(row.name) + ".physics.h5");
      optimize(model, row.physics, test, "test", 0, physics);
    }
    if (o_.dry_run) return out;
    if (!physics.empty()) {
      const DatasetReader r(physics);
      physics_columns(r, r.indices(), out.values);
    }
    const YAML::Node metrics = YAML::LoadFile(eval.string())["metrics"];
    for (const auto& kv : metrics) out.values[kv.first.as<std::string>()] = kv.second["mean"].as<double>();
    const Checkpoint c = read_checkpoint(model);
    out.values["train_h"] = std::stod(c.meta.at("seconds")) / 3600.0;
    if (wants("e2e_h")) out.values["e2e_h"] = core_hours(trained);
    if (wants("infer")) out.values["infer"] = inference_ms(row, model, overrides);
    out.infer_unit = "ms";
    return out;
  }

  std::string setup_text() const {
    std::ostringstream s;
    s << "Run: `drape experiment " << spec_.file.string() << (o_.scale != 1 ? " --scale " + exact(o_.scale) : "")
      << (o_.epochs > 0 ? " --epochs " + std::to_string(o_.epochs) : "") << " --threads " << o_.threads;
    for (const auto& [key, file] : o_.data_files) s << " --data " << key << "=" << file.filename().string();
    s << "` (" << std::thread::hardware_concurrency() << " cores here). Datasets:";
    for (const auto& d : spec_.datasets) {
      // A dataset given with --data is what the table was made on, not the
      // file's recipe: name it and its split, so the heading cannot claim
      // bodies the run never saw.
      const auto given = o_.data_files.find(d.key);
      if (given != o_.data_files.end()) {
        const DatasetReader r(given->second);
        s << " " << d.key << " = " << given->second.filename().string() << " (given), " << r.indices().size()
          << " samples: " << r.indices(Split::Train).size() << " train, " << r.indices(Split::Val).size() << " val, "
          << r.indices(Split::Test).size() << " test;";
        continue;
      }
      s << " " << d.key << " = " << d.scene.filename().string() << ", " << scaled(d.count) << " bodies, BMI " << d.bmi
        << ", seed " << d.seed << ";";
    }
    const ExperimentTraining& t = spec_.training;
    s << " training: " << (o_.epochs > 0 ? o_.epochs : t.epochs) << " epochs, batch " << t.batch << ", lr " << t.lr << " ("
      << t.schedule << "), patience " << t.patience << (t.monitor.empty() ? "" : ", the best epoch by " + t.monitor)
      << ", seed " << t.seed << " (rows may override).";
    return s.str();
  }

  const ExperimentSpec& spec_;
  const ExperimentOptions& o_;
  fs::path work_;
  std::map<std::string, fs::path> datasets_;
  std::set<std::string> trained_;
};

}  // namespace

fs::path experiment_work_dir(const ExperimentSpec& spec, const ExperimentOptions& options) {
  if (!options.work_dir.empty()) return options.work_dir;
  std::string name = spec.name;
  if (options.scale != 1.0) {
    std::ostringstream s;
    s << "-x" << options.scale;
    name += s.str();
  }
  if (options.epochs > 0) name += "-e" + std::to_string(options.epochs);
  return fs::path("runs") / name;
}

ExperimentTable run_experiment(const ExperimentSpec& spec, const ExperimentOptions& options) {
  return Runner(spec, options).run();
}

}  // namespace drape::cli
