// Bending of a hinge whose wing collapses: the energy is faded out below 10 %
// of the wing's rest height (plugins/energies/bending/wing_fade.hpp) with exact
// derivatives, and stays bounded where theta's own derivatives grow like 1/h.
#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "../../plugins/energies/bending/dihedral_angle.hpp"
#include "energy_test_util.hpp"

using namespace drape;
using namespace drape::test;
namespace dh = drape::dihedral;

namespace {

constexpr double kFadeKnitBending = 1e-5;
constexpr double kFadeHeight = 0.1;  // 10 % of the unit rest heights below

// Edge x0 = (0,0,0) -> x1 = (1,0,0); wing 0's tip at height f0 over it, off the
// edge's midpoint and tilted by 0.2 rad; wing 1's tip at height f1, folded by
// 0.7 rad. Rest (UV) heights are 1, l = 1 and A0 + A1 = 1: E = k theta^2 / 8.
Eigen::MatrixX3d fade_hinge_positions(double f0, double f1 = 1.0) {
  Eigen::MatrixX3d x(4, 3);
  x << 0, 0, 0, 1, 0, 0, 0.3, f0 * std::cos(0.2), f0 * std::sin(0.2), 0.6, -f1 * std::cos(0.7), f1 * std::sin(0.7);
  return x;
}

Garment fade_hinge_garment() {
  Eigen::MatrixX3i f(2, 3);
  f << 0, 1, 2, 1, 0, 3;
  Eigen::MatrixX2d uv(4, 2);
  uv << 0, 0, 1, 0, 0.5, 1, 0.5, -1;
  return small_garment(fade_hinge_positions(1.0), f, uv);
}

// The same hinge with an ArcSim table: k_b depends on theta.
Garment tabulated_hinge_garment() {
  Garment g = fade_hinge_garment();
  g.materials[0].model = Material::Model::Arcsim;
  g.materials[0].arcsim.bending = {{{2e-5, 3e-5, 3.5e-5, 4e-5, 2.5e-5},
                                    {2.5e-5, 1.9e-5, 1.6e-5, 2.5e-5, 0.9e-5},
                                    {1.4e-5, 0.7e-5, 1.5e-5, 2.5e-5, 1.9e-5}}};
  return g;
}

dh::Hinge hinge_of(const Eigen::MatrixX3d& x) {
  return dh::Hinge(x.row(0).transpose(), x.row(1).transpose(), x.row(2).transpose(), x.row(3).transpose());
}

// dtheta/dx straight from the plugin's dihedral-angle helper: what the
// gradient of an unfaded hinge is made of.
dh::Vec12 angle_gradient(const Eigen::MatrixX3d& x) {
  const dh::Hinge h = hinge_of(x);
  return dh::gradient(dh::Wing(h.e, h.a0, h.n0, h.q0, h.e2), dh::Wing(h.e, h.a1, h.n1, h.q1, h.e2));
}

dh::Vec12 flat(const Eigen::MatrixX3d& g) {
  dh::Vec12 v;
  for (int k = 0; k < 12; ++k) v[k] = g(k / 3, k % 3);
  return v;
}

// The fade's C2 step, 10 r^3 - 15 r^4 + 6 r^5 (wing_fade.hpp), written out.
double smootherstep(double r) { return r >= 1.0 ? 1.0 : 10 * std::pow(r, 3) - 15 * std::pow(r, 4) + 6 * std::pow(r, 5); }

}  // namespace

TEST_CASE("bending fades out a collapsing wing with exact derivatives", "[bending][gradcheck]") {
  const Garment linear = fade_hinge_garment(), tabulated = tabulated_hinge_garment();
  for (const Garment* g : {&linear, &tabulated}) {
    for (const std::string projection : {"gauss_newton", "eigen"}) {
      const auto e = bound_energy("bending", "{projection: " + projection + "}", *g);
      // One wing at 5 % and 1 % of its rest height, and both wings inside the fade.
      for (const Eigen::MatrixX3d& x : {fade_hinge_positions(0.05), fade_hinge_positions(0.01), fade_hinge_positions(0.03, 0.06)}) {
        if (g == &linear) {
          const double theta = hinge_of(x).angle(), r0 = x(2, 1) / std::cos(0.2) / kFadeHeight;
          const double r1 = std::hypot(x(3, 1), x(3, 2)) / kFadeHeight;
          CHECK(e->value(x) == Approx(smootherstep(r0) * smootherstep(r1) * kFadeKnitBending * theta * theta / 8).epsilon(1e-12));
        }
        const GradCheckReport r = check_energy_derivatives(*e, x);
        INFO((g == &linear ? "linear" : "tabulated") << ", " << projection << ", wing 0 at " << x(2, 1) << "\n" << r.str());
        CHECK(r.ok(1e-5));
      }
    }
  }
}

TEST_CASE("bending of a wing at half its rest height is the unfaded energy, bit for bit", "[bending]") {
  const Garment g = fade_hinge_garment();
  const auto e = bound_energy("bending", "{}", g);
  const Eigen::MatrixX3d x = fade_hinge_positions(0.5);
  // The plugin's linear path: c d^2 with c = k l^2 / (8 (A0 + A1)), all exact here.
  const double c = kFadeKnitBending * 1.0 * 1.0 / (8.0 * 1.0), d = std::remainder(hinge_of(x).angle(), 2.0 * std::numbers::pi);
  CHECK(e->value(x) == c * d * d);
  const dh::Vec12 dtheta = angle_gradient(x);
  CHECK(flat(gradient_of(*e, x)) == (2.0 * c * d) * dtheta);
  const Eigen::MatrixXd gauss_newton = (2.0 * c) * dtheta * dtheta.transpose();
  CHECK(dense_hessian(*e, x, true) == gauss_newton);
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.ok(1e-5));

  // The fade joins the unfaded energy continuously, with a continuous gradient (C1).
  const Eigen::MatrixX3d below = fade_hinge_positions(kFadeHeight * (1 - 1e-7)), above = fade_hinge_positions(kFadeHeight * (1 + 1e-7));
  CHECK(e->value(below) == Approx(e->value(above)).epsilon(1e-6));
  CHECK((gradient_of(*e, below) - gradient_of(*e, above)).norm() < 1e-5 * gradient_of(*e, above).norm());
}

TEST_CASE("bending of a wing collapsing to zero height stays bounded where theta's derivatives blow up", "[bending]") {
  const Garment g = fade_hinge_garment();
  const auto gn = bound_energy("bending", "{}", g);
  const auto eigen = bound_energy("bending", "{projection: eigen}", g);
  // The scale of an unfaded hinge's derivatives: wing 0 at the edge of the fade.
  const Eigen::MatrixX3d edge_of_fade = fade_hinge_positions(kFadeHeight);
  const double gradient_scale = gradient_of(*gn, edge_of_fade).norm();
  const double hessian_scale = dense_hessian(*eigen, edge_of_fade, false).cwiseAbs().maxCoeff();
  REQUIRE(gradient_scale > 0.0);
  for (double f : {1e-6, 1e-9, 0.0}) {
    const Eigen::MatrixX3d x = fade_hinge_positions(f);
    const double theta = hinge_of(x).angle();
    INFO("wing 0 at " << f << " of its rest height, theta " << theta);
    const double value = gn->value(x);
    const Eigen::MatrixX3d grad = gradient_of(*gn, x);
    CHECK(std::isfinite(value));
    CHECK(value <= 3.0 * (f / kFadeHeight) * (f / kFadeHeight) * kFadeKnitBending * theta * theta / 8);
    CHECK(grad.allFinite());
    CHECK(grad.norm() <= gradient_scale);
    for (const auto* e : {gn.get(), eigen.get()})
      for (bool project : {false, true}) {
        const Eigen::MatrixXd h = dense_hessian(*e, x, project);
        CHECK(h.allFinite());
        CHECK(h.cwiseAbs().maxCoeff() <= 10.0 * hessian_scale);
      }
    if (f == 0.0) {
      CHECK(value == 0.0);
      CHECK(grad.isZero(0.0));
      continue;
    }
    // Unfaded, the force would be E' dtheta with |dtheta| ~ 1/h: a million
    // times the scale at 1e-6 of the height, so this test can fail.
    const double unfaded = kFadeKnitBending * std::abs(theta) / 4 * angle_gradient(x).norm();
    INFO("faded gradient " << grad.norm() << ", unfaded " << unfaded << ", scale " << gradient_scale);
    CHECK(unfaded > 1e3 * gradient_scale);
  }
}
