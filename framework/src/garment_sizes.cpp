#include <drape/garment_sizes.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace drape {

GarmentSizes::GarmentSizes(std::vector<double> grades, Builder build)
    : grades_(std::move(grades)), build_(std::move(build)), materials_(grades_.size()) {}

std::optional<std::size_t> GarmentSizes::find(double g) const {
  for (std::size_t k = 0; k < grades_.size(); ++k)
    if (std::abs(grades_[k] - g) <= 1e-5 * grades_[k]) return k;
  return std::nullopt;
}

const Mesh& GarmentSizes::material(std::size_t k) const {
  if (k >= grades_.size())
    throw std::out_of_range("garment size " + std::to_string(k) + " of " + std::to_string(grades_.size()));
  // One lock over the build: two threads asking for the same size build it
  // once, and a build is rare (once per size per model).
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!materials_[k]) materials_[k] = std::make_unique<const Mesh>(build_(k));
  return *materials_[k];
}

std::size_t GarmentSizes::built() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::size_t n = 0;
  for (const auto& m : materials_) n += m != nullptr;
  return n;
}

}  // namespace drape
