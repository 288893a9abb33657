#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("mlp loads as a decoder: rows default to the input's rows", "[mlp]") {
  const PluginDescriptor& d = plugins().get("mlp");
  CHECK(d.kind == "decoder");
  CHECK(d.file.find("libdrape_plugin_mlp") != std::string::npos);
  auto node = make_node("mlp");
  CHECK(node->setup({{"x", {10, 4}}}, {}).at("out") == Shape{10, 3});
  CHECK(node->weights().at("mlp_w0").value.shape() == Shape{40, 256});
  CHECK(node->weights().at("mlp_w1").value.shape() == Shape{256, 256});
  CHECK(node->weights().at("mlp_w2").value.shape() == Shape{256, 30});
  CHECK(node->flops_per_sample() == Approx(40.0 * 256 + 256.0 * 256 + 256.0 * 30));
  auto from_global = make_node("mlp", "{rows: 7, widths: [16]}");
  CHECK(from_global->setup({{"x", {1, 8}}}, {}).at("out") == Shape{7, 3});
}

TEST_CASE("mlp rejects bad parameters", "[mlp]") {
  CHECK_THROWS_WITH(make_node("mlp", "{rows: -1}"), Catch::Contains("rows"));
  CHECK_THROWS_AS(make_node("mlp", "{rows: 2.5}"), ConfigError);
  CHECK_THROWS_AS(make_node("mlp", "{widths: [0]}"), ConfigError);
  CHECK_THROWS_AS(make_node("mlp", "{activation: softmax}"), ConfigError);
}

TEST_CASE("mlp without hidden layers is one dense map of the flattened input", "[mlp]") {
  auto node = make_node("mlp", "{widths: [], rows: 1}");
  Tensor x(2, 2, 2);
  const float xv[2][4] = {{1, 2, 3, 4}, {-1, 0, 0.5f, 2}};
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < 4; ++i) x(b, i / 2, i % 2) = xv[b][i];
  const auto out = run_forward(*node, {{"x", x}}, {}, [](Node& n) {
    for (int r = 0; r < 4; ++r)  // [4, 3]: flattened input -> xyz of the one output row
      for (int c = 0; c < 3; ++c) n.weights().at("mlp_w0").value(0, r, c) = float(r - c);
    for (int c = 0; c < 3; ++c) n.weights().at("mlp_b0").value(0, 0, c) = 0.5f * float(c);
  });
  for (int b = 0; b < 2; ++b)
    for (int c = 0; c < 3; ++c) {
      float expected = 0.5f * float(c);
      for (int i = 0; i < 4; ++i) expected += xv[b][i] * float(i - c);
      CHECK(out.at("out")(b, 0, c) == Approx(expected));
    }
}

TEST_CASE("mlp backward matches finite differences", "[mlp][gradcheck]") {
  const std::pair<const char*, bool> configs[] = {{"{widths: [12, 9], rows: 4}", true},
                                                   {"{widths: [10], activation: leaky_relu}", true},
                                                   {"{widths: [8, 6], activation: tanh}", false},
                                                   {"{widths: [], rows: 2}", false}};
  for (const auto& [params, piecewise_linear] : configs) {
    INFO(params);
    auto node = make_node("mlp", params);
    const GradCheckReport r = check_node_gradients(*node, {{"x", random_tensor(3, 5, 2, 21)}}, {"dec", 9},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 1 + node->weights().size());
    CHECK(r.ok(1e-2));
  }
}
