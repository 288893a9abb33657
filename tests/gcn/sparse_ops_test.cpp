// The framework pieces under the graph-convolution plugins (drape/nn/sparse_ops,
// mesh_graph, graph_conv): matrices against their definitions, transposes
// against adjointness, gradients against finite differences.
#include <drape/errors.hpp>
#include <drape/gradcheck.hpp>
#include <drape/nn/graph_conv.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/mesh_graph.hpp>
#include <drape/nn/sparse_ops.hpp>

#include <Eigen/Eigenvalues>

#include <catch2/catch.hpp>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// A path 0-1-2-3-4 and a triangle 5-6-7 (two components, degrees 1 to 2).
nn::Neighbours small_graph() { return {{1}, {0, 2}, {1, 3}, {2, 4}, {3}, {6, 7}, {5, 7}, {5, 6}}; }

// The pattern's matrix with other values (in its own storage order).
DenseF dense_ring_from(const nn::SparseRM& pattern, const float* values) {
  return DenseF(Eigen::Map<const nn::SparseRM>(pattern.rows(), pattern.cols(), pattern.nonZeros(),
                                               pattern.outerIndexPtr(), pattern.innerIndexPtr(), values));
}

MatrixRM random_rows(int rows, int cols, std::uint64_t seed) { return random_tensor(1, rows, cols, seed).mat(0); }

// A node around one GraphConvLayer, for the finite-difference check.
class ConvNode final : public Node {
 public:
  explicit ConvNode(std::function<nn::GraphConvLayer(int in)> make) : make_(std::move(make)) {}
  ShapeMap setup(const ShapeMap& in, const NodeContext& ctx) override {
    layer_ = make_(in.at("x").cols);
    layer_.create_weights(*this, "g_", ctx.seed);
    randomise_weights(*this, 5);  // learned aggregation weights away from their tidy start
    return {{"y", {in.at("x").rows, layer_.out()}}};
  }
  void forward(const TensorIn& in, const TensorOut& out) override {
    out.at("y")->flat() = layer_.forward(in.at("x")->flat(), in.at("x")->batch());
  }
  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    MatrixRM gx;
    layer_.backward(in.at("x")->flat(), gout.at("y")->flat(), in.at("x")->batch(), &gx);
    gin.at("x")->flat() = gx;
  }

 private:
  std::function<nn::GraphConvLayer(int)> make_;
  nn::GraphConvLayer layer_;
};

}  // namespace

TEST_CASE("ring_mean: 1-ring and self, each row the neighbourhood mean", "[gcn][nn]") {
  const nn::SparseRM a = nn::ring_mean(small_graph());
  const DenseF d(a);
  CHECK(a.nonZeros() == 8 + 2 * 7);
  CHECK(d(0, 0) == Approx(0.5f));
  CHECK(d(0, 1) == Approx(0.5f));
  CHECK(d(2, 1) == Approx(1.0f / 3));
  CHECK(d(2, 3) == Approx(1.0f / 3));
  CHECK(d(2, 4) == 0.0f);
  CHECK(d(6, 5) == Approx(1.0f / 3));
  CHECK(d(5, 0) == 0.0f);
  CHECK((d.rowwise().sum().array() - 1.0f).abs().maxCoeff() < 1e-6f);
  CHECK_THROWS_AS(nn::ring_mean({{1, 1}, {0}}), Error);  // repeated neighbour
  CHECK_THROWS_AS(nn::ring_mean({{0}}), Error);          // itself
  CHECK_THROWS_AS(nn::ring_mean({{3}}), Error);          // out of range
}

TEST_CASE("kipf_adjacency is D^-1/2 (A + I) D^-1/2", "[gcn][nn]") {
  const DenseF d(nn::kipf_adjacency(small_graph()));
  CHECK((d - d.transpose()).cwiseAbs().maxCoeff() == 0.0f);
  // Degrees with the self loop: 2, 3, 3, 3, 2, 3, 3, 3.
  CHECK(d(0, 0) == Approx(1.0f / 2));
  CHECK(d(0, 1) == Approx(1.0f / std::sqrt(6.0f)));
  CHECK(d(1, 2) == Approx(1.0f / 3));
  CHECK(d(3, 4) == Approx(1.0f / std::sqrt(6.0f)));
  CHECK(d(5, 7) == Approx(1.0f / 3));
  CHECK(d(4, 5) == 0.0f);
  // Its largest eigenvalue is 1 (eigenvector D^1/2 1): the scale of features is kept.
  const Eigen::SelfAdjointEigenSolver<DenseF> eig(d);
  CHECK(eig.eigenvalues().maxCoeff() == Approx(1.0f));
}

TEST_CASE("pool_consecutive averages blocks and joins blocks with adjacent vertices", "[gcn][nn]") {
  const nn::BlockPooling p = nn::pool_consecutive(small_graph(), 3);  // blocks {0,1,2} {3,4,5} {6,7}
  const DenseF pool(p.pool);
  REQUIRE(pool.rows() == 3);
  REQUIRE(pool.cols() == 8);
  CHECK(pool(0, 0) == Approx(1.0f / 3));
  CHECK(pool(1, 5) == Approx(1.0f / 3));
  CHECK(pool(2, 6) == Approx(0.5f));
  CHECK(pool(2, 7) == Approx(0.5f));
  CHECK(pool(0, 3) == 0.0f);
  CHECK((pool.rowwise().sum().array() - 1.0f).abs().maxCoeff() < 1e-6f);
  // 2-3 joins blocks 0 and 1; 5-6, 5-7 join blocks 1 and 2; 6-7 stays inside block 2.
  CHECK(p.neighbours == nn::Neighbours{{1}, {0, 2}, {1}});
  CHECK(nn::pool_consecutive(small_graph(), 1).neighbours == small_graph());
  CHECK_THROWS_AS(nn::pool_consecutive(small_graph(), 0), ConfigError);
}

TEST_CASE("restriction_of is U^T with rows normalised, and keeps constants", "[gcn][nn]") {
  const auto assets = gcn_assets();
  const nn::SparseRM& u = level(*assets, 0).upsample;
  const DenseF r(nn::restriction_of(u));
  const DenseF ut = DenseF(u).transpose();
  REQUIRE(r.rows() == vertices_of(*assets, 1));
  REQUIRE(r.cols() == vertices_of(*assets, 0));
  for (Eigen::Index j = 0; j < r.rows(); ++j) {
    CHECK(r.row(j).sum() == Approx(1.0f));
    CHECK((r.row(j) - ut.row(j) / ut.row(j).sum()).cwiseAbs().maxCoeff() < 1e-6f);
  }
  nn::SparseRM unused(3, 2);
  unused.insert(0, 0) = 1;
  unused.insert(1, 0) = 1;
  unused.insert(2, 0) = 1;  // coarse vertex 1 is never used
  CHECK_THROWS_AS(nn::restriction_of(unused), Error);
}

TEST_CASE("SparseOperator applies A and its transpose to every sample of a batch", "[gcn][nn]") {
  nn::BlockPooling p = nn::pool_consecutive(small_graph(), 3);
  const nn::SparseOperator op(p.pool);
  const DenseF a(p.pool);
  const MatrixRM x = random_rows(2 * 8, 4, 1), g = random_rows(2 * 3, 4, 2);
  MatrixRM y(2 * 3, 4), gx(2 * 8, 4);
  op.apply(x, 2, y);
  op.apply_transpose(g, 2, gx);
  for (int b = 0; b < 2; ++b) {
    CHECK((DenseF(y.middleRows(3 * b, 3)) - a * DenseF(x.middleRows(8 * b, 8))).cwiseAbs().maxCoeff() < 1e-6f);
    CHECK((DenseF(gx.middleRows(8 * b, 8)) - a.transpose() * DenseF(g.middleRows(3 * b, 3))).cwiseAbs().maxCoeff() < 1e-6f);
  }
  MatrixRM wrong(2 * 3, 4);
  CHECK_THROWS_AS(op.apply(x, 1, wrong), Error);  // x is two samples' worth
}

TEST_CASE("SparseOperator: every channel count (register blocks and the rest) and strided views", "[gcn][nn]") {
  const nn::SparseRM m = nn::kipf_adjacency(small_graph());
  const nn::SparseOperator op(m);
  const DenseF a(m);
  for (int c : {1, 3, 8, 16, 20, 32, 37, 64, 70, 128}) {
    INFO(c << " channels");
    // x and y are column blocks of wider matrices: rows are strided.
    const MatrixRM wide = random_rows(2 * 8, c + 5, std::uint64_t(c));
    MatrixRM out = MatrixRM::Constant(2 * 8, c + 3, 7.0f);
    op.apply(wide.leftCols(c), 2, out.rightCols(c));
    for (int b = 0; b < 2; ++b) {
      const DenseF expected = a * DenseF(wide.block(8 * b, 0, 8, c));
      CHECK((DenseF(out.block(8 * b, 3, 8, c)) - expected).cwiseAbs().maxCoeff() < 1e-5f);
    }
    CHECK((out.leftCols(3).array() == 7.0f).all());  // nothing written outside the view
  }
}

TEST_CASE("LearnedAggregation: the weights are the matrix values in row-major order, with exact gradients", "[gcn][nn]") {
  struct Owner final : Node {
    ShapeMap setup(const ShapeMap&, const NodeContext&) override { return {}; }
    void forward(const TensorIn&, const TensorOut&) override {}
    void backward(const TensorIn&, const TensorIn&, const TensorIn&, const TensorOut&) override {}
  } owner;
  nn::LearnedAggregation agg(nn::ring_mean(small_graph()));
  agg.create_weights(owner, "a");
  Weight& theta = owner.weights().at("a");
  REQUIRE(theta.value.cols() == 22);
  CHECK(theta.value(0, 0, 0) == Approx(0.5f));  // starts at the neighbourhood mean
  theta.value = random_tensor(1, 1, 22, 3);
  // Row-major with ascending columns: row 0 -> (0,0) (0,1); row 1 -> (1,0) (1,1) (1,2); ...
  DenseF a = DenseF::Zero(8, 8);
  const int cols[][3] = {{0, 1, -1}, {0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, -1}, {5, 6, 7}, {5, 6, 7}, {5, 6, 7}};
  for (int i = 0, k = 0; i < 8; ++i)
    for (int j : cols[i])
      if (j >= 0) a(i, j) = theta.value(0, 0, k++);
  const MatrixRM u = random_rows(3 * 8, 5, 4), g = random_rows(3 * 8, 5, 6);
  MatrixRM y(3 * 8, 5), gu(3 * 8, 5);
  agg.apply(u, 3, y);
  nn::MatRef gu_ref(gu);
  agg.backward(u, g, 3, &gu_ref);
  DenseF expected_grad = DenseF::Zero(8, 8);
  for (int b = 0; b < 3; ++b) {
    const DenseF ub = u.middleRows(8 * b, 8), gb = g.middleRows(8 * b, 8);
    CHECK((DenseF(y.middleRows(8 * b, 8)) - a * ub).cwiseAbs().maxCoeff() < 1e-5f);
    CHECK((DenseF(gu.middleRows(8 * b, 8)) - a.transpose() * gb).cwiseAbs().maxCoeff() < 1e-5f);
    expected_grad += gb * ub.transpose();  // d<g, A u>/dA
  }
  for (int i = 0, k = 0; i < 8; ++i)
    for (int j : cols[i])
      if (j >= 0) CHECK(theta.grad(0, 0, k++) == Approx(expected_grad(i, j)).margin(1e-5));
  // Gradients accumulate.
  agg.backward(u, g, 3, nullptr);
  CHECK(theta.grad(0, 0, 0) == Approx(2 * expected_grad(0, 0)).margin(1e-5));
}

TEST_CASE("GraphConvLayer: y = f(A x W + b) on either side, fixed or learned, and its gradients", "[gcn][nn][gradcheck]") {
  const auto kipf = std::make_shared<const nn::SparseOperator>(nn::kipf_adjacency(small_graph()));
  const nn::SparseRM pattern = nn::ring_mean(small_graph());
  const nn::Activation tanh{nn::ActivationKind::Tanh};
  // in < out aggregates first, in > out transforms first: both orders, both kinds.
  for (int out : {7, 2})
    for (bool learned : {false, true}) {
      INFO("out " << out << (learned ? " learned" : " fixed"));
      ConvNode node([&](int in) {
        return learned ? nn::GraphConvLayer(pattern, in, out, tanh) : nn::GraphConvLayer(kipf, in, out, tanh);
      });
      const Tensor x = random_tensor(2, 8, 4, 8);
      const auto y = run_forward(node, {{"x", x}});
      const DenseF a = learned ? dense_ring_from(pattern, node.weights().at("g_a").value.data())
                               : DenseF(kipf->matrix());
      for (int b = 0; b < 2; ++b) {
        const DenseF expected = activate_dense(
            (a * dense_of(x, b) * weight_of(node, "g_w")).rowwise() + bias_of(node, "g_b"), "tanh");
        CHECK((dense_of(y.at("y"), b) - expected).cwiseAbs().maxCoeff() < 1e-5f);
      }
      const GradCheckReport r = check_node_gradients(node, {{"x", x}}, {"conv", 3});
      INFO(r.str());
      CHECK(r.entries.size() == (learned ? 4u : 3u));
      CHECK(r.ok(1e-2));
    }
}

TEST_CASE("GraphConvLayer counts its multiply-adds and refuses empty sizes", "[gcn][nn]") {
  const nn::SparseRM pattern = nn::ring_mean(small_graph());
  const nn::GraphConvLayer wide(pattern, 3, 10, {}), narrow(pattern, 10, 3, {});
  CHECK(wide.flops_per_sample() == Approx(8.0 * 3 * 10 + 22.0 * 3));
  CHECK(narrow.flops_per_sample() == Approx(8.0 * 10 * 3 + 22.0 * 3));
  CHECK(wide.learned());
  CHECK_THROWS_AS(nn::GraphConvLayer(pattern, 0, 3, {}), ConfigError);
  CHECK_THROWS_AS(nn::GraphConvLayer(std::shared_ptr<const nn::SparseOperator>(), 3, 3, {}), Error);
}
