#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("cnn1d loads from its plugin library as an encoder", "[cnn1d]") {
  const PluginDescriptor& d = plugins().get("cnn1d");
  CHECK(d.kind == "encoder");
  CHECK(d.file.find("libdrape_plugin_cnn1d") != std::string::npos);
}

TEST_CASE("cnn1d defaults: three strided layers of 32, 64, 128 channels, kernel 5", "[cnn1d]") {
  auto node = make_node("cnn1d");
  const ShapeMap out = node->setup({{"body", {100, 3}}}, {});
  CHECK(out.at("features") == Shape{100, 128});
  CHECK(out.at("global") == Shape{1, 128});
  REQUIRE(node->weights().size() == 6);
  CHECK(node->weights().at("conv0_w").value.shape() == Shape{5 * 3, 32});
  CHECK(node->weights().at("conv1_w").value.shape() == Shape{5 * 32, 64});
  CHECK(node->weights().at("conv2_w").value.shape() == Shape{5 * 64, 128});
  // Rows 100 -> 50 -> 25 -> 13; multiply-adds of each layer: rows * kernel*Cin * Cout.
  CHECK(node->flops_per_sample() == Approx(50.0 * 15 * 32 + 25.0 * 160 * 64 + 13.0 * 320 * 128));
}

TEST_CASE("cnn1d rejects bad parameters and inputs", "[cnn1d]") {
  CHECK_THROWS_AS(make_node("cnn1d", "{kernel: 0}"), ConfigError);
  CHECK_THROWS_AS(make_node("cnn1d", "{stride: 0}"), ConfigError);
  CHECK_THROWS_AS(make_node("cnn1d", "{channels: [32, 0]}"), ConfigError);
  CHECK_THROWS_WITH(make_node("cnn1d", "{channels: []}"), Catch::Contains("channels"));
  CHECK_THROWS_WITH(make_node("cnn1d", "{activation: leaky}"), Catch::Contains("leaky_relu"));
  CHECK_THROWS_AS(make_node("cnn1d", "{negative_slope: 1.5}"), ConfigError);
  auto node = make_node("cnn1d");
  CHECK_THROWS_WITH(node->setup({{"body", {10, 2}}}, {}), Catch::Contains("[vertices, 3]"));
}

TEST_CASE("cnn1d computes a strided convolution, nearest upsampling and the mean", "[cnn1d]") {
  auto node = make_node("cnn1d", "{channels: [2], kernel: 3, stride: 2, activation: leaky_relu, negative_slope: 0.25}");
  float w[9][2];
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 2; ++c) w[r][c] = 0.1f * float(r + 1) * (c == 0 ? 1.0f : -1.0f);
  const float bias[2] = {0.5f, -0.25f};
  const Tensor body = random_tensor(2, 5, 3, 11);
  const auto out = run_forward(*node, {{"body", body}}, {}, [&](Node& n) {
    for (int r = 0; r < 9; ++r)
      for (int c = 0; c < 2; ++c) n.weights().at("conv0_w").value(0, r, c) = w[r][c];  // row j*3 + k: tap j, channel k
    for (int c = 0; c < 2; ++c) n.weights().at("conv0_b").value(0, 0, c) = bias[c];
  });
  // Output row o is centred on input row 2o: taps at rows 2o-1, 2o, 2o+1, zero outside.
  int negative = 0;
  for (int b = 0; b < 2; ++b) {
    float expected[3][2];
    for (int o = 0; o < 3; ++o)
      for (int c = 0; c < 2; ++c) {
        float z = bias[c];
        for (int j = 0; j < 3; ++j) {
          const int r = 2 * o - 1 + j;
          if (r < 0 || r >= 5) continue;
          for (int k = 0; k < 3; ++k) z += w[j * 3 + k][c] * body(b, r, k);
        }
        expected[o][c] = z > 0 ? z : 0.25f * z;
        negative += z < 0;
      }
    // Vertex v takes the row centred nearest to it: 0->0, 1->1 (tie up), 2->1, 3->2, 4->2.
    const int nearest[5] = {0, 1, 1, 2, 2};
    for (int v = 0; v < 5; ++v)
      for (int c = 0; c < 2; ++c) CHECK(out.at("features")(b, v, c) == Approx(expected[nearest[v]][c]).margin(1e-6));
    for (int c = 0; c < 2; ++c)
      CHECK(out.at("global")(b, 0, c) ==
            Approx((expected[0][c] + expected[1][c] + expected[2][c]) / 3.0f).margin(1e-6));
  }
  CHECK(negative > 0);  // the leaky branch was exercised
  CHECK(negative < 12);
}

TEST_CASE("cnn1d backward matches finite differences for the body and every weight", "[cnn1d][gradcheck]") {
  const std::pair<const char*, bool> configs[] = {{"{channels: [4, 6], kernel: 3, stride: 2}", true},
                                                   {"{channels: [3, 5, 4], kernel: 5, stride: 3, activation: tanh}", false},
                                                   {"{channels: [4], kernel: 4, stride: 1}", true}};
  for (const auto& [params, piecewise_linear] : configs) {
    INFO(params);
    auto node = make_node("cnn1d", params);
    const GradCheckReport r = check_node_gradients(*node, {{"body", random_tensor(2, 23, 3, 5)}}, {"enc", 42},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 1 + node->weights().size());
    CHECK(r.ok(1e-2));
  }
}

TEST_CASE("cnn1d weights follow the node seed", "[cnn1d]") {
  auto a = make_node("cnn1d", "{channels: [8]}"), b = make_node("cnn1d", "{channels: [8]}"),
       c = make_node("cnn1d", "{channels: [8]}");
  a->setup({{"body", {20, 3}}}, {"a", 1});
  b->setup({{"body", {20, 3}}}, {"b", 1});
  c->setup({{"body", {20, 3}}}, {"c", 2});
  const auto& wa = a->weights().at("conv0_w").value;
  CHECK(wa.vec() == b->weights().at("conv0_w").value.vec());
  CHECK(wa.vec() != c->weights().at("conv0_w").value.vec());
  // He initialisation for leaky_relu(0.2): std = sqrt(2 / (1.04 * fan_in)), fan_in = 15.
  const double var = wa.vec().squaredNorm() / double(wa.size());
  CHECK(std::sqrt(var) == Approx(std::sqrt(2.0 / (1.04 * 15))).epsilon(0.35));
}
