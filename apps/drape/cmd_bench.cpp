// `drape bench <name> [options]`: runs one of the registered benchmarks
// (bench.hpp); `drape bench list` or `--help` lists them.
#include "bench.hpp"

#include <drape/errors.hpp>

#include <algorithm>
#include <iostream>

namespace drape::cli {

std::vector<Bench>& benches() {
  static std::vector<Bench> list;
  return list;
}

BestAndMedian best_and_median(std::vector<double> times) {
  std::sort(times.begin(), times.end());
  return {times.front(), times[times.size() / 2]};
}

int count_option(const po::variables_map& vm, const std::string& name) {
  const int n = vm[name].as<int>();
  if (n < 1) throw UsageError("--" + name + " " + std::to_string(n) + ": expected at least 1");
  return n;
}

void require_model_or_graph(const po::variables_map& vm) {
  if (vm.count("model") == vm.count("graph")) throw UsageError("give exactly one of --model FILE and --graph FILE");
}

namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

const char* kUsage = "drape bench <name> [options]   (drape bench <name> --help for its options)";

std::vector<std::string> bench_names() {
  std::vector<std::string> names;
  for (const auto& b : benches()) names.push_back(b.name);
  std::sort(names.begin(), names.end());
  return names;
}

std::string listing() {
  std::vector<Bench> list = benches();
  std::sort(list.begin(), list.end(), [](const Bench& a, const Bench& b) { return a.name < b.name; });
  std::size_t width = 0;
  for (const auto& b : list) width = std::max(width, b.name.size());
  std::string s = "benchmarks:\n";
  for (const auto& b : list) s += "  " + b.name + std::string(width + 2 - b.name.size(), ' ') + b.summary + "\n";
  return s;
}

int run(const std::vector<std::string>& args) {
  if (args.empty()) throw UsageError(std::string("which benchmark?\nusage: ") + kUsage + "\n" + listing());
  const std::string& name = args[0];
  if (name == "list" || name == "--help" || name == "-h" || name == "help") {
    std::cout << "usage: " << kUsage << "\n\n" << listing();
    return 0;
  }
  for (const auto& b : benches())
    if (b.name == name) return b.run(std::vector<std::string>(args.begin() + 1, args.end()));
  throw UsageError("unknown benchmark '" + name + "'" + did_you_mean(name, bench_names()) +
                   " (drape bench list shows them)");
}

const RegisterCommand registration{{"bench", "run a benchmark: drape bench <name> (drape bench list)", run}};

}  // namespace
}  // namespace drape::cli
