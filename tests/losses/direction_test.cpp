// direction (the seed's L_dir, eq. 6.7): both terms by hand on a cube body,
// the undefined directions, finite differences for pred, target and body.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("direction loads as a loss and checks its inputs", "[losses][direction]") {
  CHECK(plugins().get("direction").kind == "loss");
  auto node = make_node("direction");
  const ShapeMap shapes{{"pred", {2, 3}}, {"target", {2, 3}}, {"body", {8, 3}}};
  CHECK_THROWS_WITH(node->setup(shapes, {}), Catch::Contains("body's faces"));
  const auto assets = body_assets(cube_body());
  CHECK(node->setup(shapes, {"d", 0, assets.get()}).at("loss") == Shape{1, 1});
  CHECK_THROWS_WITH(node->setup({{"pred", {2, 3}}, {"target", {2, 3}}, {"body", {7, 3}}}, {"d", 0, assets.get()}),
                    Catch::Contains("[8, 3]"));
  CHECK_THROWS_AS(node->setup({{"pred", {2, 3}}, {"target", {3, 3}}, {"body", {8, 3}}}, {"d", 0, assets.get()}), ConfigError);
  CHECK_THROWS_WITH(make_node("direction", "{outside_weight: -1}"), Catch::Contains("outside_weight"));
  Tensor nan_target(1, 2, 3, 0.5f);
  nan_target(0, 1, 2) = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_WITH(run_forward(*node, {{"pred", Tensor(1, 2, 3, 0.5f)}, {"target", nan_target},
                                        {"body", tensor_of(assets->body.vertices)}}, {"d", 0, assets.get()}),
                    Catch::Contains("non-finite target"));
}

TEST_CASE("direction is the ReLU on the correspondence plus one minus the offset cosine", "[losses][direction]") {
  const auto assets = body_assets(cube_body());
  const Tensor body = tensor_of(assets->body.vertices);
  // Vertex 0: y = (0.1, 1.5, 0.4) over the top face: c_y = (0.1, 1, 0.4), n = d_y / |d_y| = +Y.
  //   x = (0.5, 0.8, 0) is inside, nearest the top: c_x = (0.5, 1, 0); c_x - c_y is tangent: term (1) = 0.
  //   x - c_y = (0.4, -0.2, -0.4) (length 0.6) against d_y = (0, 0.5, 0): cos = -1/3, term (2) = 4/3.
  // Vertex 1: y = (0.9, 1.5, 0.2): c_y = (0.9, 1, 0.2), n = +Y. x = (1.5, 0.5, 0.2) is beside the right
  //   face: c_x = (1, 0.5, 0.2), below the tangent plane at c_y: term (1) = 0.5 / sqrt(0.26).
  //   x - c_y = (0.6, -0.5, 0): cos = -0.5 / sqrt(0.61), term (2) = 1 + 0.5 / sqrt(0.61).
  const Tensor pred = tensor_of(rows3({{0.5, 0.8, 0.0}, {1.5, 0.5, 0.2}}));
  const Tensor target = tensor_of(rows3({{0.1, 1.5, 0.4}, {0.9, 1.5, 0.2}}));
  const double outside = 0.5 / std::sqrt(0.26), offset = 4.0 / 3.0 + 1.0 + 0.5 / std::sqrt(0.61);
  const NodeContext ctx{"d", 0, assets.get()};
  auto run = [&](const std::string& yaml, const Tensor& p, const Tensor& t) {
    auto node = make_node("direction", yaml);
    return run_forward(*node, {{"pred", p}, {"target", t}, {"body", body}}, ctx).at("loss")(0, 0, 0);
  };
  CHECK(run("{}", pred, target) == Approx((outside + offset) / 2).epsilon(1e-6));
  CHECK(run("{reduction: sum}", pred, target) == Approx(outside + offset).epsilon(1e-6));
  CHECK(run("{outside_weight: 0}", pred, target) == Approx(offset / 2).epsilon(1e-6));
  CHECK(run("{offset_weight: 0, outside_weight: 2}", pred, target) == Approx(outside).epsilon(1e-6));
  // The prediction on the ground truth: c_x = c_y and x - c_y = d_y, both terms vanish.
  CHECK(run("{}", target, target) == Approx(0.0).margin(1e-6));
  // Closer to the body: term (1) is the same (it is scale-free, as in eq. 6.7), term (2) follows the angles.
  const Tensor pred_near = tensor_of(rows3({{0.5, 0.9, 0.0}, {1.25, 0.5, 0.2}}));
  const Tensor target_near = tensor_of(rows3({{0.1, 1.25, 0.4}, {0.9, 1.25, 0.2}}));
  // Vertex 0: x - c_y = (0.4, -0.1, -0.4), |.| = sqrt(0.33): cos = -0.1 / sqrt(0.33). Vertex 1: c_x = (1, 0.5, 0.2),
  // e = (0.1, -0.5, 0) as before; x - c_y = (0.35, -0.5, 0): cos = -0.5 / sqrt(0.3725).
  const double near = 0.5 / std::sqrt(0.26) + 1 + 0.1 / std::sqrt(0.33) + 1 + 0.5 / std::sqrt(0.3725);
  CHECK(run("{reduction: sum}", pred_near, target_near) == Approx(near).epsilon(1e-5));
  // A ground truth lying on the body has no offset direction: term (2) is 0 there.
  const Tensor on_body = tensor_of(rows3({{0.1, 1.0, 0.4}}));
  const Tensor above = tensor_of(rows3({{0.1, 1.3, 0.4}}));
  CHECK(run("{}", above, on_body) == Approx(0.0).margin(1e-6));
}

TEST_CASE("direction backward matches finite differences for pred, target and body", "[losses][direction][gradcheck]") {
  const Mesh sphere = geometry::icosphere(1, 0.5);
  const auto assets = body_assets(sphere);
  std::vector<Eigen::MatrixX3d> x, y, bodies;
  for (int b = 0; b < 2; ++b) {
    const Tensor rx = random_tensor(1, 8, 3, 60 + b), ry = random_tensor(1, 8, 3, 70 + b);
    Eigen::MatrixX3d xb(8, 3), yb(8, 3);
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d dir = rx.mat(0).row(i).cast<double>().normalized();
      xb.row(i) = (0.4 + 0.05 * i) * dir;  // inside and outside
      yb.row(i) = (0.56 + 0.02 * i) * (dir + 0.5 * ry.mat(0).row(i).cast<double>().transpose()).normalized();
    }
    x.push_back(xb);
    y.push_back(yb);
    bodies.push_back(sphere.vertices * (1.0 - 0.1 * b));
  }
  auto node = make_node("direction", "{reduction: sum}");
  const GradCheckReport r = check_node_gradients(
      *node, {{"pred", tensor_of(x)}, {"target", tensor_of(y)}, {"body", tensor_of(bodies)}}, {"d", 0, assets.get()});
  INFO(r.str());
  CHECK(r.entries.size() == 3);
  CHECK(r.ok(1e-2));
}
