// skin_rotation: each garment vertex's blended joint rotation minus the
// identity, checked against the blend worked by hand, zero at rest, its
// gradient to the transforms against finite differences, and clear errors
// without weights or with the wrong size.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("skin_rotation gives each vertex its blended rotation minus the identity", "[skin_rotation]") {
  const Assets a = two_joint_skinned_assets();
  const NodeContext context{"skin_rotation", 1, &a};
  auto node = make_node("skin_rotation");
  // Joint 0 moved by (5, 6, 7), which must not show: the translations are left out.
  const Tensor f = run_forward(*node, {{"transforms", two_joint_transforms(1, {5, 6, 7})}}, context).at("out");
  REQUIRE(f.rows() == 4);
  REQUIRE(f.cols() == 9);
  // Worked by hand: R1 - I = rows (-1 0 1), (0 0 0), (-1 0 -1); a vertex with
  // weight w on joint 1 feels w (R1 - I) (joint 0 adds (1 - w) I, and I goes).
  const float turned_minus_identity[9] = {-1, 0, 1, 0, 0, 0, -1, 0, -1};
  const float w1[4] = {0, 1, 0.75f, 0.25f};
  for (int v = 0; v < 4; ++v)
    for (int k = 0; k < 9; ++k) CHECK(f(0, v, k) == Approx(w1[v] * turned_minus_identity[k]).margin(1e-6));

  const Tensor rest = run_forward(*node, {{"transforms", two_joint_transforms(1, {5, 6, 7}, false)}}, context).at("out");
  for (std::size_t k = 0; k < rest.size(); ++k) CHECK(rest.data()[k] == 0.0f);
}

TEST_CASE("skin_rotation's gradient matches finite differences", "[skin_rotation][gradcheck]") {
  const Assets a = two_joint_skinned_assets();
  const NodeContext context{"skin_rotation", 1, &a};
  auto node = make_node("skin_rotation");
  Tensor transforms = two_joint_transforms(2, {5, 6, 7});
  const Tensor noise = random_tensor(2, 2, 12, 7, 0.3f);
  for (std::size_t i = 0; i < transforms.size(); ++i) transforms.data()[i] += noise.data()[i];
  const GradCheckReport r = check_node_gradients(*node, {{"transforms", transforms}}, context);
  INFO(r.str());
  CHECK(r.ok(1e-2));
}

TEST_CASE("skin_rotation needs the garment's weights and the right size", "[skin_rotation]") {
  auto node = make_node("skin_rotation");
  const Assets bare = assets_with(grid_garment(2, 0.1));
  CHECK_THROWS_WITH(node->setup({{"transforms", {2, 12}}}, {"skin_rotation", 1, &bare}),
                    Catch::Contains("has none (its body model has no skeleton"));
  const Assets a = two_joint_skinned_assets();
  CHECK_THROWS_WITH(node->setup({{"transforms", {3, 12}}}, {"skin_rotation", 1, &a}),
                    Catch::Contains("'transforms' must be [2, 12]"));
}
