#pragma once
// A model's garment in each size of its size chart, built only when asked:
// a model of a dozen sizes dresses one body in one of them, and building all
// twelve patterns at load (each a pattern graded, meshed and dressed) cost
// half of a `drape predict`.
#include <drape/mesh.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace drape {

class GarmentSizes {
 public:
  // Builds the material space (a mesh with UVs) of the size at an index of
  // `grades`.
  using Builder = std::function<Mesh(std::size_t)>;

  GarmentSizes(std::vector<double> grades, Builder build);

  // Each size's grade (the garment's girth over the design size's), in the
  // chart's order.
  const std::vector<double>& grades() const { return grades_; }

  // The size of grade g, if the chart has one: equal to a relative 1e-5 (a
  // graph's grade input is a float32).
  std::optional<std::size_t> find(double g) const;

  // The material space of size k, built at the first call; safe to call
  // from several threads. Throws std::out_of_range past the last size.
  const Mesh& material(std::size_t k) const;

  // How many sizes have been built so far (what the laziness saves: tests).
  std::size_t built() const;

 private:
  std::vector<double> grades_;
  Builder build_;
  mutable std::mutex mutex_;
  mutable std::vector<std::unique_ptr<const Mesh>> materials_;  // null until built
};

}  // namespace drape
