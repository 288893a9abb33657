// The edge loss (the seed's L_e) on one triangle by hand, and its one
// departure: a ground-truth edge collapsed below 1 % of its template length
// is measured against 1 % of that length, so one collapsed edge in a drape
// cannot make the loss unbounded.
#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include <cmath>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// One right triangle with legs of 1 cm: edges 0-1 and 0-2 of 0.01 m, 1-2 of 0.01 sqrt(2).
std::shared_ptr<Garment> small_triangle() {
  auto g = std::make_shared<Garment>();
  g->mesh.vertices = rows3({{0, 0, 0}, {0.01, 0, 0}, {0, 0.01, 0}});
  g->mesh.faces.resize(1, 3);
  g->mesh.faces << 0, 1, 2;
  g->mesh.uv.resize(3, 2);
  g->mesh.uv << 0, 0, 0.01, 0, 0, 0.01;
  g->mesh.uv_faces = g->mesh.faces;
  g->materials.emplace_back();
  return g;
}

float edge_loss(const Assets& assets, const Eigen::MatrixX3d& pred, const Eigen::MatrixX3d& target) {
  auto node = make_node("edge");
  return run_forward(*node, {{"pred", tensor_of(pred)}, {"target", tensor_of(target)}}, {"e", 0, &assets})
      .at("loss")(0, 0, 0);
}

}  // namespace

TEST_CASE("the edge loss is the seed's relative edge error, with collapsed ground-truth edges floored",
          "[losses][edge]") {
  const Assets assets = assets_with(small_triangle());
  const Eigen::MatrixX3d rest = small_triangle()->mesh.vertices;
  // The seed's definition, by hand: the prediction stretched by 10 % along x
  // against the rest shape: edge 0-1 is 10 % long, edge 0-2 exact, edge 1-2
  // from sqrt(2) to sqrt(1.21 + 1) cm.
  Eigen::MatrixX3d stretched = rest;
  stretched.col(0) *= 1.1;
  const double hypotenuse = (std::sqrt(1.21 + 1.0) - std::sqrt(2.0)) / std::sqrt(2.0);
  CHECK(edge_loss(assets, stretched, rest) == Approx((0.1 + 0.0 + hypotenuse) / 3.0).epsilon(1e-5));

  // A ground truth whose vertex 1 sits on vertex 0 (edge 0-1 collapsed to
  // 1e-12 m): the edge counts as 1 % of its 1 cm, i.e. 1e-4 m, so a prediction
  // at rest (edge 1 cm) errs by (0.01 - 1e-4) / 1e-4 = 99 on it.
  Eigen::MatrixX3d collapsed = rest;
  collapsed.row(1) << 1e-12, 0, 0;
  const double e12 = (std::sqrt(2.0) * 0.01 - 0.01) / 0.01;  // edge 1-2: 1.414 cm predicted, 1 cm in the target
  const float loss = edge_loss(assets, rest, collapsed);
  CHECK(std::isfinite(loss));
  CHECK(loss == Approx((99.0 + 0.0 + e12) / 3.0).epsilon(1e-4));

  // Its gradient stays exact where the floor is active (the floored length is a constant).
  Tensor pred = tensor_of(rest * 1.05);
  pred(0, 2, 2) = 0.002f;  // off the plane, so no edge length ties the target's
  auto node = make_node("edge");
  const GradCheckReport r =
      check_node_gradients(*node, {{"pred", pred}, {"target", tensor_of(collapsed)}}, {"e", 0, &assets}, kink_safe());
  INFO(r.str());
  CHECK(r.ok(1e-2));
}
