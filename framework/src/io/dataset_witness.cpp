// A slim dataset's witness of the bodies it left out: a few numbers per body
// that say whether the body rebuilt from the parameters is the body the drape
// was simulated on. Without it a change to the body model (a rig's neck made
// slimmer) would silently pair every stored drape with another body.
#include "dataset_internal.hpp"

#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace drape::dataset_detail {
namespace {

// Block b of `blocks` over `vertices`: [first, last).
std::pair<std::size_t, std::size_t> block_range(std::size_t b, std::size_t blocks, std::size_t vertices) {
  return {b * vertices / blocks, (b + 1) * vertices / blocks};
}

}  // namespace

std::size_t witness_blocks(int body_vertices) {
  return std::min<std::size_t>(kWitnessBlocks, static_cast<std::size_t>(std::max(body_vertices, 0)));
}

void body_witness(const float* body, int body_vertices, double* out) {
  const std::size_t n = static_cast<std::size_t>(body_vertices), blocks = witness_blocks(body_vertices);
  for (std::size_t b = 0; b < blocks; ++b) {
    const auto [first, last] = block_range(b, blocks, n);
    double mean[3] = {0, 0, 0};
    for (std::size_t i = first; i < last; ++i)
      for (int c = 0; c < 3; ++c) mean[c] += body[i * 3 + static_cast<std::size_t>(c)];
    for (double& m : mean) m /= static_cast<double>(last - first);
    double spread = 0;  // mean squared distance from the block's mean
    for (std::size_t i = first; i < last; ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = body[i * 3 + static_cast<std::size_t>(c)] - mean[c];
        spread += d * d;
      }
    double* w = out + b * 4;
    w[0] = mean[0], w[1] = mean[1], w[2] = mean[2];
    w[3] = std::sqrt(spread / static_cast<double>(last - first));
  }
}

std::string not_the_simulated_body(const std::string& file, std::size_t row, const float* rebuilt, int body_vertices,
                                   const double* stored) {
  const std::size_t blocks = witness_blocks(body_vertices);
  std::vector<double> now(blocks * 4);
  body_witness(rebuilt, body_vertices, now.data());
  double worst = 0;
  std::size_t worst_block = 0;
  for (std::size_t k = 0; k < now.size(); ++k) {
    const double d = std::abs(now[k] - stored[k]);
    if (!(d <= worst)) worst = d, worst_block = k / 4;  // NaN counts as the worst
  }
  if (worst <= kWitnessTolerance) return "";
  const auto [first, last] = block_range(worst_block, blocks, static_cast<std::size_t>(body_vertices));
  char moved[160];
  std::snprintf(moved, sizeof moved, "its vertices %zu-%zu moved %.2f mm on average or in their spread", first, last - 1,
                1e3 * worst);
  return file + ": sample " + std::to_string(row) +
         "'s body, rebuilt from its parameters by the body model of the dataset's scene, is not the body its drape was "
         "simulated on (" + moved + "): the body model has changed since the dataset was made, and its drapes belong to "
         "other bodies. Generate the dataset again with this program (a full, not slim, copy keeps the bodies it was "
         "made on)";
}

void check_witness_shape(const h5::File& file, const DatasetLayout& layout) {
  const h5::Dims want{layout.samples, witness_blocks(layout.body_vertices), 4};
  const h5::Dims have = file.shape(kBodyWitness);
  if (have != want)
    throw ConfigError(file.path().string() + ": " + kBodyWitness + " has shape " + h5::to_string(have) + ", expected " +
                      h5::to_string(want) + " (the witness of its " + std::to_string(layout.samples) + " bodies of " +
                      std::to_string(layout.body_vertices) + " vertices)");
}

}  // namespace drape::dataset_detail
