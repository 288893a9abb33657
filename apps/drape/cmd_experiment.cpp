// `drape experiment graphs/experiments/<table>.yaml`: one table of the seed --
// its datasets generated (or reused), every row trained, optimised or
// simulated, measured on the test split -- written as Markdown and CSV next to
// the seed's numbers. Interrupted runs resume with the same command.
#include "command.hpp"
#include "experiment/experiment_runner.hpp"
#include "sample_ranges.hpp"

#include <drape/experiment/experiment.hpp>
#include <drape/graph.hpp>
#include <drape/registry.hpp>

#include <algorithm>
#include <cstdio>
#include <thread>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

// Each evaluate row's `set: {node.param: value}` against the graph of the
// row that trains its model: a node the graph lacks, or a parameter its
// plugin lacks, failed only after every row before it had run (an outside
// check's `postt.enabled` after an hour's training, and `post.enabeld`
// blamed on line 36 of the model's graph). --dry-run says it too.
void check_evaluate_sets(const ExperimentSpec& spec, const Registry& registry) {
  for (const ExperimentRow& row : spec.rows) {
    if (row.kind != ExperimentRowKind::Evaluate || row.set.empty()) continue;
    // The row whose graph made the model (an optimize row's model is its source's).
    const ExperimentRow* trained = &row;
    for (int hops = 0; trained->kind != ExperimentRowKind::Train && !trained->source.empty() && hops < 64; ++hops)
      trained = &spec.row(trained->source);
    if (trained->kind != ExperimentRowKind::Train) continue;
    const GraphSpec graph = parse_graph_file(trained->graph);
    std::vector<std::string> nodes;
    for (const NodeSpec& n : graph.nodes) nodes.push_back(n.name);
    for (const auto& [key, value] : row.set) {
      const std::string node = key.substr(0, key.find('.')), param = key.substr(key.find('.') + 1);
      const auto it = std::find_if(graph.nodes.begin(), graph.nodes.end(), [&](const NodeSpec& n) { return n.name == node; });
      const std::string at = "row '" + row.name + "' set '" + key + "': ";
      if (it == graph.nodes.end())
        throw ConfigError(row.where, at + "the graph of row '" + trained->name + "' (" + trained->graph.string() +
                                         ") has no node '" + node + "'" + did_you_mean(node, nodes));
      if (param.find('.') != std::string::npos) continue;  // (in.PORT: an input connected, not a parameter)
      const PluginDescriptor* d = registry.find(it->type);
      if (!d) continue;  // (an unknown type is the training's own error)
      std::vector<std::string> params;
      for (const ParamSpec& p : d->params) params.push_back(p.name);
      if (std::find(params.begin(), params.end(), param) == params.end())
        throw ConfigError(row.where, at + "node '" + node + "' (" + it->type + ") has no parameter '" + param + "'" +
                                         did_you_mean(param, params));
    }
  }
}

// Every node of a training row's graph names a plugin that is loaded: a
// misspelt type in a row's graph passed --dry-run and stopped the run when
// that row began, after the rows before it had trained (an outside check).
void check_row_plugins(const ExperimentSpec& spec, const Registry& registry) {
  for (const ExperimentRow& row : spec.rows) {
    if (row.kind != ExperimentRowKind::Train) continue;
    for (const NodeSpec& node : parse_graph_file(row.graph).nodes) {
      if (registry.find(node.type)) continue;
      try {
        registry.get(node.type);  // throws, with the close matches
      } catch (const ConfigError& e) {
        throw ConfigError(node.where, "row '" + row.name + "': " + (node.is_loss ? "loss '" : "node '") + node.name +
                                          "': " + e.what());
      }
    }
  }
}

// Each dataset's `bmi:` as the runner hands it to generate (parse_range): a
// reversed "40:20" failed as generate's "--bmi '40:20'", an option never
// typed, after every row before it had run (an outside check).
void check_dataset_ranges(const ExperimentSpec& spec) {
  for (const ExperimentDataset& d : spec.datasets) {
    if (!d.merge.empty()) continue;  // (its parts' own)
    try {
      parse_range("bmi", d.bmi);
    } catch (const UsageError&) {
      throw ConfigError(d.where, "dataset '" + d.key + "'.bmi '" + d.bmi + "': expected a BMI or a range lo:hi with lo <= hi");
    }
  }
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape experiment");
  opts.add_options()("file", po::value<std::string>(), "experiment file (graphs/experiments/*.yaml)")(
      "scale", po::value<double>()->default_value(1.0), "dataset sizes x this (e.g. 20 for the seed's 20,000 bodies, 0.1 for a quick look)")(
      "epochs", po::value<long>()->default_value(0), "override every row's epochs (0: the file's)")(
      "threads", po::value<int>()->default_value(0), "threads for generate, train and optimize (0: all cores)")(
      "work", po::value<std::string>(), "the run's folder (default runs/<name>[-x<scale>][-e<epochs>])")(
      "data-dir", po::value<std::string>()->default_value("runs/data"), "where generated datasets are kept and found again")(
      "data", po::value<std::vector<std::string>>(), "KEY=FILE: use this dataset for KEY instead of generating one (repeatable)")(
      "dry-run", po::bool_switch(), "print the commands the run needs, run nothing");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  const std::string usage =
      "drape experiment graphs/experiments/table_6_1.yaml [--scale 1] [--epochs N] [--threads T] [--data KEY=FILE] [--dry-run]";
  if (!parse(usage, args, opts, pos, vm)) return 0;
  if (!vm.count("file")) throw UsageError("an experiment file is required, e.g. graphs/experiments/table_6_1.yaml");
  ExperimentOptions o;
  o.scale = vm["scale"].as<double>();
  // (inf and 1e300 planned 10-body sets in a folder named "-xinf": an outside check.)
  if (!(o.scale > 0) || !(o.scale <= 1000))
    throw UsageError("--scale must be a number in (0, 1000] (the dataset sizes times it; 20 for the seed's 20,000 bodies)");
  o.epochs = vm["epochs"].as<long>();
  if (o.epochs < 0) throw UsageError("--epochs must be >= 0");
  o.threads = vm["threads"].as<int>();
  if (o.threads <= 0) o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.data_dir = vm["data-dir"].as<std::string>();
  o.dry_run = vm["dry-run"].as<bool>();
  if (vm.count("data"))
    for (const auto& kv : vm["data"].as<std::vector<std::string>>()) {
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size()) throw UsageError("--data wants KEY=FILE, got '" + kv + "'");
      o.data_files[kv.substr(0, eq)] = kv.substr(eq + 1);
    }

  const Registry& registry = Registry::load_default(plugin_path(vm));
  const ExperimentSpec spec = parse_experiment_file(find_input_file(vm["file"].as<std::string>()));
  for (const auto& [key, file] : o.data_files) spec.dataset(key);  // a misspelt key fails before any work
  check_dataset_ranges(spec);
  check_evaluate_sets(spec, registry);
  check_row_plugins(spec, registry);
  if (vm.count("work")) o.work_dir = vm["work"].as<std::string>();
  const auto work = experiment_work_dir(spec, o);
  std::printf("experiment %s -> %s\n", spec.name.c_str(), work.c_str());
  const ExperimentTable table = run_experiment(spec, o);
  if (o.dry_run) return 0;
  write_table(table, work);
  std::printf("\n%s\nwrote %s and %s\n", table_markdown(table).c_str(), (work / "table.md").c_str(),
              (work / "table.csv").c_str());
  return 0;
}

const RegisterCommand registered{
    {"experiment", "run one table of the seed from an experiment file (resumable) and write it as Markdown and CSV", run}};

}  // namespace
}  // namespace drape::cli
