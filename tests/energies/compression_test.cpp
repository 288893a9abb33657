// The stretching energy's `compressive_stiffness` (plugins/energies/stretching/compression.hpp):
// compressive principal strains shortened at a fraction of the material's
// stiffness, tension exactly the material's; exact derivatives through the map.
#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>
#include <drape/materials/materials.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "../../plugins/energies/stretching/compression.hpp"
#include "energy_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// The unit grid turned by `degrees` in its plane and scaled by (a, b) along
// the turned axes: a principal strain along a direction that is neither u nor v.
Eigen::MatrixX3d scaled_along(const Eigen::MatrixX3d& x, double degrees, double a, double b) {
  const double t = degrees * std::numbers::pi / 180.0;
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  r.topLeftCorner<2, 2>() << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  const Eigen::Matrix3d s = Eigen::Vector3d(a, b, 1.0).asDiagonal();
  return (x * (r * s * r.transpose()).transpose()).eval();
}

}  // namespace

TEST_CASE("the compression map: identity in tension, a scaled compression, smooth in between", "[stretching]") {
  const membrane::CompressionMap map(0.04);  // c = 0.2
  // Tension both ways (and no map at all when s = 1): untouched, not even rounded.
  CHECK_FALSE(map.compressed(Eigen::Vector3d(0.01, 0.02, 0.005)));
  CHECK_FALSE(membrane::CompressionMap(1.0).compressed(Eigen::Vector3d(-0.1, -0.1, 0.0)));
  // Uniaxial compression along u past the blend: f(l) = c l - (1 - c) delta / 2.
  const double delta = membrane::CompressionMap::kBlend;
  const auto g = map.apply(std::array<double, 3>{-0.05, 0.01, 0.0});
  CHECK(g[0] == Approx(0.2 * -0.05 - 0.8 * delta / 2).epsilon(1e-12));
  CHECK(g[1] == Approx(0.01).epsilon(1e-12));
  CHECK(g[2] == Approx(0.0).margin(1e-15));
  // The same strain turned by 30 degrees is mapped to the same strain turned (rotation invariance).
  const double t = std::numbers::pi / 6, c = std::cos(t), s = std::sin(t);
  const double l1 = -0.05, l2 = 0.01;
  const auto turned = map.apply(std::array<double, 3>{c * c * l1 + s * s * l2, s * s * l1 + c * c * l2, c * s * (l1 - l2)});
  CHECK(turned[0] == Approx(c * c * g[0] + s * s * g[1]).epsilon(1e-10));
  CHECK(turned[2] == Approx(c * s * (g[0] - g[1])).epsilon(1e-10));
  // f is C2 across the blend's ends and 0.
  for (double x : {-delta, 0.0})
    for (int order = 0; order <= 2; ++order)
      CHECK(map.f(x - 1e-12, order) == Approx(map.f(x + 1e-12, order)).margin(1e-5));
  // Near-isotropic strains (r below kIsotropic) take the Taylor branch: it meets the exact one.
  const auto a = map.apply(std::array<double, 3>{-1e-3, -1e-3 + 4e-8, 0.0});
  const auto b = map.apply(std::array<double, 3>{-1e-3, -1e-3 + 1e-8, 0.0});
  CHECK(a[0] == Approx(b[0]).epsilon(1e-7));
  // The map's Dual derivatives against differences of its values, in both branches and in the blend.
  for (const std::array<double, 3>& g0 : {std::array<double, 3>{-0.0013, 0.004, 0.0021}, std::array<double, 3>{-0.03, -0.01, 0.02},
                                           std::array<double, 3>{-0.0007, -0.0007 + 5e-9, 1e-9}}) {
    using D = Dual<3, 2>;
    const auto out = map.apply(std::array<D, 3>{D::variable(g0[0], 0), D::variable(g0[1], 1), D::variable(g0[2], 2)});
    for (int i = 0; i < 3; ++i) {
      auto at = [&](int k, double step) {
        std::array<double, 3> p = g0;
        p[static_cast<std::size_t>(k)] += step;
        return map.apply(p)[static_cast<std::size_t>(i)];
      };
      for (int k = 0; k < 3; ++k) {
        const double h = 1e-7, fd = (at(k, h) - at(k, -h)) / (2 * h);
        INFO("component " << i << ", d/dg" << k << " at (" << g0[0] << ", " << g0[1] << ", " << g0[2] << ")");
        CHECK(out[static_cast<std::size_t>(i)].g[k] == Approx(fd).margin(1e-6));
      }
    }
  }
}

TEST_CASE("stretching with compressive_stiffness: tension as before, compression at s times the stiffness",
          "[stretching][arcsim]") {
  auto garment = grid_garment(4, 0.1);
  garment->materials[0] = arcsim_knit();
  const auto plain = bound_energy("stretching", "{}", *garment);
  const auto soft = bound_energy("stretching", "{compressive_stiffness: 0.04}", *garment);
  CHECK(params_for("stretching", "{}").get_float("compressive_stiffness") == 1.0);
  CHECK_THROWS_AS(params_for("stretching", "{compressive_stiffness: 0}"), ConfigError);
  // Stretched 4 % along u and 2 % along v, turned: bit for bit the same.
  const Eigen::MatrixX3d taut = scaled_along(garment->mesh.vertices, 25.0, 1.04, 1.02);
  CHECK(soft->value(taut) == plain->value(taut));
  CHECK(gradient_of(*soft, taut) == gradient_of(*plain, taut));
  // Compressed 3 % along a direction 25 degrees from u, unstrained across: the
  // face shortens against about s of the stiffness (the blend adds a little).
  const Eigen::MatrixX3d squeezed = scaled_along(garment->mesh.vertices, 25.0, 0.97, 1.0);
  const double ratio = soft->value(squeezed) / plain->value(squeezed);
  CHECK(ratio > 0.04);
  CHECK(ratio < 0.06);
}

TEST_CASE("stretching's derivatives with compressive_stiffness match finite differences", "[stretching][gradcheck]") {
  for (bool arcsim : {false, true}) {
    const auto garment = two_material_grid(5, 0.1);
    if (arcsim) garment->materials[0] = arcsim_knit();
    const auto e = bound_energy("stretching", "{compressive_stiffness: 0.05}", *garment);
    Eigen::MatrixX3d x = garment->mesh.vertices;
    x.col(0) *= 0.985;  // compressed 1.5 % along u: every face in or near the blend
    for (double amount : {0.002, 0.02}) {
      const Eigen::MatrixX3d y = perturbed(x, amount, 23);
      const GradCheckReport r = check_energy_derivatives(*e, y, {1e-8, 64, 7});
      INFO((arcsim ? "ArcSim knit" : "linear") << ", perturbation " << amount << "\n" << r.str());
      CHECK(r.ok(1e-5));
    }
  }
}
