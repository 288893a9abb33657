// deformation (the seed's L_d, eqs. 6.10-6.11): deformation gradients by hand
// on one triangle and a grid, finite differences, errors.
#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// One triangle at rest in the XY plane; its material space is (x, y) * uv_scale.
std::shared_ptr<Garment> triangle(double uv_scale = 1.0) {
  auto g = std::make_shared<Garment>();
  g->mesh.vertices = rows3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  g->mesh.faces.resize(1, 3);
  g->mesh.faces << 0, 1, 2;
  g->mesh.uv.resize(3, 2);
  g->mesh.uv << 0, 0, uv_scale, 0, 0, uv_scale;
  g->mesh.uv_faces = g->mesh.faces;
  g->materials.emplace_back();
  return g;
}

float loss_of(const Assets& assets, const Eigen::MatrixX3d& pred, const Eigen::MatrixX3d& target,
              const std::string& yaml = "{}") {
  auto node = make_node("deformation", yaml);
  return run_forward(*node, {{"pred", tensor_of(pred)}, {"target", tensor_of(target)}}, {"d", 0, &assets})
      .at("loss")(0, 0, 0);
}

}  // namespace

TEST_CASE("deformation loads as a loss and checks the garment and shapes", "[losses][deformation]") {
  CHECK(plugins().get("deformation").kind == "loss");
  auto node = make_node("deformation");
  CHECK_THROWS_WITH(node->setup({{"pred", {3, 3}}, {"target", {3, 3}}}, {}), Catch::Contains("no garment template"));
  const Assets assets = assets_with(triangle());
  CHECK(node->setup({{"pred", {3, 3}}, {"target", {3, 3}}}, {"d", 0, &assets}).at("loss") == Shape{1, 1});
  CHECK_THROWS_WITH(node->setup({{"pred", {4, 3}}, {"target", {4, 3}}}, {"d", 0, &assets}), Catch::Contains("[3, 3]"));
  CHECK_THROWS_AS(node->setup({{"pred", {3, 3}}, {"target", {3, 2}}}, {"d", 0, &assets}), ConfigError);
  auto no_uv = triangle();
  no_uv->mesh.uv.resize(0, 2);
  const Assets bare = assets_with(no_uv);
  CHECK_THROWS_WITH(node->setup({{"pred", {3, 3}}, {"target", {3, 3}}}, {"d", 0, &bare}), Catch::Contains("UV"));
  auto flat = triangle();
  flat->mesh.uv.row(2) << 2.0, 0.0;  // collinear material-space corners
  const Assets degenerate = assets_with(flat);
  CHECK_THROWS_WITH(node->setup({{"pred", {3, 3}}, {"target", {3, 3}}}, {"d", 0, &degenerate}),
                    Catch::Contains("face 0") && Catch::Contains("degenerate"));
}

TEST_CASE("deformation is the L1 difference of the deformation gradients", "[losses][deformation]") {
  const Assets assets = assets_with(triangle());
  const Eigen::MatrixX3d rest = triangle()->mesh.vertices;
  // Stretch x by 2: F_x = [2 0; 0 1; 0 0], F_y = [1 0; 0 1; 0 0]: one entry differs by 1.
  Eigen::MatrixX3d stretched = rest;
  stretched.col(0) *= 2.0;
  CHECK(loss_of(assets, stretched, rest) == Approx(1.0).epsilon(1e-6));
  // Material space at half scale: X^-1 = 2 I, every F doubles, so does the difference.
  const Assets half = assets_with(triangle(0.5));
  CHECK(loss_of(half, stretched, rest) == Approx(2.0).epsilon(1e-6));
  // Shear: the second edge leans by 0.3 in x: F differs by 0.3 in entry (x, v).
  Eigen::MatrixX3d sheared = rest;
  sheared(2, 0) = 0.3;
  CHECK(loss_of(assets, sheared, rest) == Approx(0.3).epsilon(1e-6));
  // A translation leaves F alone; a rotation about X by 90 degrees turns the v column from Y to Z:
  // |(0, -1, 1)|_1 = 2 (F is compared as is, not its strain).
  CHECK(loss_of(assets, rest.rowwise() + Eigen::RowVector3d(0.2, -1.0, 3.0), rest) == Approx(0.0).margin(1e-6));
  Eigen::MatrixX3d rotated = rest;
  rotated.col(1) = -rest.col(2);
  rotated.col(2) = rest.col(1);
  CHECK(loss_of(assets, rotated, rest) == Approx(2.0).epsilon(1e-6));

  // A 4x4 grid (18 faces) scaled by 1.3: F_x - F_y = 0.3 [I; 0] on every face, |.|_1 = 0.6.
  const auto grid = grid_garment(4, 0.1);
  const Assets grid_assets = assets_with(grid);
  const Eigen::MatrixX3d g0 = grid->mesh.vertices;
  CHECK(loss_of(grid_assets, 1.3 * g0, g0) == Approx(0.6).epsilon(1e-5));
  CHECK(loss_of(grid_assets, 1.3 * g0, g0, "{reduction: sum}") == Approx(0.6 * 18).epsilon(1e-5));
}

TEST_CASE("deformation backward matches finite differences", "[losses][deformation][gradcheck]") {
  const auto grid = grid_garment(4, 0.1);
  const Assets assets = assets_with(grid);
  Tensor target(2, 16, 3), pred(2, 16, 3);
  const Tensor nt = random_tensor(2, 16, 3, 21, 0.02f), np = random_tensor(2, 16, 3, 22, 0.03f);
  for (int b = 0; b < 2; ++b) {
    target.mat(b) = grid->mesh.vertices.cast<float>() + nt.mat(b);
    pred.mat(b) = target.mat(b) + np.mat(b);
  }
  auto node = make_node("deformation");
  const GradCheckReport r = check_node_gradients(*node, {{"pred", pred}, {"target", target}}, {"d", 0, &assets}, kink_safe());
  INFO(r.str());
  CHECK(r.entries.size() == 2);
  CHECK(r.ok(1e-2));
}
