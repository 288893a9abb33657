// cnn1d_decoder: shapes and weights, a convolution by hand along the vertex
// order, finite differences for input and weights, errors.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("cnn1d_decoder: shapes, weights and errors", "[decoders][cnn1d_decoder]") {
  CHECK(plugins().get("cnn1d_decoder").kind == "decoder");
  auto node = make_node("cnn1d_decoder", "{channels: [8, 4], kernel: 5}");
  CHECK(node->setup({{"x", {20, 6}}}, {}).at("out") == Shape{20, 3});
  CHECK(node->weights().at("conv0_w").value.shape() == Shape{5 * 6, 8});
  CHECK(node->weights().at("conv1_w").value.shape() == Shape{5 * 8, 4});
  CHECK(node->weights().at("conv2_w").value.shape() == Shape{5 * 4, 3});
  CHECK(node->weights().at("conv2_b").value.shape() == Shape{1, 3});
  CHECK(node->flops_per_sample() == Approx(20.0 * (30 * 8 + 40 * 4 + 20 * 3)));
  // With a garment bound, one row per garment vertex.
  const Assets assets = assets_with(grid_garment(4, 0.1));
  CHECK(node->setup({{"x", {16, 6}}}, {"c", 0, &assets}).at("out") == Shape{16, 3});
  CHECK_THROWS_WITH(node->setup({{"x", {15, 6}}}, {"c", 0, &assets}), Catch::Contains("one row per garment vertex (16)"));
  CHECK_THROWS_WITH(make_node("cnn1d_decoder", "{kernel: 0}"), Catch::Contains("kernel"));
  CHECK_THROWS_WITH(make_node("cnn1d_decoder", "{activation: softmax}"), Catch::Contains("softmax"));
}

TEST_CASE("cnn1d_decoder convolves along the vertex order with zero padding", "[decoders][cnn1d_decoder]") {
  // No hidden layer, kernel 3, one input channel: out_0[i] = x[i-1] + 2 x[i] + 3 x[i+1],
  // out_1[i] = 0.5, out_2[i] = x[i+1] (zero beyond the ends).
  auto node = make_node("cnn1d_decoder", "{channels: [], kernel: 3}");
  Tensor x(1, 5, 1);
  for (int i = 0; i < 5; ++i) x(0, i, 0) = float(i + 1);
  const auto out = run_forward(*node, {{"x", x}}, {}, [](Node& n) {
    auto w = n.weights().at("conv0_w").value.mat(0);
    w << 1, 0, 0, 2, 0, 0, 3, 0, 1;
    n.weights().at("conv0_b").value.mat(0) << 0, 0.5f, 0;
  });
  const float expected0[5] = {0 + 2 * 1 + 3 * 2, 1 + 2 * 2 + 3 * 3, 2 + 2 * 3 + 3 * 4, 3 + 2 * 4 + 3 * 5, 4 + 2 * 5 + 0};
  for (int i = 0; i < 5; ++i) {
    CHECK(out.at("out")(0, i, 0) == Approx(expected0[i]));
    CHECK(out.at("out")(0, i, 1) == Approx(0.5));
    CHECK(out.at("out")(0, i, 2) == Approx(i < 4 ? i + 2 : 0));
  }
}

TEST_CASE("cnn1d_decoder backward matches finite differences", "[decoders][cnn1d_decoder][gradcheck]") {
  const Tensor x = random_tensor(2, 12, 2, 5);
  for (const char* yaml : {"{channels: [4, 3], kernel: 3, activation: tanh}", "{channels: [4], kernel: 5}"}) {
    auto node = make_node("cnn1d_decoder", yaml);
    const GradCheckReport r = check_node_gradients(*node, {{"x", x}}, {"c", 11}, kink_safe());
    INFO(yaml << "\n" << r.str());
    CHECK(r.ok(1e-2));
  }
}
