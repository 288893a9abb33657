// resample_body: the body's offset from its mean read at fixed surface points
// (the assets' encoder resampling), its gradient against finite differences,
// and clear errors without an encoder body.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include <omp.h>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// A unit square of two triangles (0 1 2) and (0 2 3), and three points on it:
// inside the first face, on a corner of the second, inside the second.
Assets square_assets() {
  Assets a = assets_with(grid_garment(2, 0.1));
  a.body.vertices.resize(4, 3);
  a.body.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  a.body.faces.resize(2, 3);
  a.body.faces << 0, 1, 2, 0, 2, 3;
  geometry::BodyResampling& r = a.encoder_resampling;
  r.attachment.face.resize(3);
  r.attachment.face << 0, 1, 1;
  r.attachment.barycentric.resize(3, 3);
  r.attachment.barycentric << 0.2, 0.3, 0.5, 1.0, 0.0, 0.0, 0.25, 0.25, 0.5;
  r.source_faces = a.body.faces;
  r.source_vertices = 4;
  // The mean body at those points, by hand: 0.2 (0,0) + 0.3 (1,0) + 0.5 (1,1); (0,0); 0.25 (0,0) + 0.25 (1,1) + 0.5 (0,1).
  r.resampled_template.resize(3, 3);
  r.resampled_template << 0.8, 0.5, 0.0, 0.0, 0.0, 0.0, 0.25, 0.75, 0.0;
  return a;
}

}  // namespace

TEST_CASE("resample_body reads the body's offset from its mean at the encoder body's points", "[resample_body]") {
  const Assets a = square_assets();
  const NodeContext context{"n", 1, &a};
  auto node = make_node("resample_body");
  CHECK(plugins().get("resample_body").kind == "op");
  Tensor body(2, 4, 3);
  for (int s = 0; s < 2; ++s)
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) body(s, v, k) = static_cast<float>(a.body.vertices(v, k) + 0.1 * (s + 1) * (v + k));
  const auto out = run_forward(*node, {{"x", body}}, context).at("out");
  REQUIRE(out.rows() == 3);
  for (int s = 0; s < 2; ++s)
    for (int k = 0; k < 3; ++k) {
      // The body moved by d(v, k) = 0.1 (s + 1) (v + k): the offsets are those moves, interpolated.
      const double d = 0.1 * (s + 1);
      CHECK(out(s, 0, k) == Approx(d * (0.2 * (0 + k) + 0.3 * (1 + k) + 0.5 * (2 + k))).margin(1e-6));
      CHECK(out(s, 1, k) == Approx(d * (0 + k)).margin(1e-6));
      CHECK(out(s, 2, k) == Approx(d * (0.25 * (0 + k) + 0.25 * (2 + k) + 0.5 * (3 + k))).margin(1e-6));
    }
  // The mean body itself reads as zero.
  Tensor mean(1, 4, 3);
  for (int v = 0; v < 4; ++v)
    for (int k = 0; k < 3; ++k) mean(0, v, k) = static_cast<float>(a.body.vertices(v, k));
  const auto zero = run_forward(*node, {{"x", mean}}, context).at("out");
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) CHECK(zero(0, i, k) == Approx(0.0).margin(1e-7));
}

TEST_CASE("resample_body's backward matches finite differences", "[resample_body][gradcheck]") {
  const Assets a = square_assets();
  auto node = make_node("resample_body");
  const GradCheckReport r = check_node_gradients(*node, {{"x", random_tensor(2, 4, 3, 5)}}, {"n", 1, &a});
  INFO(r.str());
  CHECK_FALSE(r.entries.empty());
  CHECK(r.ok(1e-2));
}

TEST_CASE("resample_body gives the same bits on one thread and two", "[resample_body]") {
  const Assets a = square_assets();
  const NodeContext context{"n", 1, &a};
  const Tensor x = random_tensor(6, 4, 3, 8), g = random_tensor(6, 3, 3, 9);
  auto run = [&](int threads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    auto node = make_node("resample_body");
    auto out = run_forward(*node, {{"x", x}}, context);
    Tensor gx(6, 4, 3);
    node->backward({{"x", &x}}, {{"out", &out.at("out")}}, {{"out", &g}}, {{"x", &gx}});
    omp_set_num_threads(before);
    return std::make_pair(out.at("out"), gx);
  };
  const auto one = run(1), two = run(2);
  CHECK(one.first.vec() == two.first.vec());
  CHECK(one.second.vec() == two.second.vec());
  CHECK(one.second.vec().cwiseAbs().maxCoeff() > 0);
}

TEST_CASE("resample_body needs assets with an encoder body and the body's vertex count", "[resample_body]") {
  auto node = make_node("resample_body");
  CHECK_THROWS_WITH(node->setup({{"x", {4, 3}}}, {}), Catch::Contains("assets"));
  Assets plain = square_assets();
  plain.encoder_resampling = {};
  CHECK_THROWS_WITH(node->setup({{"x", {4, 3}}}, {"n", 1, &plain}), Catch::Contains("--encoder-body"));
  const Assets a = square_assets();
  CHECK_THROWS_WITH(node->setup({{"x", {5, 3}}}, {"n", 1, &a}), Catch::Contains("must be [4, 3]"));
}

TEST_CASE("with an encoder body, gather refuses the body's own rows for the correspondences", "[resample_body][gather]") {
  Assets a = square_assets();
  a.correspondence = {0, 2, 1, 0};  // indices of the three encoder points
  auto gather = make_node("gather");
  CHECK_THROWS_WITH(gather->setup({{"x", {4, 3}}}, {"n", 1, &a}),
                    Catch::Contains("encoder body's 3 points") && Catch::Contains("resample_body"));
  auto ok = make_node("gather");
  CHECK(ok->setup({{"x", {3, 8}}}, {"n", 1, &a}).at("out").rows == 4);
}
