// The parts of the TailorNet-style baseline (graphs/baselines/tailornet_*.yaml):
// spectral_lowpass (the low-frequency target), anchor_blend (the anchors'
// high frequencies) and push_out (its post-processing).
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/push_out.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/strain_limit.hpp>
#include <drape/garment_grading.hpp>
#include <drape/garment_sizes.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("spectral_lowpass projects on the first k eigenvectors, and its gradient checks", "[gcn][tailornet]") {
  const auto assets = gcn_assets();  // 6 orthonormal eigenvectors
  const int ng = vertices_of(*assets, 0);
  auto node = make_node("spectral_lowpass", "{k: 3}");
  const Tensor x = random_tensor(2, ng, 3, 5);
  const auto out = run_forward(*node, {{"x", x}}, {"low", 1, assets.get()});
  const DenseF v = assets->eigenvectors.leftCols(3);
  for (int b = 0; b < 2; ++b) {
    CHECK((dense_of(out.at("out"), b) - v * (v.transpose() * dense_of(x, b))).cwiseAbs().maxCoeff() < 1e-5f);
    // A projection: applying it again changes nothing.
    const auto twice = run_forward(*node, {{"x", out.at("out")}}, {"low", 1, assets.get()});
    CHECK((dense_of(twice.at("out"), b) - dense_of(out.at("out"), b)).cwiseAbs().maxCoeff() < 1e-5f);
  }
  const GradCheckReport r = check_node_gradients(*make_node("spectral_lowpass", "{k: 4}"), {{"x", x}}, {"low", 1, assets.get()});
  INFO(r.str());
  CHECK(r.ok(1e-2));
  CHECK_THROWS_WITH(make_node("spectral_lowpass")->setup({{"x", {ng + 1, 3}}}, {"low", 1, assets.get()}), Catch::Contains("must be"));
}

TEST_CASE("anchor_blend: inverse-distance weights over learnt anchors, and its gradient checks", "[gcn][tailornet]") {
  const auto assets = gcn_assets();
  const int ng = vertices_of(*assets, 0);
  auto node = make_node("anchor_blend", "{anchors: 3, power: 2}");
  const Tensor x = random_tensor(2, 1, 4, 8);
  node->setup({{"x", {1, 4}}}, {"hf", 1, assets.get()});
  randomise_weights(*node, 4, 0.5f);
  const auto out = run_forward(*node, {{"x", x}}, {"hf", 1, assets.get()});
  const DenseF codes = weight_of(*node, "codes"), anchors = weight_of(*node, "anchors");
  for (int b = 0; b < 2; ++b) {
    Eigen::RowVectorXd u(3);
    for (int k = 0; k < 3; ++k) {
      double d = 1e-6;
      for (int j = 0; j < 4; ++j) d += std::pow(double(x.data()[4 * b + j]) - double(codes(k, j)), 2);
      u(k) = 1.0 / d;  // p = 2
    }
    const Eigen::RowVectorXd w = u / u.sum();
    CHECK((dense_of(out.at("weights"), b).cast<double>() - w).cwiseAbs().maxCoeff() < 1e-5);
    const Eigen::RowVectorXf field = w.cast<float>() * anchors;
    CHECK((dense_of(out.at("out"), b) - Eigen::Map<const DenseF>(field.data(), 3, ng).transpose()).cwiseAbs().maxCoeff() < 1e-5f);
  }
  // A body on an anchor takes that anchor's field (the weights stay finite).
  Tensor on(1, 1, 4);
  on.mat(0) = codes.row(1);
  const auto at = run_forward(*node, {{"x", on}}, {"hf", 1, assets.get()});
  CHECK(dense_of(at.at("weights"), 0)(1) > 0.999f);
  auto fresh = make_node("anchor_blend", "{anchors: 3, power: 2}");
  const GradCheckReport r = check_node_gradients(*fresh, {{"x", x}}, {"hf", 2, assets.get()});
  INFO(r.str());
  CHECK(r.entries.size() == 1 + fresh->weights().size());
  CHECK(r.ok(1e-2));
}

namespace {

// A closed unit cube centred at the origin, faces counter-clockwise seen from outside.
std::shared_ptr<Assets> cube_body_assets() {
  auto a = gcn_assets();
  Mesh& cube = a->body;
  cube.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) cube.vertices.row(i) << (i & 1 ? 0.5 : -0.5), (i & 2 ? 0.5 : -0.5), (i & 4 ? 0.5 : -0.5);
  cube.faces.resize(12, 3);
  cube.faces << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  cube.uv.resize(0, 2);
  cube.uv_faces.resize(0, 3);
  return a;
}

}  // namespace

TEST_CASE("push_out moves vertices inside the body to epsilon outside and leaves the rest", "[gcn][tailornet]") {
  const auto assets = cube_body_assets();
  Tensor body(1, 8, 3);
  body.mat(0) = assets->body.vertices.cast<float>();
  Tensor x(1, 4, 3);
  x.mat(0) << 0.0f, 0.0f, 0.4f,   // inside, 0.1 below the top face z = 0.5
      0.3f, 0.0f, 0.0f,           // inside, nearest the x = 0.5 face
      0.0f, 0.0f, 0.501f,         // outside but closer than epsilon
      0.0f, 0.9f, 0.0f;           // well outside
  auto node = make_node("push_out", "{epsilon: 0.01, edges: false, untangle: false}");  // four loose vertices, not the garment
  const auto out = run_forward(*node, {{"x", x}, {"body", body}}, {"post", 1, assets.get()});
  const DenseF y = dense_of(out.at("out"), 0);
  CHECK((y.row(0) - Eigen::RowVector3f(0, 0, 0.51f)).norm() < 1e-5f);
  CHECK((y.row(1) - Eigen::RowVector3f(0.51f, 0, 0)).norm() < 1e-5f);
  CHECK((y.row(2) - Eigen::RowVector3f(0, 0, 0.51f)).norm() < 1e-5f);
  CHECK(y.row(3) == x.mat(0).row(3));
  const geometry::BodySurface surface(assets->body.vertices, assets->body.faces);
  CHECK(surface.signed_distances(y.cast<double>()).minCoeff() >= 0.01 - 1e-6);

  auto off = make_node("push_out", "{epsilon: 0.01, enabled: false, edges: false, untangle: false}");
  CHECK(dense_of(run_forward(*off, {{"x", x}, {"body", body}}, {"post", 1, assets.get()}).at("out"), 0) == DenseF(x.mat(0)));
  // Straight-through backward for the garment.
  Tensor g(1, 4, 3);
  g.vec().setLinSpaced(-1, 1);
  Tensor gx(1, 4, 3);
  node->backward({{"x", &x}, {"body", &body}}, {}, {{"out", &g}}, {{"x", &gx}});
  CHECK(gx.vec() == g.vec());
}

TEST_CASE("push_out answers every body of a batch and of later calls by that body alone", "[gcn][tailornet]") {
  // The node keeps one closest-point surface and refits it to each body: a
  // second body (the cube moved and grown) and a later call on the first must
  // come out as each body's own push-out (geometry::push_out on a surface
  // built for it), not the first body's.
  const auto assets = cube_body_assets();
  Tensor body(2, 8, 3);
  body.mat(0) = assets->body.vertices.cast<float>();
  body.mat(1) = ((assets->body.vertices * 1.6).rowwise() + Eigen::RowVector3d(0.2, -0.1, 0.3)).cast<float>();
  Tensor x(2, 3, 3);
  x.mat(0) << 0.0f, 0.0f, 0.4f, 0.7f, 0.0f, 0.0f, 0.0f, 0.3f, 0.1f;
  x.mat(1) = x.mat(0);
  auto node = make_node("push_out", "{epsilon: 0.01, edges: false, untangle: false}");
  const auto expected = [&](int b) {
    const geometry::BodySurface own(body.mat(b).cast<double>(), assets->body.faces);
    Eigen::MatrixX3d p = x.mat(b).cast<double>();
    geometry::push_out(own, p, 0.01);
    return DenseF(p.cast<float>());
  };
  for (int call = 0; call < 2; ++call) {
    const auto out = run_forward(*node, {{"x", x}, {"body", body}}, {"post", 2, assets.get()});
    for (int b = 0; b < 2; ++b) CHECK((dense_of(out.at("out"), b) - expected(b)).cwiseAbs().maxCoeff() < 1e-6f);
  }
  CHECK((expected(0) - expected(1)).cwiseAbs().maxCoeff() > 0.05f);  // the two bodies push differently
}

TEST_CASE("push_out with edges (the default) lifts the bound garment's edges as geometry::push_out does", "[gcn][tailornet]") {
  // (and the faces a peak of the body rises through: the cube's corners)
  // The garment of the test assets shrunk onto the unit cube's surface, so
  // vertices fall inside and edges run through it, on two bodies (the cube,
  // and the cube moved and grown) in one batch, twice: the node keeps the
  // last body's surface (normals left to the queries) and closest faces, and
  // every answer must still be that body's own push-out with the garment's
  // edges, on a surface built for it with no hints. It refuses a mesh of
  // another size.
  const auto assets = cube_body_assets();
  const Mesh& garment = assets->garment->mesh;
  const Eigen::RowVector3d centre = garment.vertices.colwise().mean();
  Eigen::MatrixX3d start = garment.vertices.rowwise() - centre;
  start *= 0.55 / start.rowwise().norm().maxCoeff();
  Tensor body(2, 8, 3), x(2, garment.num_vertices(), 3);
  body.mat(0) = assets->body.vertices.cast<float>();
  body.mat(1) = ((assets->body.vertices * 1.3).rowwise() + Eigen::RowVector3d(0.05, -0.02, 0.03)).cast<float>();
  x.mat(0) = start.cast<float>();
  x.mat(1) = x.mat(0);
  const std::vector<std::array<int, 2>> edges = geometry::edge_list(garment.faces);
  geometry::PushOutOptions options;
  options.margin = 0.01;
  options.edges = &edges;
  options.faces = &garment.faces;  // as the node: faces a corner of the cube rises through lifted too
  std::vector<DenseF> expected;
  int peaks = 0;
  for (int b = 0; b < 2; ++b) {
    const geometry::BodySurface own(body.mat(b).cast<double>(), assets->body.faces);
    Eigen::MatrixX3d p = x.mat(b).cast<double>();
    const geometry::PushOutReport report = geometry::push_out(own, p, options);
    CHECK(report.edges_searched > 0);
    peaks += report.peaks_cleared;
    expected.push_back(p.cast<float>());
  }
  CHECK(peaks > 0);
  CHECK((expected[0] - expected[1]).cwiseAbs().maxCoeff() > 0.01f);  // the two bodies push differently
  auto node = make_node("push_out", "{epsilon: 0.01, untangle: false}");
  for (int call = 0; call < 2; ++call) {
    const auto out = run_forward(*node, {{"x", x}, {"body", body}}, {"post", 2, assets.get()});
    for (int b = 0; b < 2; ++b) {
      INFO("call " << call << ", body " << b);
      CHECK((dense_of(out.at("out"), b) - expected[static_cast<std::size_t>(b)]).cwiseAbs().maxCoeff() < 1e-6f);
    }
  }
  // With untangle (the default) the shrunk garment, pressed onto the cube's
  // faces through itself, crosses itself less (self_edge_crossings: the
  // measurement's grid, not the untangle's own search) and still keeps every
  // vertex out of the body.
  auto untangling = make_node("push_out", "{epsilon: 0.01}");
  const auto out = run_forward(*untangling, {{"x", x}, {"body", body}}, {"post", 2, assets.get()});
  for (int b = 0; b < 2; ++b) {
    INFO("body " << b);
    const Eigen::MatrixX3d pushed = expected[static_cast<std::size_t>(b)].cast<double>();
    const Eigen::MatrixX3d untangled = dense_of(out.at("out"), b).cast<double>();
    const auto before = geometry::self_edge_crossings(pushed, garment.faces, 100000).size();
    const auto after = geometry::self_edge_crossings(untangled, garment.faces, 100000).size();
    INFO("crossings " << before << " -> " << after);
    CHECK(before > 0);
    CHECK(after < before);
    const geometry::BodySurface own(body.mat(b).cast<double>(), assets->body.faces);
    CHECK(own.signed_distances(untangled).minCoeff() > 0.0049);
  }
  CHECK_THROWS_WITH(make_node("push_out", "{epsilon: 0.01}")->setup({{"x", {4, 3}}, {"body", {8, 3}}}, {"post", 1, assets.get()}),
                    Catch::Contains("edges: false"));
}

TEST_CASE("push_out's strain limit holds each edge to (1 + s) times the rest length of the garment's own grade", "[gcn][tailornet][strain_limit]") {
  // The test garment far from the cube (the push-out moves nothing) with
  // one vertex torn half a metre off: the node's answer is limit_strain's
  // (as the node calls it: slack 0.025) against the rest lengths of the
  // garment of the input grade: the template's without one; the model's
  // size of that grade (NodeContext::garment_sizes: here the template's
  // pattern doubled, a size of grade 2); else the template graded by it.
  const auto assets = cube_body_assets();
  const Mesh& garment = assets->garment->mesh;
  const auto edges = geometry::edge_list(garment.faces);
  Tensor body(1, 8, 3);
  body.mat(0) = assets->body.vertices.cast<float>();
  Eigen::MatrixX3d far = garment.vertices.rowwise() + Eigen::RowVector3d(20.0, 0.0, 0.0);
  far.row(3) += Eigen::RowVector3d(0.0, 0.0, 0.5);
  Tensor x(1, garment.num_vertices(), 3);
  x.mat(0) = far.cast<float>();
  Mesh doubled = garment;
  doubled.uv *= 2.0;
  // The model's sizes are built when a body first wears one: counted here.
  const auto sizes = std::make_shared<const GarmentSizes>(std::vector<double>{2.0}, [&](std::size_t) { return doubled; });
  NodeContext context{"post", 1, assets.get(), sizes};
  const auto expected = [&](const std::vector<double>& rest) {
    Eigen::MatrixX3d p = x.mat(0).cast<double>();
    geometry::limit_strain(p, edges, rest, 0.3, 50, 0.025);
    return DenseF(p.cast<float>());
  };
  const std::vector<double> template_rest = geometry::material_edge_lengths(garment, edges);
  REQUIRE(geometry::worst_strain(far, edges, template_rest) > 1.0);
  auto node = make_node("push_out", "{epsilon: 0.01, untangle: false, strain_limit: 0.3}");
  const auto plain = run_forward(*node, {{"x", x}, {"body", body}}, context);
  const DenseF limited = dense_of(plain.at("out"), 0);
  CHECK((limited - expected(template_rest)).cwiseAbs().maxCoeff() < 1e-6f);
  CHECK(geometry::worst_strain(limited.cast<double>(), edges, template_rest) <= 0.3 + 0.025 + 1e-5);
  CHECK(sizes->built() == 0);  // no body wore size 2 yet
  for (const double g : {2.0, 1.3}) {
    INFO("grade " << g);
    Tensor grade(1, 1, 1, static_cast<float>(g));
    auto graded = make_node("push_out", "{epsilon: 0.01, untangle: false, strain_limit: 0.3}");
    const auto out = run_forward(*graded, {{"x", x}, {"body", body}, {"grade", grade}}, context);
    Mesh own = garment;
    if (g == 2.0) own = doubled;
    else grade_material(own, g);
    const std::vector<double> rest = geometry::material_edge_lengths(own, edges);
    CHECK((dense_of(out.at("out"), 0) - expected(rest)).cwiseAbs().maxCoeff() < 1e-6f);
    CHECK((dense_of(out.at("out"), 0) - limited).cwiseAbs().maxCoeff() > 1e-3f);  // not the template's
    CHECK(sizes->built() == 1);  // size 2, once; grade 1.3 is not a size of the model
  }
  CHECK_THROWS_AS(sizes->material(1), std::out_of_range);
  // A garment without a material space is refused at setup, before any body.
  auto bare = cube_body_assets();
  auto without_uv = std::make_shared<Garment>(*bare->garment);
  without_uv->mesh.uv.resize(0, 2);
  bare->garment = without_uv;
  CHECK_THROWS_WITH(make_node("push_out", "{untangle: false, strain_limit: 0.3}")
                        ->setup({{"x", {garment.num_vertices(), 3}}, {"body", {8, 3}}}, {"post", 1, bare.get(), sizes}),
                    Catch::Contains("UVs"));
  CHECK(sizes->built() == 1);
  // Off (the default): the torn edge stays.
  auto off = make_node("push_out", "{epsilon: 0.01, untangle: false}");
  CHECK(dense_of(run_forward(*off, {{"x", x}, {"body", body}}, context).at("out"), 0) == DenseF(x.mat(0)));
  CHECK_THROWS_WITH(make_node("push_out", "{strain_limit: 0.3}")->setup({{"x", {garment.num_vertices(), 3}}, {"body", {8, 3}}, {"grade", {2, 1}}}, context),
                    Catch::Contains("input 'grade' must be [1, 1]"));
}

TEST_CASE("concat puts a one-row flag beside every row, and its gradient checks", "[gcn][sizes]") {
  const auto assets = gcn_assets();
  auto node = make_node("concat");
  const Tensor a = random_tensor(2, 5, 3, 1), b = random_tensor(2, 1, 1, 2);
  const auto out = run_forward(*node, {{"a", a}, {"b", b}}, {"cat", 1, assets.get()});
  for (int s = 0; s < 2; ++s) {
    CHECK(dense_of(out.at("out"), s).leftCols(3) == dense_of(a, s));
    for (int r = 0; r < 5; ++r) CHECK(out.at("out")(s, r, 3) == b(s, 0, 0));
  }
  for (const auto& [rows_b, cols_b] : std::vector<std::pair<int, int>>{{1, 2}, {5, 2}}) {
    INFO("b " << rows_b << " x " << cols_b);
    auto fresh = make_node("concat");
    const GradCheckReport r = check_node_gradients(*fresh, {{"a", a}, {"b", random_tensor(2, rows_b, cols_b, 3)}}, {"cat", 1, assets.get()});
    INFO(r.str());
    CHECK(r.ok(1e-2));
  }
  CHECK_THROWS_WITH(make_node("concat")->setup({{"a", {5, 3}}, {"b", {2, 1}}}, {"cat", 1, assets.get()}), Catch::Contains("rows or one"));
}
