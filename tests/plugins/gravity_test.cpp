#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

std::unique_ptr<Energy> gravity(const std::string& yaml, const Garment& garment) {
  auto e = plugins().create_energy("gravity", params_for("gravity", yaml));
  EnergyContext ctx;
  ctx.garment = &garment;
  e->bind(ctx);
  return e;
}

}  // namespace

TEST_CASE("gravity loads as an energy with g = 9.81 by default and checks g", "[gravity]") {
  const PluginDescriptor& d = plugins().get("gravity");
  CHECK(d.kind == "energy");
  CHECK(d.file.find("libdrape_plugin_gravity") != std::string::npos);
  CHECK(params_for("gravity", "{}").get_float("g") == 9.81);
  CHECK_THROWS_WITH(params_for("gravity", "{g: -1}"), Catch::Contains("'g'"));
  CHECK_THROWS_AS(params_for("gravity", "{g: heavy}"), ConfigError);
}

TEST_CASE("gravity lumps face masses to corners and sums m g y", "[gravity]") {
  // One unit quad: face (0, 1, 3) is knit (0.187 kg/m^2), face (0, 3, 2) is print (0.5 kg/m^2).
  const auto garment = grid_garment(2, 1.0, true);
  const auto e = gravity("{}", *garment);
  const double knit = 0.187 * 0.5 / 3, print = 0.5 * 0.5 / 3;
  const double mass[4] = {knit + print, knit, print, knit + print};
  Eigen::MatrixX3d x(4, 3);
  x << 0.3, 1.0, 7.0,  //
      -2.0, 0.5, 1.0,  //
      5.0, -0.25, 0.0,  //
      1.0, 2.0, -3.0;
  double expected = 0.0;
  for (int v = 0; v < 4; ++v) expected += mass[v] * 9.81 * x(v, 1);
  CHECK(e->value(x) == Approx(expected).epsilon(1e-12));
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Ones(4, 3);
  CHECK(e->add_gradient(x, g) == Approx(expected).epsilon(1e-12));
  for (int v = 0; v < 4; ++v) {
    CHECK(g(v, 0) == 1.0);
    CHECK(g(v, 1) == Approx(1.0 + mass[v] * 9.81).epsilon(1e-12));
    CHECK(g(v, 2) == 1.0);
  }
  Triplets h;
  e->add_hessian(x, h, true);
  CHECK(h.empty());
  // The magnitude is the parameter's: on the moon the energy scales by 1.62 / 9.81.
  CHECK(gravity("{g: 1.62}", *garment)->value(x) == Approx(expected * 1.62 / 9.81).epsilon(1e-12));
}

TEST_CASE("gravity's total mass is the material-space area times the density", "[gravity]") {
  const auto garment = grid_garment(4, 0.1, true);  // 0.3 m x 0.3 m, half the faces knit, half print
  const auto e = gravity("{}", *garment);
  Eigen::MatrixX3d lifted = garment->mesh.vertices;
  const double e0 = e->value(lifted);
  lifted.col(1).array() += 2.0;
  CHECK(e->value(lifted) - e0 == Approx(0.09 * (0.187 + 0.5) / 2 * 9.81 * 2.0).epsilon(1e-12));
}

TEST_CASE("gravity derivatives match finite differences", "[gravity][gradcheck]") {
  const auto garment = grid_garment(4, 0.1, true);
  const auto e = gravity("{}", *garment);
  Eigen::MatrixX3d x = garment->mesh.vertices + 0.05 * Eigen::MatrixX3d::Random(16, 3);
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.entries.size() == 4);
  CHECK(r.ok(1e-6));
}

TEST_CASE("gravity needs material-space UVs", "[gravity]") {
  auto garment = grid_garment(3, 0.1);
  garment->mesh.uv.resize(0, 2);
  garment->mesh.uv_faces.resize(0, 3);
  CHECK_THROWS_WITH(gravity("{}", *garment), Catch::Contains("UV"));
}

TEST_CASE("gravity works as a graph loss node on float positions", "[gravity][gradcheck]") {
  const auto garment = grid_garment(4, 0.1, true);
  const Assets assets = assets_with(garment);
  auto node = make_node("gravity");
  Tensor x = random_tensor(2, 16, 3, 3, 0.5f);
  const auto out = run_forward(*node, {{"x", x}}, {"g", 0, &assets});
  const auto e = gravity("{}", *garment);
  for (int b = 0; b < 2; ++b) CHECK(out.at("energy")(b, 0, 0) == Approx(e->value(x.mat(b).cast<double>())).epsilon(1e-5));
  const GradCheckReport r = check_node_gradients(*node, {{"x", x}}, {"g", 0, &assets});
  INFO(r.str());
  CHECK(r.ok(1e-2));
}
