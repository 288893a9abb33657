#include <drape/errors.hpp>
#include <drape/training/init.hpp>

#include <cmath>
#include <string>

namespace drape {

void uniform_fill(Tensor& weight, double bound, Rng& rng) {
  for (std::size_t i = 0; i < weight.size(); ++i) weight.data()[i] = static_cast<float>(rng.uniform(-bound, bound));
}

void xavier_uniform(Tensor& weight, int fan_in, int fan_out, Rng& rng, double gain) {
  if (fan_in + fan_out <= 0) throw Error("xavier_uniform: fan_in + fan_out must be positive, got " + std::to_string(fan_in + fan_out));
  uniform_fill(weight, gain * std::sqrt(6.0 / (fan_in + fan_out)), rng);
}

void he_uniform(Tensor& weight, int fan_in, Rng& rng) {
  if (fan_in <= 0) throw Error("he_uniform: fan_in must be positive, got " + std::to_string(fan_in));
  uniform_fill(weight, std::sqrt(6.0 / fan_in), rng);
}

}  // namespace drape
