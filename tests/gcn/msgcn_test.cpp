// msgcn, the seed's multi-scale GCN decoder (Sec. 6.3.2, eq. 6.4), on a small
// garment grid and its hierarchy.
#include <drape/nn/mesh_graph.hpp>

#include <catch2/catch.hpp>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// Dense restriction of level l -> l+1: U_l^T with rows normalised.
DenseF dense_restriction(const Assets& a, int l) {
  DenseF r = DenseF(level(a, l).upsample).transpose();
  return r.array().colwise() / r.rowwise().sum().array();
}

DenseF dense_upsample(const Assets& a, int l) { return DenseF(level(a, l).upsample); }

DenseF learned_ring(const Node& n, const Assets& a, int l, int k) {
  return dense_ring(level(a, l).mesh, n.weights().at("level" + std::to_string(l) + "_conv" + std::to_string(k) + "_a").value.data());
}

DenseF conv(const Node& n, const Assets& a, int l, int k, const DenseF& x, const std::string& f) {
  const std::string p = "level" + std::to_string(l) + "_conv" + std::to_string(k) + "_";
  return activate_dense((learned_ring(n, a, l, k) * x * weight_of(n, p + "w")).rowwise() + bias_of(n, p + "b"), f);
}

}  // namespace

TEST_CASE("msgcn loads from its plugin library as a decoder", "[gcn][msgcn]") {
  const PluginDescriptor& d = plugins().get("msgcn");
  CHECK(d.kind == "decoder");
  CHECK(d.file.find("libdrape_plugin_msgcn") != std::string::npos);
}

TEST_CASE("msgcn defaults: four levels coarsest first, two learned convolutions each, a head to 3", "[gcn][msgcn]") {
  const auto assets = gcn_assets();
  REQUIRE(assets->hierarchy.num_levels() == 4);
  const int ng = vertices_of(*assets, 0);
  auto node = make_node("msgcn");
  const ShapeMap out = node->setup({{"x", {ng, 5}}}, {"dec", 1, assets.get()});
  CHECK(out.at("out") == Shape{ng, 3});
  CHECK(node->weights().size() == 4 * 2 * 3 + 2);
  // Channels [64, 64, 32, 32] on levels 3, 2, 1, 0.
  CHECK(node->weights().at("level3_conv0_w").value.shape() == Shape{5, 64});
  CHECK(node->weights().at("level3_conv1_w").value.shape() == Shape{64, 64});
  CHECK(node->weights().at("level2_conv0_w").value.shape() == Shape{64, 64});
  CHECK(node->weights().at("level1_conv0_w").value.shape() == Shape{64, 32});
  CHECK(node->weights().at("level0_conv1_w").value.shape() == Shape{32, 32});
  CHECK(node->weights().at("out_w0").value.shape() == Shape{32, 3});
  // One aggregation weight per vertex and neighbour, and per vertex for itself.
  double expected_flops = 0.0;
  const int channels[4] = {64, 64, 32, 32};
  DenseF pool = DenseF::Identity(ng, ng);
  for (int l = 0; l < 3; ++l) pool = dense_restriction(*assets, l) * pool;
  expected_flops += double((pool.array() != 0.0f).count()) * 5;
  for (int l = 3; l >= 0; --l) {
    const Mesh& mesh = level(*assets, l).mesh;
    const int n = mesh.num_vertices();
    const long nnz = n + 2 * long(geometry::edge_list(mesh.faces).size());
    for (int k = 0; k < 2; ++k)
      CHECK(node->weights().at("level" + std::to_string(l) + "_conv" + std::to_string(k) + "_a").value.shape() ==
            Shape{1, int(nnz)});
    const int c = channels[3 - l], c_in = l == 3 ? 5 : channels[2 - l];
    expected_flops += double(n) * c_in * c + double(nnz) * std::min(c_in, c) + double(n) * c * c + double(nnz) * c;
    if (l < 3) expected_flops += double((dense_upsample(*assets, l).array() != 0.0f).count()) * c_in;
  }
  expected_flops += double(ng) * 32 * 3;
  CHECK(node->flops_per_sample() == Approx(expected_flops));
  // The aggregation starts as the neighbourhood mean: each vertex's weights sum to 1.
  const DenseF a0 = learned_ring(*node, *assets, 0, 0);
  CHECK((a0.rowwise().sum().array() - 1.0f).abs().maxCoeff() < 1e-5f);
}

TEST_CASE("msgcn rejects bad parameters, inputs and missing assets", "[gcn][msgcn]") {
  const auto assets = gcn_assets();
  const int ng = vertices_of(*assets, 0);
  const NodeContext ctx{"dec", 1, assets.get()};
  CHECK_THROWS_WITH(make_node("msgcn", "{channels: []}"), Catch::Contains("channels"));
  CHECK_THROWS_WITH(make_node("msgcn", "{layers: []}"), Catch::Contains("layers"));
  CHECK_THROWS_AS(make_node("msgcn", "{layers: [0]}"), ConfigError);
  CHECK_THROWS_AS(make_node("msgcn", "{channels: [8, 0]}"), ConfigError);
  CHECK_THROWS_WITH(make_node("msgcn", "{activation: swish}"), Catch::Contains("leaky_relu"));
  CHECK_THROWS_WITH(make_node("msgcn", "{channels: [8, 8, 8, 8, 8]}")->setup({{"x", {ng, 4}}}, ctx),
                    Catch::Contains("hierarchy has 4 levels"));
  CHECK_THROWS_WITH(make_node("msgcn", "{channels: [8, 8, 8], layers: [1, 2]}")->setup({{"x", {ng, 4}}}, ctx),
                    Catch::Contains("one per level (3)"));
  CHECK_THROWS_WITH(make_node("msgcn")->setup({{"x", {ng + 1, 4}}}, ctx), Catch::Contains("garment vertices"));
  CHECK_THROWS_WITH(make_node("msgcn")->setup({{"x", {ng, 4}}}, {}), Catch::Contains("assets"));
}

TEST_CASE("msgcn pools the input to the coarsest level, convolves and up-samples level by level", "[gcn][msgcn]") {
  const auto assets = gcn_assets();
  const int ng = vertices_of(*assets, 0);
  auto node = make_node("msgcn", "{channels: [3, 4, 2], layers: [1, 2, 1], activation: tanh}");
  const Tensor x = random_tensor(2, ng, 3, 21);
  const auto out = run_forward(*node, {{"x", x}}, {"dec", 1, assets.get()}, [](Node& n) { randomise_weights(n, 40); });
  CHECK(out.at("out").shape() == Shape{ng, 3});
  const DenseF pool = dense_restriction(*assets, 1) * dense_restriction(*assets, 0);
  for (int b = 0; b < 2; ++b) {
    DenseF h = conv(*node, *assets, 2, 0, pool * dense_of(x, b), "tanh");
    h = dense_upsample(*assets, 1) * h;
    h = conv(*node, *assets, 1, 1, conv(*node, *assets, 1, 0, h, "tanh"), "tanh");
    h = conv(*node, *assets, 0, 0, dense_upsample(*assets, 0) * h, "tanh");
    const DenseF expected = (h * weight_of(*node, "out_w0")).rowwise() + bias_of(*node, "out_b0");
    CHECK((dense_of(out.at("out"), b) - expected).cwiseAbs().maxCoeff() < 1e-4f);
  }
}

TEST_CASE("msgcn's aggregation weights belong to one vertex and one neighbour each (eq. 6.4)", "[gcn][msgcn]") {
  const auto assets = gcn_assets();
  const int ng = vertices_of(*assets, 0);
  const Mesh& garment = level(*assets, 0).mesh;
  const auto nbrs = geometry::vertex_neighbours(garment.faces, ng);
  auto node = make_node("msgcn", "{channels: [4, 4], layers: [1], activation: tanh}");
  const Tensor x = random_tensor(1, ng, 3, 5);
  const NodeContext ctx{"dec", 3, assets.get()};
  const auto before = run_forward(*node, {{"x", x}}, ctx).at("out");
  // The entry of garment vertex i for neighbour j: row i, after the entries of its smaller columns.
  const int i = ng / 2;
  const int j = nbrs[std::size_t(i)].back();
  int k = 0;
  for (int r = 0; r < i; ++r) k += int(nbrs[std::size_t(r)].size()) + 1;
  k += int(nbrs[std::size_t(i)].size());  // j is i's largest neighbour and j > i on this grid
  REQUIRE(j > i);
  const auto after = run_forward(*node, {{"x", x}}, ctx, [&](Node& n) { n.weights().at("level0_conv0_a").value(0, 0, k) += 0.5f; })
                         .at("out");
  // Only vertex i's output moves (the last convolution feeds a per-vertex head), and
  // by the change of its aggregated features: 0.5 * (x W)_j through tanh and the head.
  for (int v = 0; v < ng; ++v) {
    const double moved = (after.mat(0).row(v) - before.mat(0).row(v)).norm();
    if (v == i) CHECK(moved > 1e-4);
    else CHECK(moved == 0.0);
  }
}

TEST_CASE("msgcn backward matches finite differences for the input and every weight", "[gcn][msgcn][gradcheck]") {
  const auto assets = gcn_assets();
  const int ng = vertices_of(*assets, 0);
  // Pooled and up-sampled features are averages, small at the coarse levels;
  // with zero initial biases many pre-activations there sit within a step of
  // leaky_relu's kink, so the deep piecewise-linear check uses two levels and
  // tanh covers all four.
  const std::pair<const char*, bool> configs[] = {
      {"{channels: [4, 3, 2], layers: [1, 2, 1], activation: tanh}", false},
      {"{channels: [3, 3, 3, 2], layers: [1], activation: tanh}", false},
      {"{channels: [4, 3], layers: [1], activation: leaky_relu}", true},
      {"{channels: [3], layers: [2], activation: tanh}", false}};  // the garment level alone, no pooling
  for (const auto& [params, piecewise_linear] : configs) {
    INFO(params);
    auto node = make_node("msgcn", params);
    const GradCheckReport r = check_node_gradients(*node, {{"x", random_tensor(2, ng, 3, 7)}}, {"dec", 9, assets.get()},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 1 + node->weights().size());
    CHECK(r.ok(1e-2));
  }
}
