// spectral_loss (the seed's L_s, eq. 6.13): coefficients by hand on a
// four-vertex basis, the choice of k, batches, finite differences on the
// coarse T-shirt's eigenbasis, errors.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// Two orthonormal "eigenvectors" on four vertices: constant and alternating.
Assets four_vertex_basis() {
  Assets a;
  a.eigenvectors.resize(4, 2);
  a.eigenvectors << 0.5f, 0.5f, 0.5f, -0.5f, 0.5f, 0.5f, 0.5f, -0.5f;
  a.eigenvalues = Eigen::Vector2d(0.0, 1.0);
  return a;
}

}  // namespace

TEST_CASE("spectral_loss loads as a loss and checks its basis and shapes", "[losses][spectral_loss]") {
  CHECK(plugins().get("spectral_loss").kind == "loss");
  const Assets assets = four_vertex_basis();
  auto node = make_node("spectral_loss");
  CHECK_THROWS_WITH(node->setup({{"pred", {4, 3}}, {"target", {4, 3}}}, {}), Catch::Contains("eigenvectors"));
  CHECK(node->setup({{"pred", {4, 3}}, {"target", {4, 3}}}, {"s", 0, &assets}).at("loss") == Shape{1, 1});
  CHECK_THROWS_WITH(node->setup({{"pred", {5, 3}}, {"target", {5, 3}}}, {"s", 0, &assets}), Catch::Contains("[4, 3]"));
  CHECK_THROWS_AS(node->setup({{"pred", {4, 3}}, {"target", {4, 1}}}, {"s", 0, &assets}), ConfigError);
  auto too_many = make_node("spectral_loss", "{k: 3}");
  CHECK_THROWS_WITH(too_many->setup({{"pred", {4, 3}}, {"target", {4, 3}}}, {"s", 0, &assets}),
                    Catch::Contains("k is 3") && Catch::Contains("2 eigenvectors"));
  CHECK_THROWS_WITH(make_node("spectral_loss", "{k: -1}"), Catch::Contains("k"));
}

TEST_CASE("spectral_loss is the L1 of the error's spectral coefficients", "[losses][spectral_loss]") {
  const Assets assets = four_vertex_basis();
  const Eigen::MatrixX3d y = rows3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  auto run = [&](const std::string& yaml, const std::vector<Eigen::MatrixX3d>& deltas) {
    std::vector<Eigen::MatrixX3d> x, t;
    for (const auto& d : deltas) x.push_back(y + d), t.push_back(y);
    auto node = make_node("spectral_loss", yaml);
    return run_forward(*node, {{"pred", tensor_of(x)}, {"target", tensor_of(t)}}, {"s", 0, &assets}).at("loss");
  };
  // Vertex 0 off by (1, 0, 0): coefficients (0.5, 0, 0) and (0.5, 0, 0).
  Eigen::MatrixX3d one = Eigen::MatrixX3d::Zero(4, 3);
  one(0, 0) = 1.0;
  // Vertices 0 and 1 off by (1, 0, 0): (1, 0, 0) on the constant vector, 0 on the alternating one.
  Eigen::MatrixX3d pair = one;
  pair(1, 0) = 1.0;
  // Every vertex off by (0, 2, 0): (0, 4, 0) on the constant vector.
  const Eigen::MatrixX3d shift = Eigen::MatrixX3d::Zero(4, 3).rowwise() + Eigen::RowVector3d(0, 2, 0);
  const Tensor sums = run("{reduction: sum}", {one, pair, shift});
  CHECK(sums(0, 0, 0) == Approx(1.0).epsilon(1e-6));
  CHECK(sums(1, 0, 0) == Approx(1.0).epsilon(1e-6));
  CHECK(sums(2, 0, 0) == Approx(4.0).epsilon(1e-6));
  const Tensor means = run("{}", {one, shift});
  CHECK(means(0, 0, 0) == Approx(0.5).epsilon(1e-6));
  CHECK(means(1, 0, 0) == Approx(2.0).epsilon(1e-6));
  // k = 1 keeps the constant vector only: vertex 0's error weighs 0.5, the alternating part is not seen.
  Eigen::MatrixX3d alternating = Eigen::MatrixX3d::Zero(4, 3);
  alternating.col(2) << 1, -1, 1, -1;
  const Tensor low = run("{k: 1, reduction: sum}", {one, alternating});
  CHECK(low(0, 0, 0) == Approx(0.5).epsilon(1e-6));
  CHECK(low(1, 0, 0) == Approx(0.0).margin(1e-6));
  CHECK(run("{reduction: sum}", {alternating})(0, 0, 0) == Approx(2.0).epsilon(1e-6));
}

TEST_CASE("spectral_loss backward matches finite differences on the T-shirt's eigenbasis", "[losses][spectral_loss][gradcheck]") {
  const Assets& assets = coarse_tshirt();
  const int n = assets.garment->mesh.num_vertices();
  Tensor target(2, n, 3), pred(2, n, 3);
  const Tensor noise = random_tensor(2, n, 3, 41, 0.05f);
  for (int b = 0; b < 2; ++b) {
    target.mat(b) = assets.garment->mesh.vertices.cast<float>();
    pred.mat(b) = target.mat(b) + noise.mat(b);
  }
  auto node = make_node("spectral_loss", "{reduction: sum}");
  const GradCheckReport r = check_node_gradients(*node, {{"pred", pred}, {"target", target}}, {"s", 0, &assets}, kink_safe());
  INFO(r.str());
  CHECK(r.ok(1e-2));
}
