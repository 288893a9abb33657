#include <drape/nn/init.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace drape::nn {

std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t salt) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (salt + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

float he_std(const Activation& f, int fan_in) {
  double gain2 = 1.0;
  if (f.kind == ActivationKind::Relu) gain2 = 2.0;
  if (f.kind == ActivationKind::LeakyRelu) gain2 = 2.0 / (1.0 + double(f.negative_slope) * f.negative_slope);
  return static_cast<float>(std::sqrt(gain2 / std::max(1, fan_in)));
}

void fill_normal(Tensor& w, float std, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> normal(0.0f, std);
  for (std::size_t i = 0; i < w.size(); ++i) w.data()[i] = normal(rng);
}

}  // namespace drape::nn
