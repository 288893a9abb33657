#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// A single triangle (0, 1, 2): three edges.
std::shared_ptr<Garment> triangle() {
  auto g = std::make_shared<Garment>();
  g->mesh.vertices = Eigen::MatrixX3d::Zero(3, 3);
  g->mesh.faces.resize(1, 3);
  g->mesh.faces << 0, 1, 2;
  g->materials.emplace_back();
  return g;
}

Tensor positions(std::initializer_list<std::initializer_list<float>> rows) {
  Tensor t(1, static_cast<int>(rows.size()), 3);
  int r = 0;
  for (const auto& row : rows) {
    int c = 0;
    for (float v : row) t(0, r, c++) = v;
    ++r;
  }
  return t;
}

}  // namespace

TEST_CASE("edge loads as a loss and needs a bound garment", "[edge]") {
  const PluginDescriptor& d = plugins().get("edge");
  CHECK(d.kind == "loss");
  CHECK(d.file.find("libdrape_plugin_edge") != std::string::npos);
  auto node = make_node("edge");
  CHECK_THROWS_WITH(node->setup({{"pred", {3, 3}}, {"target", {3, 3}}}, {}), Catch::Contains("no garment template"));
  const Assets no_garment;
  CHECK_THROWS_AS(node->setup({{"pred", {3, 3}}, {"target", {3, 3}}}, {"e", 0, &no_garment}), ConfigError);
  const Assets assets = assets_with(triangle());
  CHECK_THROWS_WITH(node->setup({{"pred", {4, 3}}, {"target", {4, 3}}}, {"e", 0, &assets}), Catch::Contains("[3, 3]"));
  CHECK_THROWS_AS(node->setup({{"pred", {3, 3}}, {"target", {3, 2}}}, {"e", 0, &assets}), ConfigError);
  CHECK(node->setup({{"pred", {3, 3}}, {"target", {3, 3}}}, {"e", 0, &assets}).at("loss") == Shape{1, 1});
  CHECK_THROWS_WITH(make_node("edge", "{weight: 1}"), Catch::Contains("no parameters"));
}

TEST_CASE("edge is the mean relative edge-length error", "[edge]") {
  const Assets assets = assets_with(triangle());
  auto node = make_node("edge");
  // Target edges: |01| = 1, |12| = sqrt(2), |02| = 1. Prediction: |01| = 2, |12| = sqrt(2), |02| = 0.5.
  const Tensor target = positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const Tensor pred = positions({{0, 0, 0}, {2, 0, 0}, {0, 0.5f, 0}});
  // |12| predicted: from (2,0,0) to (0,0.5,0) = sqrt(4.25).
  const double expected = (1.0 + std::abs(std::sqrt(4.25) - std::sqrt(2.0)) / std::sqrt(2.0) + 0.5) / 3.0;
  const auto out = run_forward(*node, {{"pred", pred}, {"target", target}}, {"e", 0, &assets});
  CHECK(out.at("loss")(0, 0, 0) == Approx(expected).epsilon(1e-6));

  // On a grid, a uniform scale s changes every edge by |s - 1|; a translation by nothing.
  const auto grid = grid_garment(4, 0.1);
  const Assets grid_assets = assets_with(grid);
  Tensor t(2, 16, 3), p(2, 16, 3);
  for (int b = 0; b < 2; ++b)
    for (int v = 0; v < 16; ++v)
      for (int k = 0; k < 3; ++k) {
        t(b, v, k) = static_cast<float>(grid->mesh.vertices(v, k));
        p(b, v, k) = b == 0 ? 1.3f * t(b, v, k) : t(b, v, k) + 0.7f;
      }
  auto grid_node = make_node("edge");
  const auto grid_out = run_forward(*grid_node, {{"pred", p}, {"target", t}}, {"e", 0, &grid_assets});
  CHECK(grid_out.at("loss")(0, 0, 0) == Approx(0.3).epsilon(1e-5));
  CHECK(grid_out.at("loss")(1, 0, 0) == Approx(0.0).margin(1e-5));
  CHECK(grid_node->flops_per_sample() == Approx(20.0 * 33));  // 3*4 horizontal + 3*4 vertical + 9 diagonal edges
}

TEST_CASE("edge backward matches finite differences for pred and target", "[edge][gradcheck]") {
  const auto grid = grid_garment(4, 0.1);
  const Assets assets = assets_with(grid);
  Tensor target(2, 16, 3), pred(2, 16, 3);
  const Tensor noise_t = random_tensor(2, 16, 3, 13, 0.02f), noise_p = random_tensor(2, 16, 3, 14, 0.03f);
  for (int b = 0; b < 2; ++b)
    for (int v = 0; v < 16; ++v)
      for (int k = 0; k < 3; ++k) {
        target(b, v, k) = static_cast<float>(grid->mesh.vertices(v, k)) + noise_t(b, v, k);
        pred(b, v, k) = target(b, v, k) + noise_p(b, v, k);
      }
  auto node = make_node("edge");
  GradCheckOptions options;
  options.step = 1e-4;  // edges are 0.1 m long; the kink of |lx - ly| must stay out of reach
  const GradCheckReport r = check_node_gradients(*node, {{"pred", pred}, {"target", target}}, {"e", 0, &assets}, options);
  INFO(r.str());
  CHECK(r.entries.size() == 2);
  CHECK(r.ok(1e-2));
}
