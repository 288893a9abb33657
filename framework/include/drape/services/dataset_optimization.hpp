#pragma once
// The service behind `drape optimize --data data.h5 --split S --out
// optimized.h5` and the experiment runner's optimize steps: the
// physics-enforced optimisation of every sample of a dataset split, parallel
// over samples, resumable (the output is a dataset written like drape
// generate's), with a progress bar. Its garments can train the network again:
// the seed's self-correcting loop.
#include <drape/services/dataset_generation.hpp>  // Shard

#include <drape/training/physics_optimization.hpp>

#include <filesystem>
#include <string>

namespace drape {

struct OptimizeDatasetOptions {
  std::filesystem::path model, data, out, scene_file;
  std::string split = "train";  // train | val | test | all
  Shard shard;                  // only this part of the split's samples (a job array's task)
  int threads = 1;
  PhysicsOptimizationOptions optimization;
};

// Returns the number of samples optimised in this run.
std::size_t optimize_dataset(const Registry& registry, const OptimizeDatasetOptions& options);

}  // namespace drape
