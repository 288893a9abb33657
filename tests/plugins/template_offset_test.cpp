// subtract_mean_body and add_template: shifts by the bound template's mean body
// and garment, identity gradients, and clear errors without a template.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

Assets template_assets() {
  Assets a = assets_with(grid_garment(3, 0.1));
  a.body.vertices = Eigen::MatrixX3d::Random(5, 3);
  a.body.faces = Eigen::MatrixX3i(0, 3);
  return a;
}

}  // namespace

TEST_CASE("subtract_mean_body and add_template shift by the template", "[template_offset]") {
  const Assets a = template_assets();
  const NodeContext context{"n", 1, &a};
  CHECK(plugins().get("add_template").kind == "op");

  auto body = make_node("subtract_mean_body");
  const Tensor b = random_tensor(2, 5, 3, 1);
  const auto shifted = run_forward(*body, {{"x", b}}, context);
  for (int s = 0; s < 2; ++s)
    for (int v = 0; v < 5; ++v)
      for (int k = 0; k < 3; ++k) CHECK(shifted.at("out")(s, v, k) == Approx(b(s, v, k) - a.body.vertices(v, k)));

  auto garment = make_node("add_template");
  const Tensor zero(2, 9, 3);
  const auto placed = run_forward(*garment, {{"x", zero}}, context);
  for (int s = 0; s < 2; ++s)
    for (int v = 0; v < 9; ++v)
      for (int k = 0; k < 3; ++k) CHECK(placed.at("out")(s, v, k) == Approx(a.garment->mesh.vertices(v, k)));
}

TEST_CASE("template offsets pass gradients through unchanged", "[template_offset][gradcheck]") {
  const Assets a = template_assets();
  const NodeContext context{"n", 1, &a};
  auto body = make_node("subtract_mean_body");
  const GradCheckReport rb = check_node_gradients(*body, {{"x", random_tensor(2, 5, 3, 2)}}, context);
  INFO(rb.str());
  CHECK(rb.ok(1e-2));
  auto garment = make_node("add_template");
  const GradCheckReport rg = check_node_gradients(*garment, {{"x", random_tensor(3, 9, 3, 3)}}, context);
  INFO(rg.str());
  CHECK(rg.ok(1e-2));
}

TEST_CASE("template offsets need the template and its vertex count", "[template_offset]") {
  const Assets a = template_assets();
  auto garment = make_node("add_template");
  CHECK_THROWS_WITH(garment->setup({{"x", {9, 3}}}, {}), Catch::Contains("no template assets"));
  CHECK_THROWS_WITH(garment->setup({{"x", {8, 3}}}, {"n", 1, &a}), Catch::Contains("must be [9, 3]"));
  auto body = make_node("subtract_mean_body");
  CHECK_THROWS_WITH(body->setup({{"x", {5, 2}}}, {"n", 1, &a}), Catch::Contains("must be [5, 3]"));
}
