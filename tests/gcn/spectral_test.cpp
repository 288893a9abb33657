// spectral: the seed's spectral residual branch (Sec. 6.3.3), Delta x = V Delta c.
#include <drape/nn/activation.hpp>
#include <drape/nn/init.hpp>

#include <catch2/catch.hpp>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("spectral loads from its plugin library as a decoder", "[gcn][spectral]") {
  const PluginDescriptor& d = plugins().get("spectral");
  CHECK(d.kind == "decoder");
  CHECK(d.file.find("libdrape_plugin_spectral") != std::string::npos);
}

TEST_CASE("spectral: k from its parameter, clamped to the assets' eigenvectors", "[gcn][spectral]") {
  const auto assets = gcn_assets();  // 6 eigenvectors
  const int ng = vertices_of(*assets, 0);
  const NodeContext ctx{"spec", 1, assets.get()};
  auto all = make_node("spectral");
  const ShapeMap out = all->setup({{"x", {1, 8}}}, ctx);
  CHECK(out.at("out") == Shape{ng, 3});
  CHECK(out.at("coefficients") == Shape{6, 3});
  CHECK(all->weights().at("mlp_w0").value.shape() == Shape{8, 256});
  CHECK(all->weights().at("mlp_w1").value.shape() == Shape{256, 18});
  CHECK(all->flops_per_sample() == Approx(8.0 * 256 + 256.0 * 18 + double(ng) * 6 * 3));
  CHECK(make_node("spectral", "{k: 4}")->setup({{"x", {1, 8}}}, ctx).at("coefficients") == Shape{4, 3});
  CHECK(make_node("spectral", "{k: 100}")->setup({{"x", {1, 8}}}, ctx).at("coefficients") == Shape{6, 3});
}

TEST_CASE("spectral scales the last layer's initial weights by init_scale", "[gcn][spectral]") {
  const auto assets = gcn_assets();
  const NodeContext ctx{"spec", 1, assets.get()};
  auto small = make_node("spectral", "{widths: [16], init_scale: 0.01}");
  auto full = make_node("spectral", "{widths: [16], init_scale: 1.0}");
  small->setup({{"x", {1, 8}}}, ctx);
  full->setup({{"x", {1, 8}}}, ctx);
  CHECK(small->weights().at("mlp_w0").value.vec() == full->weights().at("mlp_w0").value.vec());
  const Eigen::VectorXf expected = 0.01f * full->weights().at("mlp_w1").value.vec();
  CHECK((small->weights().at("mlp_w1").value.vec() - expected).cwiseAbs().maxCoeff() < 1e-9f);
  CHECK(full->weights().at("mlp_w1").value.vec().cwiseAbs().maxCoeff() > 0.0f);
}

TEST_CASE("spectral: Delta c from the MLP on the flattened input, Delta x = V Delta c", "[gcn][spectral]") {
  const auto assets = gcn_assets();
  const DenseF v = assets->eigenvectors.leftCols(4);
  // The node keeps V in bfloat16; Eigen's own conversion (round to nearest even) is the reference.
  const DenseF v16 = v.unaryExpr([](float e) { return static_cast<float>(Eigen::bfloat16(e)); });
  CHECK((v16 - v).cwiseAbs().maxCoeff() > 0.0f);  // the rounding is real at this size
  CHECK(((v16 - v).cwiseAbs().array() <= v.cwiseAbs().array() / 256).all());
  // Any batch size gives V Delta c (one sample and three: the products' row blocks and their tails).
  for (int batch : {1, 3}) {
    INFO("batch " << batch);
    auto node = make_node("spectral", "{widths: [5], k: 4, activation: tanh, init_scale: 1.0}");
    const Tensor x = random_tensor(batch, 2, 4, 2);  // [R=2, C=4] flattened to 8 inputs
    const auto out = run_forward(*node, {{"x", x}}, {"spec", 1, assets.get()});
    for (int b = 0; b < batch; ++b) {
      const Eigen::RowVectorXf flat = Eigen::Map<const Eigen::RowVectorXf>(x.mat(b).data(), 8);
      const Eigen::RowVectorXf hidden =
          ((flat * weight_of(*node, "mlp_w0")) + bias_of(*node, "mlp_b0")).array().tanh().matrix();
      const Eigen::RowVectorXf mlp = hidden * weight_of(*node, "mlp_w1") + bias_of(*node, "mlp_b1");
      DenseF dc(4, 3);
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) dc(i, c) = mlp(3 * i + c);  // coefficient i of axis c
      CHECK((dense_of(out.at("coefficients"), b) - dc).cwiseAbs().maxCoeff() < 1e-5f);
      CHECK((dense_of(out.at("out"), b) - v16 * dc).cwiseAbs().maxCoeff() < 1e-5f);
      // Orthonormal columns up to the rounding: the coefficients come back, V^T Delta x = Delta c.
      CHECK((v.transpose() * dense_of(out.at("out"), b) - dc).cwiseAbs().maxCoeff() < 1e-2f * dc.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("spectral: use_k applies only the first eigenvectors, with the same weights", "[gcn][spectral]") {
  const auto assets = gcn_assets();
  const DenseF v16 = assets->eigenvectors.leftCols(5).unaryExpr([](float e) { return static_cast<float>(Eigen::bfloat16(e)); });
  for (int batch : {1, 3}) {
    INFO("batch " << batch);
    const Tensor x = random_tensor(batch, 1, 8, 7);
    auto all = make_node("spectral", "{widths: [5], k: 5, init_scale: 1.0}");
    auto two = make_node("spectral", "{widths: [5], k: 5, use_k: 2, init_scale: 1.0}");
    const auto full = run_forward(*all, {{"x", x}}, {"spec", 1, assets.get()});
    const auto cut = run_forward(*two, {{"x", x}}, {"spec", 1, assets.get()});
    CHECK(two->flops_per_sample() < all->flops_per_sample());
    for (int b = 0; b < batch; ++b) {
      const DenseF dc = dense_of(full.at("coefficients"), b);
      CHECK(dense_of(cut.at("coefficients"), b) == dc);  // same weights, same coefficients
      CHECK((dense_of(cut.at("out"), b) - v16.leftCols(2) * dc.topRows(2)).cwiseAbs().maxCoeff() < 1e-5f);
      CHECK((dense_of(full.at("out"), b) - v16 * dc).cwiseAbs().maxCoeff() < 1e-5f);
    }
  }
}

TEST_CASE("spectral rejects bad parameters, inputs and missing assets", "[gcn][spectral]") {
  const auto assets = gcn_assets();
  CHECK_THROWS_AS(make_node("spectral", "{k: -1}"), ConfigError);
  CHECK_THROWS_AS(make_node("spectral", "{init_scale: 2.0}"), ConfigError);
  CHECK_THROWS_AS(make_node("spectral", "{widths: [0]}"), ConfigError);
  CHECK_THROWS_WITH(make_node("spectral")->setup({{"x", {1, 8}}}, {}), Catch::Contains("eigenvectors"));
  Assets no_basis;
  no_basis.garment = assets->garment;
  CHECK_THROWS_WITH(make_node("spectral")->setup({{"x", {1, 8}}}, {"spec", 1, &no_basis}), Catch::Contains("eigenvectors"));
  CHECK_THROWS_WITH(make_node("spectral")->setup({{"x", {0, 8}}}, {"spec", 1, assets.get()}), Catch::Contains("empty"));
}

TEST_CASE("spectral backward matches finite differences through both outputs", "[gcn][spectral][gradcheck]") {
  const auto assets = gcn_assets();
  // Batches of 1, 2 and 4 (the products' row blocks and their tails).
  const std::tuple<const char*, bool, int> configs[] = {{"{widths: [5], k: 4, activation: tanh, init_scale: 1.0}", false, 2},
                                                        {"{widths: [5], k: 4, activation: tanh, init_scale: 1.0}", false, 4},
                                                        {"{widths: [], init_scale: 0.5}", false, 1},
                                                        {"{widths: [6, 4], k: 3, init_scale: 1.0}", true, 4},
                                                        {"{widths: [5], k: 5, use_k: 2, activation: tanh, init_scale: 1.0}", false, 1},
                                                        {"{widths: [5], k: 5, use_k: 2, activation: tanh, init_scale: 1.0}", false, 4}};
  for (const auto& [params, piecewise_linear, batch] : configs) {
    INFO(params << " batch " << batch);
    auto node = make_node("spectral", params);
    const GradCheckReport r = check_node_gradients(*node, {{"x", random_tensor(batch, 1, 7, 4)}}, {"spec", 5, assets.get()},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 1 + node->weights().size());
    CHECK(r.ok(1e-2));
  }
}
