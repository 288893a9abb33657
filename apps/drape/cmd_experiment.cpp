// `drape experiment graphs/experiments/<table>.yaml`: one table of the seed --
// its datasets generated (or reused), every row trained, optimised or
// simulated, measured on the test split -- written as Markdown and CSV next to
// the seed's numbers. Interrupted runs resume with the same command.
#include "command.hpp"
#include "experiment/experiment_runner.hpp"

#include <drape/registry.hpp>

#include <cstdio>
#include <thread>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

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

  Registry::load_default(plugin_path(vm));
  const ExperimentSpec spec = parse_experiment_file(find_input_file(vm["file"].as<std::string>()));
  for (const auto& [key, file] : o.data_files) spec.dataset(key);  // a misspelt key fails before any work
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
