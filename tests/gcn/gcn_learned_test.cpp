// gcn_learned: the seed's learned per-vertex aggregation (eq. 6.4) as a body
// encoder, pooling consecutive vertex blocks between layers.
#include <catch2/catch.hpp>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// Vertex adjacency (without self) of a mesh, dense.
DenseF dense_adjacency(const Mesh& mesh) {
  DenseF a = DenseF::Zero(mesh.num_vertices(), mesh.num_vertices());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) a(mesh.faces(f, c), mesh.faces(f, (c + 1) % 3)) = a(mesh.faces(f, (c + 1) % 3), mesh.faces(f, c)) = 1;
  return a;
}

// Mean over blocks of `stride` consecutive rows, dense [blocks, n].
DenseF dense_block_mean(int n, int stride) {
  const int blocks = (n + stride - 1) / stride;
  DenseF p = DenseF::Zero(blocks, n);
  for (int b = 0; b < blocks; ++b) {
    const int first = b * stride, last = std::min(n, first + stride);
    p.block(b, first, 1, last - first).setConstant(1.0f / float(last - first));
  }
  return p;
}

// The graph of the pooled blocks: adjacent when any of their vertices are (B A B^T > 0 off the diagonal).
DenseF pooled_adjacency(const DenseF& adjacency, const DenseF& pool) {
  DenseF joined = ((pool * adjacency * pool.transpose()).array() > 0.0f).cast<float>();
  joined.diagonal().setZero();
  return joined;
}

// The pattern of (adjacency + I) filled with `values` row by row, columns ascending.
DenseF dense_learned(const DenseF& adjacency, const float* values) {
  DenseF a = DenseF::Zero(adjacency.rows(), adjacency.cols());
  int k = 0;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      if (i == j || adjacency(i, j) != 0.0f) a(i, j) = values[k++];
  return a;
}

}  // namespace

TEST_CASE("gcn_learned loads from its plugin library as an encoder", "[gcn][gcn_learned]") {
  const PluginDescriptor& d = plugins().get("gcn_learned");
  CHECK(d.kind == "encoder");
  CHECK(d.file.find("libdrape_plugin_gcn_learned") != std::string::npos);
}

TEST_CASE("gcn_learned defaults: three scales 2x apart, cnn1d's ports and shapes", "[gcn][gcn_learned]") {
  const auto assets = gcn_assets();
  const int nb = assets->body.num_vertices();  // 49: scales 49, 25, 13
  auto node = make_node("gcn_learned");
  const ShapeMap out = node->setup({{"body", {nb, 3}}}, {"enc", 1, assets.get()});
  CHECK(out == make_node("cnn1d")->setup({{"body", {nb, 3}}}, {}));
  CHECK(out.at("features") == Shape{nb, 128});
  REQUIRE(node->weights().size() == 9);
  CHECK(node->weights().at("conv0_w").value.shape() == Shape{3, 32});
  CHECK(node->weights().at("conv2_w").value.shape() == Shape{64, 128});
  const DenseF adj0 = dense_adjacency(assets->body);
  const DenseF p1 = dense_block_mean(nb, 2), p2 = dense_block_mean(25, 2);
  const DenseF adj1 = pooled_adjacency(adj0, p1), adj2 = pooled_adjacency(adj1, p2);
  const double nnz0 = nb + adj0.sum(), nnz1 = 25 + adj1.sum(), nnz2 = 13 + adj2.sum();
  CHECK(node->weights().at("conv0_a").value.cols() == int(nnz0));
  CHECK(node->weights().at("conv1_a").value.cols() == int(nnz1));
  CHECK(node->weights().at("conv2_a").value.cols() == int(nnz2));
  CHECK(node->flops_per_sample() == Approx(nb * 3.0 * 32 + nnz0 * 3 + double(nb) * 32 + 25 * 32.0 * 64 + nnz1 * 32 +
                                           25.0 * 64 + 13 * 64.0 * 128 + nnz2 * 64));
}

TEST_CASE("gcn_learned convolves, pools blocks between layers and maps vertices to their block", "[gcn][gcn_learned]") {
  const auto assets = gcn_assets();
  const int nb = assets->body.num_vertices();  // 49 -> 17 -> 6 with stride 3
  auto node = make_node("gcn_learned", "{channels: [3, 4, 2], stride: 3, activation: tanh}");
  const Tensor body = random_tensor(2, nb, 3, 31);
  const auto out = run_forward(*node, {{"body", body}}, {"enc", 1, assets.get()}, [](Node& n) { randomise_weights(n, 3); });
  // The pooled graphs straight from the definition: blocks adjacent when B A B^T > 0 off the diagonal.
  std::vector<DenseF> adjacency{dense_adjacency(assets->body)};
  std::vector<DenseF> pools{DenseF()};
  int rows = nb;
  for (int l = 1; l < 3; ++l) {
    const DenseF p = dense_block_mean(rows, 3);
    adjacency.push_back(pooled_adjacency(adjacency.back(), p));
    pools.push_back(p);
    rows = int(p.rows());
  }
  REQUIRE(rows == 6);
  for (int b = 0; b < 2; ++b) {
    DenseF h = dense_of(body, b);
    for (int l = 0; l < 3; ++l) {
      const std::string p = "conv" + std::to_string(l) + "_";
      if (l > 0) h = pools[std::size_t(l)] * h;
      const DenseF a = dense_learned(adjacency[std::size_t(l)], node->weights().at(p + "a").value.data());
      h = activate_dense((a * h * weight_of(*node, p + "w")).rowwise() + bias_of(*node, p + "b"), "tanh");
    }
    for (int v = 0; v < nb; ++v)
      CHECK((out.at("features").mat(b).row(v) - h.row(v / 9)).cwiseAbs().maxCoeff() < 1e-5f);
    CHECK((dense_of(out.at("global"), b) - h.colwise().mean()).cwiseAbs().maxCoeff() < 1e-5f);
  }
}

TEST_CASE("gcn_learned rejects bad parameters, inputs and missing assets", "[gcn][gcn_learned]") {
  const auto assets = gcn_assets();
  const int nb = assets->body.num_vertices();
  CHECK_THROWS_WITH(make_node("gcn_learned", "{channels: []}"), Catch::Contains("channels"));
  CHECK_THROWS_AS(make_node("gcn_learned", "{stride: 0}"), ConfigError);
  CHECK_THROWS_AS(make_node("gcn_learned", "{kernel: 3}"), ConfigError);
  CHECK_THROWS_WITH(make_node("gcn_learned")->setup({{"body", {nb, 4}}}, {"enc", 1, assets.get()}),
                    Catch::Contains("[vertices, 3]"));
  CHECK_THROWS_WITH(make_node("gcn_learned")->setup({{"body", {nb + 1, 3}}}, {"enc", 1, assets.get()}),
                    Catch::Contains("assets' body"));
  CHECK_THROWS_WITH(make_node("gcn_learned")->setup({{"body", {nb, 3}}}, {}), Catch::Contains("assets"));
}

TEST_CASE("gcn_learned backward matches finite differences for the body and every weight", "[gcn][gcn_learned][gradcheck]") {
  const auto assets = gcn_assets();
  const int nb = assets->body.num_vertices();
  const std::pair<const char*, bool> configs[] = {{"{channels: [4, 5, 3], stride: 2, activation: tanh}", false},
                                                   {"{channels: [3, 4], stride: 3}", true},
                                                   {"{channels: [4], activation: tanh}", false}};
  for (const auto& [params, piecewise_linear] : configs) {
    INFO(params);
    auto node = make_node("gcn_learned", params);
    const GradCheckReport r = check_node_gradients(*node, {{"body", random_tensor(2, nb, 3, 17)}}, {"enc", 6, assets.get()},
                                                   piecewise_linear ? kink_safe() : GradCheckOptions{});
    INFO(r.str());
    CHECK(r.entries.size() == 1 + node->weights().size());
    CHECK(r.ok(1e-2));
  }
}
