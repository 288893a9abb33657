#pragma once
// The body a model-driven command works on: `--body FILE` (a mesh in the
// model's body topology) or `--bmi X [--height H --sex S]` (made by the
// model's body plugin). Shared by predict and optimize.
#include "command.hpp"

#include <drape/model.hpp>

namespace drape::cli {

// One sample. ConfigError for a mesh of the wrong vertex count, or a mesh
// given to a graph that takes body parameters.
SampleBatch model_body(const Model& model, const po::variables_map& vm);

}  // namespace drape::cli
