// gcn (encoder) and gcn_decoder: the original GCN of Kipf & Welling on the
// body and garment meshes.
#include <catch2/catch.hpp>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("gcn and gcn_decoder load from their plugin libraries", "[gcn][kipf]") {
  CHECK(plugins().get("gcn").kind == "encoder");
  CHECK(plugins().get("gcn").file.find("libdrape_plugin_gcn.so") != std::string::npos);
  CHECK(plugins().get("gcn_decoder").kind == "decoder");
  CHECK(plugins().get("gcn_decoder").file.find("libdrape_plugin_gcn_decoder") != std::string::npos);
}

TEST_CASE("gcn encoder: cnn1d's ports and shapes, isotropic layers (only W and b are learned)", "[gcn][kipf]") {
  const auto assets = gcn_assets();
  const int nb = assets->body.num_vertices();
  auto node = make_node("gcn");
  const ShapeMap out = node->setup({{"body", {nb, 3}}}, {"enc", 1, assets.get()});
  CHECK(out.at("features") == Shape{nb, 128});
  CHECK(out.at("global") == Shape{1, 128});
  REQUIRE(node->weights().size() == 6);
  CHECK(node->weights().at("conv0_w").value.shape() == Shape{3, 32});
  CHECK(node->weights().at("conv1_w").value.shape() == Shape{32, 64});
  CHECK(node->weights().at("conv2_w").value.shape() == Shape{64, 128});
  const double nnz = nb + 2.0 * double(geometry::edge_list(assets->body.faces).size());
  CHECK(node->flops_per_sample() ==
        Approx(nb * (3.0 * 32 + 32.0 * 64 + 64.0 * 128) + nnz * (3 + 32 + 64)));
  // The same port names and shapes as cnn1d, so one replaces the other in a graph.
  auto cnn = make_node("cnn1d");
  const ShapeMap cnn_out = cnn->setup({{"body", {nb, 3}}}, {"enc", 1, assets.get()});
  CHECK(cnn_out == out);
}

TEST_CASE("gcn encoder computes H' = f(D^-1/2 (A + I) D^-1/2 H W + b) and the vertex mean", "[gcn][kipf]") {
  const auto assets = gcn_assets();
  const int nb = assets->body.num_vertices();
  auto node = make_node("gcn", "{channels: [4, 5], activation: tanh}");
  const Tensor body = random_tensor(2, nb, 3, 3);
  const auto out = run_forward(*node, {{"body", body}}, {"enc", 1, assets.get()}, [](Node& n) { randomise_weights(n, 8); });
  const DenseF a = dense_kipf(assets->body);
  for (int b = 0; b < 2; ++b) {
    DenseF h = dense_of(body, b);
    for (const char* l : {"conv0_", "conv1_"})
      h = activate_dense((a * h * weight_of(*node, std::string(l) + "w")).rowwise() + bias_of(*node, std::string(l) + "b"),
                         "tanh");
    CHECK((dense_of(out.at("features"), b) - h).cwiseAbs().maxCoeff() < 1e-5f);
    CHECK((dense_of(out.at("global"), b) - h.colwise().mean()).cwiseAbs().maxCoeff() < 1e-5f);
  }
}

TEST_CASE("gcn encoder rejects bad parameters, inputs and missing assets", "[gcn][kipf]") {
  const auto assets = gcn_assets();
  const int nb = assets->body.num_vertices();
  CHECK_THROWS_WITH(make_node("gcn", "{channels: []}"), Catch::Contains("channels"));
  CHECK_THROWS_AS(make_node("gcn", "{channels: [0]}"), ConfigError);
  CHECK_THROWS_AS(make_node("gcn", "{stride: 2}"), ConfigError);  // no such parameter
  CHECK_THROWS_WITH(make_node("gcn")->setup({{"body", {nb, 2}}}, {"enc", 1, assets.get()}), Catch::Contains("[vertices, 3]"));
  CHECK_THROWS_WITH(make_node("gcn")->setup({{"body", {nb - 1, 3}}}, {"enc", 1, assets.get()}),
                    Catch::Contains("expected " + std::to_string(nb) + " (the assets' body"));
  CHECK_THROWS_WITH(make_node("gcn")->setup({{"body", {nb, 3}}}, {}), Catch::Contains("assets"));
}

TEST_CASE("gcn encoder backward matches finite differences", "[gcn][kipf][gradcheck]") {
  const auto assets = gcn_assets();
  const int nb = assets->body.num_vertices();
  const std::pair<const char*, bool> configs[] = {{"{channels: [4, 6], activation: tanh}", false},
                                                   {"{channels: [5, 3]}", true}};
  for (const auto& [params, piecewise_linear] : configs) {
    INFO(params);
    auto node = make_node("gcn", params);
    const GradCheckReport r = check_node_gradients(*node, {{"body", random_tensor(2, nb, 3, 5)}}, {"enc", 4, assets.get()},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 1 + node->weights().size());
    CHECK(r.ok(1e-2));
  }
}

TEST_CASE("gcn_decoder: Kipf layers on the garment graph, then a dense head to 3", "[gcn][kipf]") {
  const auto assets = gcn_assets();
  const int ng = vertices_of(*assets, 0);
  auto defaults = make_node("gcn_decoder");
  CHECK(defaults->setup({{"x", {ng, 6}}}, {"dec", 1, assets.get()}).at("out") == Shape{ng, 3});
  CHECK(defaults->weights().size() == 2 * 4 + 2);
  CHECK(defaults->weights().at("conv0_w").value.shape() == Shape{6, 64});
  CHECK(defaults->weights().at("conv3_w").value.shape() == Shape{32, 32});
  CHECK(defaults->weights().at("out_w0").value.shape() == Shape{32, 3});
  const double nnz = ng + 2.0 * double(geometry::edge_list(assets->garment->mesh.faces).size());
  CHECK(defaults->flops_per_sample() ==
        Approx(ng * (6.0 * 64 + 64.0 * 64 + 64.0 * 32 + 32.0 * 32 + 32.0 * 3) + nnz * (6 + 64 + 32 + 32)));

  auto node = make_node("gcn_decoder", "{channels: [5, 2], activation: tanh}");
  const Tensor x = random_tensor(2, ng, 4, 13);
  const auto out = run_forward(*node, {{"x", x}}, {"dec", 1, assets.get()}, [](Node& n) { randomise_weights(n, 2); });
  const DenseF a = dense_kipf(assets->garment->mesh);
  for (int b = 0; b < 2; ++b) {
    DenseF h = dense_of(x, b);
    for (const char* l : {"conv0_", "conv1_"})
      h = activate_dense((a * h * weight_of(*node, std::string(l) + "w")).rowwise() + bias_of(*node, std::string(l) + "b"),
                         "tanh");
    const DenseF expected = (h * weight_of(*node, "out_w0")).rowwise() + bias_of(*node, "out_b0");
    CHECK((dense_of(out.at("out"), b) - expected).cwiseAbs().maxCoeff() < 1e-5f);
  }
}

TEST_CASE("gcn_decoder rejects bad parameters, inputs and missing assets", "[gcn][kipf]") {
  const auto assets = gcn_assets();
  const int ng = vertices_of(*assets, 0);
  CHECK_THROWS_WITH(make_node("gcn_decoder", "{channels: []}"), Catch::Contains("channels"));
  CHECK_THROWS_WITH(make_node("gcn_decoder")->setup({{"x", {ng + 2, 4}}}, {"dec", 1, assets.get()}),
                    Catch::Contains("garment vertices = " + std::to_string(ng)));
  CHECK_THROWS_WITH(make_node("gcn_decoder")->setup({{"x", {ng, 4}}}, {}), Catch::Contains("assets"));
}

TEST_CASE("gcn_decoder backward matches finite differences", "[gcn][kipf][gradcheck]") {
  const auto assets = gcn_assets();
  const int ng = vertices_of(*assets, 0);
  const std::pair<const char*, bool> configs[] = {{"{channels: [6, 3], activation: tanh}", false},
                                                   {"{channels: [2, 7, 4], activation: tanh}", false},
                                                   {"{channels: [5, 3]}", true}};
  for (const auto& [params, piecewise_linear] : configs) {
    INFO(params);
    auto node = make_node("gcn_decoder", params);
    const GradCheckReport r = check_node_gradients(*node, {{"x", random_tensor(2, ng, 4, 6)}}, {"dec", 2, assets.get()},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 1 + node->weights().size());
    CHECK(r.ok(1e-2));
  }
}
