// uvcnn: the UV image round trip (rasterise then sample) with identity
// convolutions, charts kept apart in their tiles, a convolution by hand,
// finite differences through rasterisation, convolutions and sampling, errors.
#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include <algorithm>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// Two 3x3-vertex panels sewn along one row: panel A is vertices 0..8 (row i,
// column j -> 3i + j); panel B reuses A's top row 6, 7, 8 and owns 9..14. Each
// panel has its own UV chart and both charts cover the same UV square
// [0, 0.2]^2, so only a per-chart layout keeps them apart.
std::shared_ptr<Garment> two_panels() {
  auto g = std::make_shared<Garment>();
  Mesh& m = g->mesh;
  m.vertices.resize(15, 3);
  m.uv.resize(18, 2);
  auto b_vertex = [](int i, int j) { return i == 2 ? 6 + j : 9 + 3 * i + j; };
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      m.vertices.row(3 * i + j) << 0.1 * j, 0.1 * i, 0.05;
      if (i < 2) m.vertices.row(b_vertex(i, j)) << 0.1 * j, 0.1 * i, -0.05;
      m.uv.row(3 * i + j) << 0.1 * j, 0.1 * i;
      m.uv.row(9 + 3 * i + j) << 0.1 * j, 0.1 * i;
    }
  m.faces.resize(16, 3);
  m.uv_faces.resize(16, 3);
  int f = 0;
  for (int panel = 0; panel < 2; ++panel)
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        auto v = [&](int r, int c) { return panel == 0 ? 3 * r + c : b_vertex(r, c); };
        auto t = [&](int r, int c) { return 9 * panel + 3 * r + c; };
        m.faces.row(f) << v(i, j), v(i, j + 1), v(i + 1, j + 1);
        m.uv_faces.row(f++) << t(i, j), t(i, j + 1), t(i + 1, j + 1);
        m.faces.row(f) << v(i, j), v(i + 1, j + 1), v(i + 1, j);
        m.uv_faces.row(f++) << t(i, j), t(i + 1, j + 1), t(i + 1, j);
      }
  g->materials.emplace_back();
  return g;
}

// Sets every convolution of a `channels: []` uvcnn with 3 input channels to the identity.
void identity(Node& node, int kernel) {
  auto w = node.weights().at("conv0_w").value.mat(0);
  w.setZero();
  const int centre = (kernel * kernel) / 2;
  for (int c = 0; c < 3; ++c) w(centre * 3 + c, c) = 1.0f;
}

Tensor round_trip(const Assets& assets, const Eigen::MatrixX3d& x, int resolution, int kernel = 3) {
  auto node = make_node("uvcnn", "{channels: [], kernel: " + std::to_string(kernel) +
                                     ", resolution: " + std::to_string(resolution) + "}");
  return run_forward(*node, {{"x", tensor_of(x)}}, {"u", 0, &assets}, [&](Node& n) { identity(n, kernel); }).at("out");
}

}  // namespace

TEST_CASE("uvcnn: shapes, weights and errors", "[decoders][uvcnn]") {
  CHECK(plugins().get("uvcnn").kind == "decoder");
  const Assets assets = assets_with(two_panels());
  auto node = make_node("uvcnn", "{resolution: 16, channels: [8, 4]}");
  CHECK_THROWS_WITH(node->setup({{"x", {15, 5}}}, {}), Catch::Contains("no garment template"));
  CHECK(node->setup({{"x", {15, 5}}}, {"u", 0, &assets}).at("out") == Shape{15, 3});
  CHECK(node->weights().at("conv0_w").value.shape() == Shape{9 * 5, 8});
  CHECK(node->weights().at("conv1_w").value.shape() == Shape{9 * 8, 4});
  CHECK(node->weights().at("conv2_w").value.shape() == Shape{9 * 4, 3});
  CHECK(node->flops_per_sample() > 256.0 * (45 * 8 + 72 * 4 + 36 * 3));
  CHECK_THROWS_WITH(node->setup({{"x", {14, 5}}}, {"u", 0, &assets}), Catch::Contains("[15, C]"));
  auto no_uv = two_panels();
  no_uv->mesh.uv.resize(0, 2);
  const Assets bare = assets_with(no_uv);
  CHECK_THROWS_WITH(node->setup({{"x", {15, 5}}}, {"u", 0, &bare}), Catch::Contains("no UV"));
  CHECK_THROWS_WITH(make_node("uvcnn", "{kernel: 4}"), Catch::Contains("odd"));
  CHECK_THROWS_WITH(make_node("uvcnn", "{resolution: 4}"), Catch::Contains("resolution"));
}

TEST_CASE("uvcnn: rasterise then sample reproduces constants and keeps charts apart", "[decoders][uvcnn]") {
  const Assets assets = assets_with(two_panels());
  // A constant field comes back exactly: every pixel a vertex samples is one its own splat reached.
  const Eigen::MatrixX3d constant = Eigen::MatrixX3d::Constant(15, 3, 0.7);
  for (int res : {8, 16, 64}) {
    const Tensor out = round_trip(assets, constant, res);
    CHECK((out.mat(0).cast<double>() - constant).cwiseAbs().maxCoeff() < 1e-6);
  }
  // Panel B's own vertices at 1, the rest at 0. The charts overlap in UV, so a single
  // layout would put vertex 0 and vertex 9 on the same pixels; in separate tiles, at 32
  // pixels (vertices ~6 pixels apart) every pixel a vertex samples holds that vertex
  // alone and the round trip is exact, seam vertices included.
  Eigen::MatrixX3d panel = Eigen::MatrixX3d::Zero(15, 3);
  panel.bottomRows(6).setOnes();
  const Tensor out = round_trip(assets, panel, 32);
  CHECK((out.mat(0).cast<double>() - panel).cwiseAbs().maxCoeff() < 1e-6);
}

TEST_CASE("uvcnn: a smooth field survives the round trip on the T-shirt", "[decoders][uvcnn]") {
  const Assets& assets = coarse_tshirt();
  const Mesh& mesh = assets.garment->mesh;
  const Eigen::MatrixX3d constant = Eigen::MatrixX3d::Constant(mesh.num_vertices(), 3, -1.25);
  CHECK((round_trip(assets, constant, 64).mat(0).cast<double>() - constant).cwiseAbs().maxCoeff() < 1e-5);
  // The garment's own positions are smooth over each panel: they come back within a
  // pixel (41 pixels per meter at 64: the two T-shaped panels of ~1.5 x 0.7 m stacked).
  const Tensor out = round_trip(assets, mesh.vertices, 64);
  const Eigen::VectorXd error = (out.mat(0).cast<double>() - mesh.vertices).rowwise().norm();
  std::vector<double> sorted(error.data(), error.data() + error.size());
  std::sort(sorted.begin(), sorted.end());
  INFO("median " << sorted[sorted.size() / 2] << ", 90% " << sorted[sorted.size() * 9 / 10] << ", max " << sorted.back());
  CHECK(sorted[sorted.size() / 2] < 0.005);
  CHECK(sorted[sorted.size() * 9 / 10] < 0.01);
  CHECK(sorted.back() < 1.0 / 41);
}

TEST_CASE("uvcnn: one convolution by hand", "[decoders][uvcnn]") {
  // A kernel that copies the pixel to the left of each pixel (zero padding): a constant
  // field comes back unchanged except where that pixel is background.
  const Assets assets = assets_with(two_panels());
  auto node = make_node("uvcnn", "{channels: [], resolution: 32}");
  const Eigen::MatrixX3d constant = Eigen::MatrixX3d::Constant(15, 3, 2.0);
  const auto out = run_forward(*node, {{"x", tensor_of(constant)}}, {"u", 0, &assets}, [](Node& n) {
    auto w = n.weights().at("conv0_w").value.mat(0);
    w.setZero();
    for (int c = 0; c < 3; ++c) w((1 * 3 + 0) * 3 + c, c) = 1.0f;  // tap (dy = 0, dx = -1)
    n.weights().at("conv0_b").value.mat(0) << 0.0f, 1.0f, 0.0f;
  });
  // Two charts of 0.2 m side by side in 16x32-pixel tiles: 65 pixels per meter, vertices
  // 6.5 pixels apart. Vertex 5 (u = 0.2, v = 0.1) samples pixels whose left neighbours lie
  // inside panel A: 2, and 2 + 1 with the bias. Vertex 3 (u = 0) sits on its pixel column's
  // centre, and the column left of it is background: 0.
  CHECK(out.at("out")(0, 5, 0) == Approx(2.0).epsilon(1e-6));
  CHECK(out.at("out")(0, 5, 1) == Approx(3.0).epsilon(1e-6));
  CHECK(out.at("out")(0, 3, 0) == Approx(0.0).margin(1e-6));
  CHECK(out.at("out")(0, 3, 1) == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("uvcnn backward matches finite differences through rasterisation and sampling", "[decoders][uvcnn][gradcheck]") {
  const Assets assets = assets_with(two_panels());
  const Tensor x = random_tensor(2, 15, 2, 9);
  // Background pixels hold 0, so with the zero initial biases their first
  // pre-activations sit exactly on a ReLU kink, where differences measure the mean of
  // two slopes: the checks use tanh and no activation (the same wiring).
  for (const char* yaml : {"{resolution: 10, channels: [3], activation: tanh}",
                           "{resolution: 12, channels: [4, 2], activation: none}"}) {
    auto node = make_node("uvcnn", yaml);
    const GradCheckReport r = check_node_gradients(*node, {{"x", x}}, {"u", 3, &assets}, kink_safe());
    INFO(yaml << "\n" << r.str());
    CHECK(r.ok(1e-2));
  }
}

TEST_CASE("uvcnn backward matches finite differences on the T-shirt at 64x64", "[decoders][uvcnn][gradcheck]") {
  const Assets& assets = coarse_tshirt();
  const Tensor x = random_tensor(1, assets.garment->mesh.num_vertices(), 2, 19);
  auto node = make_node("uvcnn", "{resolution: 64, channels: [4], activation: tanh}");
  const GradCheckReport r = check_node_gradients(*node, {{"x", x}}, {"u", 5, &assets});
  INFO(r.str());
  CHECK(r.ok(1e-2));
}
