// laplacian (the seed's L_l, eq. 6.12): a two-level hierarchy by hand on a
// 3x3 grid, the restriction to coarse levels, finite differences on the
// coarse T-shirt's four levels, errors.
#include <drape/geometry/laplacian.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// Level 0: the 3x3 grid (vertex i*3 + j). Level 1: its four corners 0, 2, 6, 8
// as two triangles (0, 1, 3), (0, 3, 2) in level-1 numbering.
Assets two_level_grid() {
  Assets a = assets_with(grid_garment(3, 1.0));
  geometry::HierarchyLevel fine, coarse;
  fine.mesh = a.garment->mesh;
  fine.fine_index = Eigen::VectorXi::LinSpaced(9, 0, 8);
  coarse.mesh.vertices = fine.mesh.vertices(std::vector<int>{0, 2, 6, 8}, Eigen::all);
  coarse.mesh.faces.resize(2, 3);
  coarse.mesh.faces << 0, 1, 3, 0, 3, 2;
  coarse.fine_index.resize(4);
  coarse.fine_index << 0, 2, 6, 8;
  a.hierarchy.levels = {fine, coarse};
  for (const auto& level : a.hierarchy.levels)
    a.laplacians.push_back(geometry::graph_laplacian(level.mesh.faces, level.mesh.num_vertices()).cast<float>());
  return a;
}

float loss_of(const Assets& assets, const Eigen::MatrixX3d& delta, const std::string& yaml) {
  auto node = make_node("laplacian", yaml);
  const Eigen::MatrixX3d y = assets.garment->mesh.vertices;
  return run_forward(*node, {{"pred", tensor_of(Eigen::MatrixX3d(y + delta))}, {"target", tensor_of(y)}}, {"l", 0, &assets})
      .at("loss")(0, 0, 0);
}

}  // namespace

TEST_CASE("laplacian loads as a loss and checks levels and shapes", "[losses][laplacian]") {
  CHECK(plugins().get("laplacian").kind == "loss");
  const Assets assets = two_level_grid();
  auto node = make_node("laplacian", "{levels: 2}");
  CHECK_THROWS_WITH(node->setup({{"pred", {9, 3}}, {"target", {9, 3}}}, {}), Catch::Contains("no assets"));
  CHECK(node->setup({{"pred", {9, 3}}, {"target", {9, 3}}}, {"l", 0, &assets}).at("loss") == Shape{1, 1});
  CHECK_THROWS_WITH(node->setup({{"pred", {8, 3}}, {"target", {8, 3}}}, {"l", 0, &assets}), Catch::Contains("[9, 3]"));
  auto four = make_node("laplacian");  // the seed's four levels; these assets have two
  CHECK_THROWS_WITH(four->setup({{"pred", {9, 3}}, {"target", {9, 3}}}, {"l", 0, &assets}),
                    Catch::Contains("levels is 4") && Catch::Contains("2 hierarchy levels"));
  CHECK_THROWS_WITH(make_node("laplacian", "{levels: 0}"), Catch::Contains("levels"));
}

TEST_CASE("laplacian sums the L1 of L_k (x - y) over the levels", "[losses][laplacian]") {
  const Assets assets = two_level_grid();
  // The centre vertex 4 off by (1, 0, 0). Level 0: (L d)_4 = 1; its neighbours 0 and 8
  // (3 neighbours each) get -1/3, 1, 3, 5, 7 (4 each) -1/4: sum 8/3. Level 1 lacks vertex 4: 0.
  Eigen::MatrixX3d centre = Eigen::MatrixX3d::Zero(9, 3);
  centre(4, 0) = 1.0;
  CHECK(loss_of(assets, centre, "{levels: 2, reduction: sum}") == Approx(8.0 / 3).epsilon(1e-6));
  CHECK(loss_of(assets, centre, "{levels: 2}") == Approx(8.0 / 27).epsilon(1e-6));
  // Corner 0 off by (0, 0, 1). Level 0: 1 at 0, -1/4 at 1 and 3, -1/6 at 4: 5/3. Level 1: corner 0
  // (3 neighbours) 1, corners 2 and 6 (2 each) -1/2, corner 8 (3) -1/3: 7/3.
  Eigen::MatrixX3d corner = Eigen::MatrixX3d::Zero(9, 3);
  corner(0, 2) = 1.0;
  CHECK(loss_of(assets, corner, "{levels: 2, reduction: sum}") == Approx(4.0).epsilon(1e-6));
  CHECK(loss_of(assets, corner, "{levels: 1, reduction: sum}") == Approx(5.0 / 3).epsilon(1e-6));
  CHECK(loss_of(assets, corner, "{levels: 2}") == Approx(5.0 / 27 + 7.0 / 12).epsilon(1e-6));
  // A translation is in every Laplacian's kernel.
  CHECK(loss_of(assets, Eigen::MatrixX3d::Constant(9, 3, 0.7), "{levels: 2}") == Approx(0.0).margin(1e-6));
}

TEST_CASE("laplacian backward matches finite differences on the T-shirt's four levels", "[losses][laplacian][gradcheck]") {
  const Assets& assets = coarse_tshirt();
  REQUIRE(assets.hierarchy.num_levels() == 4);
  const int n = assets.garment->mesh.num_vertices();
  Tensor target(2, n, 3), pred(2, n, 3);
  const Tensor noise = random_tensor(2, n, 3, 31, 0.05f);
  for (int b = 0; b < 2; ++b) {
    target.mat(b) = assets.garment->mesh.vertices.cast<float>();
    pred.mat(b) = target.mat(b) + noise.mat(b);
  }
  // Sums keep the float loss well above its rounding; residuals of ~5 cm keep the
  // L1 kinks out of reach of the 0.1 mm step.
  auto node = make_node("laplacian", "{reduction: sum}");
  const GradCheckReport r = check_node_gradients(*node, {{"pred", pred}, {"target", target}}, {"l", 0, &assets}, kink_safe());
  INFO(r.str());
  CHECK(r.ok(1e-2));
}
