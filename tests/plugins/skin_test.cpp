// skin: a canonical garment posed by its skinning weights and the sample's
// joint transforms, checked against the formula worked by hand, its gradients
// (to the garment and to the transforms) against finite differences, and
// clear errors without weights or with the wrong sizes.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("skin poses each vertex by its blended joint transforms", "[skin]") {
  const Assets a = two_joint_skinned_assets();
  const NodeContext context{"skin", 1, &a};
  auto skin = make_node("skin");
  Tensor x(1, 4, 3);
  const float points[4][3] = {{1, 2, 3}, {1, 2, 3}, {2, 0, 0}, {0, 0, 4}};
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) x(0, v, c) = points[v][c];
  const Tensor y = run_forward(*skin, {{"x", x}, {"transforms", two_joint_transforms(1)}}, context).at("out");
  // Worked by hand: R1 (x, y, z) = (z, y, -x), t1 = (1, 2, 3).
  const float expected[4][3] = {
      {1, 2, 3},                                      // joint 0 only: unchanged
      {3 + 1, 2 + 2, -1 + 3},                         // joint 1 only
      {0.25f * 2 + 0.75f * (0 + 1), 0.75f * 2, 0.75f * (-2 + 3)},    // (2,0,0): R1 -> (0,0,-2)
      {0.75f * 0 + 0.25f * (4 + 1), 0.25f * 2, 0.75f * 4 + 0.25f * (0 + 3)}};  // (0,0,4): R1 -> (4,0,0)
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) CHECK(y(0, v, c) == Approx(expected[v][c]).margin(1e-6));
}

TEST_CASE("skin's gradients match finite differences", "[skin][gradcheck]") {
  const Assets a = two_joint_skinned_assets();
  const NodeContext context{"skin", 1, &a};
  auto skin = make_node("skin");
  Tensor transforms = two_joint_transforms(2);
  const Tensor noise = random_tensor(2, 2, 12, 7, 0.3f);
  for (std::size_t i = 0; i < transforms.size(); ++i) transforms.data()[i] += noise.data()[i];
  const GradCheckReport r = check_node_gradients(*skin, {{"x", random_tensor(2, 4, 3, 5)}, {"transforms", transforms}}, context);
  INFO(r.str());
  CHECK(r.ok(1e-2));
}

TEST_CASE("skin needs the garment's weights and the right sizes", "[skin]") {
  auto skin = make_node("skin");
  const Assets bare = assets_with(grid_garment(2, 0.1));
  CHECK_THROWS_WITH(skin->setup({{"x", {4, 3}}, {"transforms", {2, 12}}}, {"skin", 1, &bare}),
                    Catch::Contains("has none (its body model has no skeleton"));
  const Assets a = two_joint_skinned_assets();
  CHECK_THROWS_WITH(skin->setup({{"x", {5, 3}}, {"transforms", {2, 12}}}, {"skin", 1, &a}), Catch::Contains("must be [4, 3]"));
  CHECK_THROWS_WITH(skin->setup({{"x", {4, 3}}, {"transforms", {3, 12}}}, {"skin", 1, &a}),
                    Catch::Contains("'transforms' must be [2, 12]"));
}
