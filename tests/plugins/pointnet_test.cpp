#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("pointnet loads as an encoder: defaults give 128 channels, concatenated per vertex", "[pointnet]") {
  const PluginDescriptor& d = plugins().get("pointnet");
  CHECK(d.kind == "encoder");
  CHECK(d.file.find("libdrape_plugin_pointnet") != std::string::npos);
  auto node = make_node("pointnet");
  const ShapeMap out = node->setup({{"body", {50, 3}}}, {});
  CHECK(out.at("features") == Shape{50, 256});
  CHECK(out.at("global") == Shape{1, 128});
  CHECK(node->weights().at("mlp_w0").value.shape() == Shape{3, 64});
  CHECK(node->weights().at("mlp_w1").value.shape() == Shape{64, 128});
  CHECK(node->flops_per_sample() == Approx(50.0 * (3 * 64 + 64 * 128)));
  auto plain = make_node("pointnet", "{concat_global: false}");
  CHECK(plain->setup({{"body", {50, 3}}}, {}).at("features") == Shape{50, 128});
}

TEST_CASE("pointnet rejects bad parameters", "[pointnet]") {
  CHECK_THROWS_AS(make_node("pointnet", "{widths: [64, -1]}"), ConfigError);
  CHECK_THROWS_WITH(make_node("pointnet", "{widths: []}"), Catch::Contains("widths"));
  CHECK_THROWS_AS(make_node("pointnet", "{concat_global: maybe}"), ConfigError);
  CHECK_THROWS_WITH(make_node("pointnet", "{width: 64}"), Catch::Contains("widths"));
  CHECK_THROWS_AS(make_node("pointnet")->setup({{"body", {10, 4}}}, {}), ConfigError);
}

TEST_CASE("pointnet applies the shared layer to every vertex and max-pools", "[pointnet]") {
  auto node = make_node("pointnet", "{widths: [2], activation: none}");
  const float wv[3][2] = {{1, 0}, {2, -1}, {0, 3}};
  const float bv[2] = {1, -2};
  Tensor body(1, 4, 3);
  const float xv[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  for (int v = 0; v < 4; ++v)
    for (int k = 0; k < 3; ++k) body(0, v, k) = xv[v][k];
  const auto out = run_forward(*node, {{"body", body}}, {}, [&](Node& n) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 2; ++c) n.weights().at("mlp_w0").value(0, r, c) = wv[r][c];
    for (int c = 0; c < 2; ++c) n.weights().at("mlp_b0").value(0, 0, c) = bv[c];
  });
  // h = x W + b: [2, -2], [3, -3], [1, 1], [4, 0]; max = [4, 1].
  const float h[4][2] = {{2, -2}, {3, -3}, {1, 1}, {4, 0}};
  for (int v = 0; v < 4; ++v) {
    CHECK(out.at("features")(0, v, 0) == Approx(h[v][0]));
    CHECK(out.at("features")(0, v, 1) == Approx(h[v][1]));
    CHECK(out.at("features")(0, v, 2) == Approx(4.0f));
    CHECK(out.at("features")(0, v, 3) == Approx(1.0f));
  }
  CHECK(out.at("global")(0, 0, 0) == Approx(4.0f));
  CHECK(out.at("global")(0, 0, 1) == Approx(1.0f));
}

TEST_CASE("pointnet backward matches finite differences", "[pointnet][gradcheck]") {
  const std::pair<const char*, bool> configs[] = {{"{widths: [16, 5]}", true},
                                                   {"{widths: [4, 7], activation: leaky_relu, concat_global: false}", true},
                                                   {"{widths: [5, 4], activation: tanh}", false}};
  for (const auto& [params, piecewise_linear] : configs) {
    INFO(params);
    auto node = make_node("pointnet", params);
    const GradCheckReport r = check_node_gradients(*node, {{"body", random_tensor(3, 17, 3, 8)}}, {"enc", 3},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 1 + node->weights().size());
    CHECK(r.ok(1e-2));
  }
}
