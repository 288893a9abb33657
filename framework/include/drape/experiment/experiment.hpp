#pragma once
// An experiment file (graphs/experiments/*.yaml): one table of the seed as the
// datasets it needs, the training settings, the columns and one entry per row.
// `drape experiment FILE` (apps/drape/experiment/) turns it into drape
// commands -- generate, train, eval, optimize -- whose outputs it keeps, so an
// interrupted run resumes, and writes the table next to the seed's numbers.
//
//   name: table_6_4
//   title: "Self-correcting loop (seed Table 6.4)"
//   datasets:
//     regular: {scene: ../scenes/tshirt_coarse.yaml, count: 1000, bmi: "10:65", seed: 1}
//   training: {epochs: 60, batch: 16, lr: 1.0e-3, schedule: cosine, patience: 20, seed: 0}  (monitor: v2v optional)
//   columns: [L_p, p, e2e_h, infer]
//   rows:
//     - {name: Simulation, simulation: regular, seed: {L_p: 1.0e-4, p: 0.0}}
//     - {name: 4k, train: ../drape.yaml, fraction: 0.25, physics: ../scenes/tshirt_coarse.yaml}
//     - {name: 4k-opt, optimize: 4k, scene: ../scenes/tshirt_coarse.yaml, iterations: 100}
//     - {name: 4k-retrain, train: ../drape.yaml, on_optimized: 4k, iterations: 100, physics: ...}
//
// Paths are relative to the experiment file. Errors name the file, the line
// and the key, with close matches for a misspelt key, column or row name.
#include <drape/errors.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace drape {

struct ExperimentDataset {
  std::string key;
  std::vector<std::string> merge;  // non-empty: the union of these datasets (of different garment sizes)
  std::filesystem::path scene;
  long count = 0;            // before --scale
  std::string bmi = "10:65";
  std::uint64_t seed = 0;
  SourceLocation where;
};

struct ExperimentTraining {
  long epochs = 60;
  int batch = 16;
  double lr = 1e-3;
  std::string schedule = "cosine";
  int patience = 20;
  std::uint64_t seed = 0;
  std::string monitor;  // drape train --monitor: a loss of each row's graph that chooses the best epoch; "": the total
  SourceLocation monitor_where;  // where monitor was given (it names a loss of each training row's graph: checked at load)
};

enum class ExperimentRowKind {
  Train,       // train a graph, evaluate it on the test split (and its energies under `physics`)
  Optimize,    // optimise another row's model on every test body (Sec. 6.4)
  Simulation,  // the simulated test drapes of a dataset themselves
  Evaluate,    // another row's model measured with some graph parameters changed (e.g. post-processing on)
};

struct ExperimentRow {
  std::string name;
  ExperimentRowKind kind = ExperimentRowKind::Train;
  std::filesystem::path graph;     // Train
  std::string data;                // Train: dataset key (default: the first); Simulation: its dataset
  std::string test;                // Train: dataset whose test split is measured (default: data)
  std::string test_where;          // Train, Evaluate: only test samples with this statistic value ("garment_size=1")
  double fraction = 1.0;           // Train: of the training split
  std::string on_optimized;        // Train: train on this row's model optimised over train+val (the seed's retraining)
  std::string source;              // Optimize, Evaluate: the row whose model is used
  std::map<std::string, std::string> set;  // Evaluate: "node.param" -> YAML value
  std::filesystem::path physics;   // Train: scene whose energies are measured on the predictions (optional)
  std::filesystem::path scene;     // Optimize, and on_optimized: the scene whose L_p is minimised
  int iterations = 100;            // Optimize, on_optimized
  ExperimentTraining training;     // the experiment's, with this row's overrides
  std::map<std::string, double> seed_values;  // the seed's numbers for this row, by column
  SourceLocation where;
};

struct ExperimentColumn {
  std::string name, header, unit;
  const char* doc;
  // Why the seed's number in this column is not the same quantity as ours
  // (nullptr: it is): tables then give ours alone and the seed's apart.
  const char* not_as_the_seed = nullptr;
};
// Every column an experiment may ask for, in a fixed order.
const std::vector<ExperimentColumn>& experiment_columns();

struct ExperimentSpec {
  std::filesystem::path file;
  std::string name, title, note;
  std::vector<ExperimentDataset> datasets;
  ExperimentTraining training;
  std::vector<std::string> columns;
  std::vector<ExperimentRow> rows;

  const ExperimentDataset& dataset(const std::string& key) const;
  const ExperimentRow& row(const std::string& name) const;
};

// Reads and checks an experiment file: every key known, every dataset and row
// a row refers to defined (and defined before it, for rows), every path present.
ExperimentSpec parse_experiment_file(const std::filesystem::path& file);

}  // namespace drape
