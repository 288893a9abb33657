#pragma once
// `drape experiment`: runs an experiment file (drape/experiment/experiment.hpp) as a chain
// of steps, each printed as the drape command that does it so that any step can
// be repeated by hand; generate, train and merge are calls of the framework
// services behind those commands (services/), eval and optimize still run the
// commands in this process:
//   datasets   drape generate  -> <data-dir>/<key>-<count>-<hash>.h5, shared by
//                                 every experiment that asks for the same scene,
//                                 count, BMI range and seed
//   train rows drape train --resume -> <work>/<row>.h5, then drape eval -> .eval.json,
//              and with physics: drape optimize --iters 0 on the test split -> .physics.h5
//   on_optimized  drape optimize over train+val of the source row -> <source>.optimized.h5
//   optimize rows drape optimize on the test split -> <work>/<row>.opt.h5
// A finished output is never recomputed and the commands resume their own
// partial outputs, so a killed experiment continues with the same command.
#include "experiment_table.hpp"

#include <drape/experiment/experiment.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace drape::cli {

struct ExperimentOptions {
  double scale = 1.0;                    // dataset sizes x scale (at least 10 samples each)
  long epochs = 0;                       // > 0: overrides every row's epochs (quick runs)
  int threads = 1;                       // for generate, train and optimize
  std::filesystem::path work_dir;        // empty: runs/<name> (runs/<name>-x<scale> when scaled)
  std::filesystem::path data_dir = "runs/data";
  bool dry_run = false;                  // print the commands, run nothing
  // Datasets given by hand (--data KEY=FILE) instead of generated or found in data_dir.
  std::map<std::string, std::filesystem::path> data_files;
};

// The run's folder for these options.
std::filesystem::path experiment_work_dir(const ExperimentSpec& spec, const ExperimentOptions& options);

// Runs what is missing and returns the table (rows in the file's order).
ExperimentTable run_experiment(const ExperimentSpec& spec, const ExperimentOptions& options);

}  // namespace drape::cli
