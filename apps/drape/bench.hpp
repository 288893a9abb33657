#pragma once
// Benchmarks of `drape bench <name>`. Each lives in its own bench_*.cpp and
// registers itself with one line:
//
//   const RegisterBench registration{{"geometry", "time closest-point queries ...", run}};
//
// `run` gets the arguments after the name and parses them with cli::parse()
// (usage "drape bench <name> ..."); it returns the exit code like a command.
#include "command.hpp"

#include <functional>
#include <string>
#include <vector>

namespace drape::cli {

struct Bench {
  std::string name;
  std::string summary;
  std::function<int(const std::vector<std::string>& args)> run;
};

std::vector<Bench>& benches();

struct RegisterBench {
  explicit RegisterBench(Bench b) { benches().push_back(std::move(b)); }
};

// Times of repeated runs on a shared, noisy machine: the best is the cost of
// the work, the median what to expect. `times` must not be empty.
struct BestAndMedian {
  double best = 0, median = 0;
};
BestAndMedian best_and_median(std::vector<double> times);

// The benches that time a trained model (--model FILE) or a graph with fresh
// weights (--graph FILE) take exactly one of the two (UsageError otherwise).
void require_model_or_graph(const po::variables_map& vm);

// The int option `name` (a count: repeats, steps, a batch, iterations), at
// least 1; UsageError otherwise (some benches took 0 and -1 as 1 without a
// word, others refused them).
int count_option(const po::variables_map& vm, const std::string& name);

}  // namespace drape::cli
