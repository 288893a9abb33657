#pragma once
// The dataset-filling worker pool lives in the framework (drape/io/parallel_samples.hpp).
#include <drape/io/parallel_samples.hpp>

namespace drape::cli {
using drape::make_samples_in_parallel;
using drape::SampleWorker;
}  // namespace drape::cli
