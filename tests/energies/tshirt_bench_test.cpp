// Timing of the energies on the default T-shirt (hidden: run with
// `test_energies "[.bench]"`). Prints milliseconds per call; asserts nothing
// about time.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "../garments/tshirt_support.hpp"
#include "energy_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

template <class Fn>
double best_ms(Fn&& fn, int repeats = 20) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

void bench(const std::string& name, const std::string& yaml, const Garment& garment, const Eigen::MatrixX3d& x) {
  std::unique_ptr<Energy> e;
  const double bind = best_ms([&] { e = bound_energy(name, yaml, garment); }, 3);
  Eigen::MatrixX3d g(x.rows(), 3);
  Triplets t;
  t.reserve(3'000'000);
  const double value = best_ms([&] { e->value(x); });
  const double gradient = best_ms([&] { g.setZero(); e->add_gradient(x, g); });
  const double exact = best_ms([&] { t.clear(); e->add_hessian(x, t, false); });
  const double projected = best_ms([&] { t.clear(); e->add_hessian(x, t, true); });
  std::printf("%-10s %-22s bind %7.2f  value %6.2f  gradient %6.2f  hessian exact %6.2f  projected %6.2f ms  (%zu triplets)\n",
              name.c_str(), yaml.c_str(), bind, value, gradient, exact, projected, t.size());
  CHECK(std::isfinite(e->value(x)));
}

}  // namespace

TEST_CASE("energy timings on the default T-shirt", "[.bench]") {
  const Garment garment = build_tshirt();
  std::printf("T-shirt: %d vertices, %d faces\n", garment.mesh.num_vertices(), garment.mesh.num_faces());
  // The dressed rest state, and one perturbed by 2 mm (mixed tension and compression).
  for (const bool perturb : {false, true}) {
    const Eigen::MatrixX3d x = perturb ? perturbed(garment.mesh.vertices, 0.002, 1) : garment.mesh.vertices;
    for (const int threads : {1, 2}) {
#ifdef _OPENMP
      omp_set_num_threads(threads);
#else
      if (threads > 1) continue;
#endif
      std::printf("-- %s, %d thread(s)\n", perturb ? "perturbed 2 mm" : "dressed rest state", threads);
      bench("stretching", "{}", garment, x);
      bench("bending", "{}", garment, x);
      bench("bending", "{projection: eigen}", garment, x);
    }
  }
}
