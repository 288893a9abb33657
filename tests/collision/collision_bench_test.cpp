// Timing of the collision energy on the real sizes: the default T-shirt
// (~3.5k vertices) dressed on the mean parametric body (~6.5k vertices).
// Hidden (run with: build/tests/test_collision "[.bench]"); prints, asserts nothing on time.
#include "collision_test_util.hpp"

#include <drape/body.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/geometry/penetration.hpp>

#include <catch2/catch.hpp>

#include <chrono>
#include <random>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif
#include <iostream>

using namespace drape;
using namespace drape::test;

namespace {
int threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}
}  // namespace

TEST_CASE("collision timing: T-shirt on the parametric body", "[.bench][collision]") {
  const PluginDescriptor& bd = plugins().get("parametric");
  const auto model = plugins().create_body("parametric", Params(bd.params, {}, "parametric"));
  const Mesh body_mesh{model->vertices(model->mean_shape()), model->faces(), {}, {}};
  const PluginDescriptor& gd = plugins().get("tshirt");
  Garment garment = plugins().create_garment("tshirt", Params(gd.params, {}, "tshirt"))->build();
  const geometry::BodySurface body(body_mesh);
  dress(garment, body_mesh);
  const auto e = collision_energy("{}", garment, &body);
  // Two states: the dressed garment (1 cm clear of the body), and the same
  // garment pressed onto the skin, every vertex within 4 mm of its closest body
  // point on either side (most of them in contact: the solver's hard case).
  const Eigen::MatrixX3d dressed = garment.mesh.vertices;
  Eigen::MatrixX3d pressed = dressed;
  {
    const auto located = body.locate_all(dressed);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> offset(-0.004, 0.004);
    for (Eigen::Index v = 0; v < pressed.rows(); ++v)
      pressed.row(v) = (located[v].point + offset(rng) * located[v].normal).transpose();
  }

  using clock = std::chrono::steady_clock;
  const auto ms = [](clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  std::cout << "collision: " << dressed.rows() << " garment vertices, " << body_mesh.num_vertices()
            << " body vertices, " << threads() << " OpenMP threads\n";
  for (const auto& [name, x] : {std::pair<std::string, const Eigen::MatrixX3d&>{"dressed", dressed}, {"pressed", pressed}}) {
    const int repeats = 20;
    double t_value = 0, t_gradient = 0, t_hessian = 0, energy = 0;
    Triplets h;
    for (int r = 0; r < repeats; ++r) {
      auto t0 = clock::now();
      energy = e->value(x);
      auto t1 = clock::now();
      Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
      e->add_gradient(x, g);
      auto t2 = clock::now();
      h.clear();
      e->add_hessian(x, h, true);
      auto t3 = clock::now();
      t_value += ms(t1 - t0), t_gradient += ms(t2 - t1), t_hessian += ms(t3 - t2);
    }
    const Eigen::VectorXd d = body.signed_distances(x);
    std::cout << "  " << name << ": " << (d.array() < 0.003).count() << " vertices within the 3 mm margin, p = "
              << geometry::penetration_ratio(body, x) << ", E = " << energy << " J; value " << t_value / repeats
              << " ms, gradient " << t_gradient / repeats << " ms, hessian " << t_hessian / repeats
              << " ms, all three " << (t_value + t_gradient + t_hessian) / repeats << " ms\n";
    CHECK(h.size() == 9 * static_cast<std::size_t>(x.rows()));
  }
}
