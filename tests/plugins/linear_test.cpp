#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("linear loads as an op and maps [R, Cin] to [R, width]", "[linear]") {
  const PluginDescriptor& d = plugins().get("linear");
  CHECK(d.kind == "op");
  CHECK(d.file.find("libdrape_plugin_linear") != std::string::npos);
  auto node = make_node("linear");
  CHECK(node->setup({{"x", {9, 5}}}, {}).at("out") == Shape{9, 64});
  CHECK(node->weights().at("w0").value.shape() == Shape{5, 64});
  CHECK(node->weights().at("b0").value.shape() == Shape{1, 64});
  CHECK(node->flops_per_sample() == Approx(9.0 * 5 * 64));
  CHECK_THROWS_AS(make_node("linear", "{width: 0}"), ConfigError);
  CHECK_THROWS_AS(make_node("linear", "{activation: elu}"), ConfigError);
  CHECK_THROWS_AS(make_node("linear", "{negative_slope: -0.1}"), ConfigError);
}

TEST_CASE("linear computes x w + b per row, then the activation", "[linear]") {
  auto node = make_node("linear", "{width: 2, activation: relu}");
  Tensor x(1, 3, 2);
  const float xv[3][2] = {{1, 1}, {-2, 0}, {0.5f, -1}};
  for (int r = 0; r < 3; ++r) x(0, r, 0) = xv[r][0], x(0, r, 1) = xv[r][1];
  const auto out = run_forward(*node, {{"x", x}}, {}, [](Node& n) {
    Tensor& w = n.weights().at("w0").value;
    Tensor& b = n.weights().at("b0").value;
    w(0, 0, 0) = 1.0f, w(0, 0, 1) = -1.0f, w(0, 1, 0) = 2.0f, w(0, 1, 1) = 0.5f;
    b(0, 0, 0) = -1.0f, b(0, 0, 1) = 0.25f;
  });
  for (int r = 0; r < 3; ++r) {
    const float z0 = xv[r][0] * 1.0f + xv[r][1] * 2.0f - 1.0f;
    const float z1 = xv[r][0] * -1.0f + xv[r][1] * 0.5f + 0.25f;
    CHECK(out.at("out")(0, r, 0) == Approx(std::max(z0, 0.0f)));
    CHECK(out.at("out")(0, r, 1) == Approx(std::max(z1, 0.0f)));
  }
}

TEST_CASE("linear backward matches finite differences", "[linear][gradcheck]") {
  const std::pair<const char*, bool> configs[] = {{"{width: 6}", false},
                                                   {"{width: 4, activation: tanh}", false},
                                                   {"{width: 5, activation: leaky_relu}", true},
                                                   {"{width: 5, activation: relu}", true}};
  for (const auto& [params, piecewise_linear] : configs) {
    INFO(params);
    auto node = make_node("linear", params);
    const GradCheckReport r = check_node_gradients(*node, {{"x", random_tensor(2, 7, 3, 42)}}, {"t", 5},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 3);
    CHECK(r.ok(1e-2));
  }
}

TEST_CASE("linear with init: zero starts as nothing and still learns", "[linear]") {
  auto node = make_node("linear", "{width: 3, init: zero}");
  const Tensor x = random_tensor(2, 4, 5, 3);
  const Tensor y = run_forward(*node, {{"x", x}}, {}).at("out");
  for (std::size_t i = 0; i < y.size(); ++i) CHECK(y.data()[i] == 0.0f);
  // Its gradient reaches the weights (x^T g for w, the sum of g for b).
  const GradCheckReport r = check_node_gradients(*node, {{"x", x}}, {"t", 5});
  INFO(r.str());
  CHECK(r.ok(1e-2));
  CHECK_THROWS_AS(make_node("linear", "{init: ones}"), ConfigError);
}
