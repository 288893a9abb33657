// The energies sum in a fixed order whatever the number of threads: value,
// gradient and Hessian triplets are bit-identical with 1 and 2 threads.
#include <drape/element_assembly.hpp>

#include <catch2/catch.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "energy_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

struct Evaluation {
  double value, gradient_value;
  Eigen::MatrixX3d gradient;
  Triplets hessian, projected;
};

Evaluation evaluate(const Energy& e, const Eigen::MatrixX3d& x) {
  Evaluation r;
  r.value = e.value(x);
  r.gradient = Eigen::MatrixX3d::Zero(x.rows(), 3);
  r.gradient_value = e.add_gradient(x, r.gradient);
  e.add_hessian(x, r.hessian, false);
  e.add_hessian(x, r.projected, true);
  return r;
}

bool identical(const Triplets& a, const Triplets& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].row() != b[i].row() || a[i].col() != b[i].col() || a[i].value() != b[i].value()) return false;
  return true;
}

}  // namespace

TEST_CASE("energies give bit-identical results with 1 and 2 threads", "[stretching][bending]") {
#ifndef _OPENMP
  WARN("built without OpenMP: nothing to compare");
#else
  // 8464 vertices, 16562 faces, 24655 hinges: past the sizes from which sums run in parallel.
  const auto garment = two_material_grid(92, 0.005);
  static_assert(2 * 91 * 91 >= kParallelSumMinimum);
  const Eigen::MatrixX3d x = perturbed(garment->mesh.vertices, 0.0015, 8);
  for (const std::string name : {"stretching", "bending"}) {
    const auto e = bound_energy(name, "{}", *garment);
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const Evaluation one = evaluate(*e, x);
    omp_set_num_threads(2);
    const Evaluation two = evaluate(*e, x);
    omp_set_num_threads(threads);
    INFO(name);
    CHECK(one.value > 0.0);
    CHECK(one.value == two.value);
    CHECK(one.gradient_value == one.value);
    CHECK(two.gradient_value == two.value);
    CHECK(one.gradient == two.gradient);
    CHECK(identical(one.hessian, two.hessian));
    CHECK(identical(one.projected, two.projected));
  }
#endif
}
