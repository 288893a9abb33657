// The collision energy's plugin, parameters, binding errors and values against
// hand computation: zero outside the margin, k * area * (margin - d)^3 / 3 inside.
#include "collision_test_util.hpp"

#include <drape/energy_node.hpp>

#include <catch2/catch.hpp>

using namespace drape;
using namespace drape::test;

TEST_CASE("collision loads as an energy with documented defaults and checks its parameters", "[collision]") {
  const PluginDescriptor& d = plugins().get("collision");
  CHECK(d.kind == "energy");
  CHECK(d.file.find("libdrape_plugin_collision") != std::string::npos);
  const Params p = params_for("collision", "{}");
  CHECK(p.get_float("stiffness") == 1e7);
  CHECK(p.get_float("margin") == 0.003);
  CHECK(p.get_float("max_depth") == 0.0);
  CHECK_THROWS_WITH(params_for("collision", "{stiffness: -1}"), Catch::Contains("'stiffness'"));
  CHECK_THROWS_WITH(params_for("collision", "{margin: -0.001}"), Catch::Contains("'margin'"));
  CHECK_THROWS_WITH(params_for("collision", "{max_depth: -1}"), Catch::Contains("'max_depth'"));
  CHECK_THROWS_AS(params_for("collision", "{margn: 0.01}"), ConfigError);
}

TEST_CASE("collision refuses to bind without a body or without material-space UVs", "[collision]") {
  const auto garment = grid_garment(3, 0.1);
  const geometry::BodySurface body = sphere_body(1, 1.0);
  const std::string no_body = message_of([&] { collision_energy("{}", *garment, nullptr); });
  CHECK_THAT(no_body, Catch::Contains("collision") && Catch::Contains("no body"));
  CHECK_THROWS_AS(collision_energy("{}", *garment, nullptr), ConfigError);

  auto flat = *garment;
  flat.mesh.uv.resize(0, 2);
  flat.mesh.uv_faces.resize(0, 3);
  CHECK_THROWS_AS(collision_energy("{}", flat, &body), ConfigError);
  CHECK_THAT(message_of([&] { collision_energy("{}", flat, &body); }), Catch::Contains("collision") && Catch::Contains("UV"));

  auto unbound = plugins().create_energy("collision", params_for("collision", "{}"));
  CHECK_THAT(message_of([&] { unbound->value(garment->mesh.vertices); }), Catch::Contains("bind"));
}

TEST_CASE("collision rejects positions of the wrong size or not finite", "[collision]") {
  const auto garment = grid_garment(3, 0.1);
  const geometry::BodySurface body = sphere_body(1, 1.0);
  const auto e = collision_energy("{}", *garment, &body);
  CHECK_THAT(message_of([&] { e->value(Eigen::MatrixX3d::Zero(4, 3)); }), Catch::Contains("4 vertices given"));
  Eigen::MatrixX3d x = garment->mesh.vertices;
  x(5, 1) = std::nan("");
  CHECK_THAT(message_of([&] { e->value(x); }), Catch::Contains("vertex 5"));
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(9, 3);
  Triplets h;
  CHECK_THROWS_AS(e->add_gradient(x, g), Error);
  CHECK_THROWS_AS(e->add_hessian(x, h), Error);
}

TEST_CASE("collision energy is k * area * (margin - d)^3 / 3 with force k * area * (margin - d)^2 along the normal",
          "[collision]") {
  // Unit quad of two faces (0, 1, 3), (0, 3, 2), spacing 0.1: corners 0 and 3
  // are on both faces (area 2 * 0.005 / 3), corners 1 and 2 on one (0.005 / 3).
  const auto garment = grid_garment(2, 0.1);
  const double area[4] = {0.01 / 3, 0.005 / 3, 0.005 / 3, 0.01 / 3};
  // A coarse unit sphere: faces are large, so a point a few cm off a face's
  // centroid along its normal has that centroid as its closest point.
  const geometry::BodySurface body = sphere_body(2, 1.0);
  const Eigen::Vector3d centroid(1.0 / 3, 1.0 / 3, 1.0 / 3);
  const double k = 2e6, margin = 0.004;
  // Beyond the margin, inside the margin, just inside the body, 2 cm inside.
  const double distance[4] = {0.01, 0.001, -0.002, -0.02};
  const int face[4] = {3, 17, 40, 77};
  Eigen::MatrixX3d x(4, 3);
  for (int v = 0; v < 4; ++v) x.row(v) = off_face(body, face[v], centroid, distance[v]);
  for (int v = 0; v < 4; ++v) REQUIRE(body.locate(x.row(v).transpose()).signed_distance == Approx(distance[v]).margin(1e-12));

  const auto e = collision_energy("{stiffness: 2e6, margin: 0.004}", *garment, &body);
  double expected = 0;
  for (int v = 1; v < 4; ++v) expected += k * area[v] * std::pow(margin - distance[v], 3) / 3;
  CHECK(e->value(x) == Approx(expected).epsilon(1e-12));

  Eigen::MatrixX3d g = Eigen::MatrixX3d::Ones(4, 3);
  CHECK(e->add_gradient(x, g) == Approx(expected).epsilon(1e-12));
  CHECK(g.row(0) == Eigen::RowVector3d::Ones());  // beyond the margin: nothing added
  for (int v = 1; v < 4; ++v) {
    const Eigen::RowVector3d n = body.locate(x.row(v).transpose()).normal.transpose();
    const Eigen::RowVector3d force = k * area[v] * std::pow(margin - distance[v], 2) * n;
    CHECK((g.row(v) - Eigen::RowVector3d::Ones() + force).norm() <= 1e-12 * force.norm());
  }

  // In a face's interior the Hessian block is 2 k area (margin - d) n n^T, projected or not.
  for (bool project : {false, true}) {
    Triplets h;
    e->add_hessian(x, h, project);
    Eigen::SparseMatrix<double> hs(12, 12);
    hs.setFromTriplets(h.begin(), h.end());
    const Eigen::MatrixXd dense(hs);
    for (int v = 0; v < 4; ++v) {
      const Eigen::Vector3d n = body.locate(x.row(v).transpose()).normal;
      const Eigen::Matrix3d expected_block =
          v == 0 ? Eigen::Matrix3d::Zero() : Eigen::Matrix3d(2 * k * area[v] * (margin - distance[v]) * n * n.transpose());
      CHECK((dense.block<3, 3>(3 * v, 3 * v) - expected_block).norm() <= 1e-9 * (1 + expected_block.norm()));
    }
    for (int a = 0; a < 4; ++a)  // no coupling between vertices
      for (int b = 0; b < 4; ++b)
        if (a != b) CHECK(dense.block<3, 3>(3 * a, 3 * b).isZero(0.0));
  }
}

TEST_CASE("collision is zero, with a zero gradient, for a garment entirely beyond the margin", "[collision]") {
  const auto garment = grid_garment(5, 0.02);
  const geometry::BodySurface body = sphere_body(3, 0.2);
  const Eigen::MatrixX3d x = points_at_distances(body, Eigen::Vector3d::Zero(), 25, 0.0031, 0.05, 3);
  const auto e = collision_energy("{}", *garment, &body);
  CHECK(e->value(x) == 0.0);
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(25, 3);
  CHECK(e->add_gradient(x, g) == 0.0);
  CHECK(g.isZero(0.0));
  // One vertex moved into the margin makes the energy positive.
  Eigen::MatrixX3d closer = x;
  closer.row(7) = points_at_distances(body, Eigen::Vector3d::Zero(), 1, 0.001, 0.001, 9);
  CHECK(e->value(closer) > 0.0);
}

TEST_CASE("collision scales with the stiffness and follows the margin", "[collision]") {
  const auto garment = grid_garment(4, 0.03);
  const geometry::BodySurface body = sphere_body(3, 0.2);
  const Eigen::MatrixX3d x = points_at_distances(body, Eigen::Vector3d::Zero(), 16, -0.01, 0.004, 5);
  const double base = collision_energy("{}", *garment, &body)->value(x);
  REQUIRE(base > 0);
  CHECK(collision_energy("{stiffness: 3e9}", *garment, &body)->value(x) == Approx(base * 300).epsilon(1e-12));
  // A zero margin counts only the depth inside the body; a wider margin more.
  CHECK(collision_energy("{margin: 0}", *garment, &body)->value(x) < base);
  CHECK(collision_energy("{margin: 0.01}", *garment, &body)->value(x) > base);
}

TEST_CASE("collision through the EnergyNode adapter: a graph loss cannot bind a body yet, and says so", "[collision]") {
  // EnergyNode binds only the garment template (EnergyContext::body stays null),
  // so the collision energy cannot be a graph loss until the adapter can bind a body.
  const auto garment = grid_garment(3, 0.1);
  const Assets assets = assets_with(garment);
  auto node = make_node("collision");
  const std::string message = message_of([&] { node->setup({{"x", {9, 3}}}, {"collision", 0, &assets}); });
  CHECK_THAT(message, Catch::Contains("no body"));
  CHECK_THROWS_AS(node->setup({{"x", {9, 3}}}, {"collision", 0, &assets}), ConfigError);
}
