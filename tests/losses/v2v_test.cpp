// v2v (the seed's L_V2V, eq. 6.8): values by hand on a cube body, the split
// versus plain L1, finite differences for pred, target and body, errors.
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include <limits>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("v2v loads as a loss, needs the body's faces and checks shapes", "[losses][v2v]") {
  CHECK(plugins().get("v2v").kind == "loss");
  auto node = make_node("v2v");
  const ShapeMap shapes{{"pred", {4, 3}}, {"target", {4, 3}}, {"body", {8, 3}}};
  CHECK_THROWS_WITH(node->setup(shapes, {}), Catch::Contains("body's faces"));
  const auto assets = body_assets(cube_body());
  CHECK(node->setup(shapes, {"v", 0, assets.get()}).at("loss") == Shape{1, 1});
  CHECK_THROWS_WITH(node->setup({{"pred", {4, 3}}, {"target", {5, 3}}, {"body", {8, 3}}}, {"v", 0, assets.get()}),
                    Catch::Contains("differ in shape"));
  CHECK_THROWS_WITH(node->setup({{"pred", {4, 3}}, {"target", {4, 3}}, {"body", {9, 3}}}, {"v", 0, assets.get()}),
                    Catch::Contains("[8, 3]"));
  CHECK_THROWS_WITH(node->setup({{"pred", {4, 2}}, {"target", {4, 2}}, {"body", {8, 3}}}, {"v", 0, assets.get()}),
                    Catch::Contains("[vertices, 3]"));
  CHECK_THROWS_WITH(make_node("v2v", "{reduction: max}"), Catch::Contains("reduction"));
  // Non-finite values are an error, not a NaN loss.
  Tensor nan_pred(1, 4, 3, 0.5f);
  nan_pred(0, 2, 1) = std::numeric_limits<float>::quiet_NaN();
  const Tensor finite(1, 4, 3, 0.5f), cube = tensor_of(assets->body.vertices);
  CHECK_THROWS_WITH(run_forward(*node, {{"pred", nan_pred}, {"target", finite}, {"body", cube}}, {"v", 0, assets.get()}),
                    Catch::Contains("non-finite pred"));
  Tensor nan_body = cube;
  nan_body(0, 3, 0) = std::numeric_limits<float>::infinity();
  CHECK_THROWS_WITH(run_forward(*node, {{"pred", finite}, {"target", finite}, {"body", nan_body}}, {"v", 0, assets.get()}),
                    Catch::Contains("not all finite"));
}

TEST_CASE("v2v is the L1 of the closest-point and displacement parts", "[losses][v2v]") {
  const auto assets = body_assets(cube_body());
  const Tensor body = tensor_of(assets->body.vertices);
  // Vertex 0: pred above the top face at (0.2, 1.5, 0.1): c_x = (0.2, 1, 0.1), d_x = (0, 0.5, 0);
  //           target (0.5, 1.2, -0.3): c_y = (0.5, 1, -0.3), d_y = (0, 0.2, 0). Terms 0.7 + 0.3.
  // Vertex 1: pred inside, nearest the right face: (0.8, 0.5, 0) -> c_x = (1, 0.5, 0), d_x = (-0.2, 0, 0);
  //           target above the top face: (0.5, 1.2, 0) -> c_y = (0.5, 1, 0), d_y = (0, 0.2, 0).
  //           Terms |(0.5, -0.5, 0)| = 1.0 and |(-0.2, -0.2, 0)| = 0.4, where L1 of x - y is 1.0.
  const Tensor pred = tensor_of(rows3({{0.2, 1.5, 0.1}, {0.8, 0.5, 0.0}}));
  const Tensor target = tensor_of(rows3({{0.5, 1.2, -0.3}, {0.5, 1.2, 0.0}}));
  auto mean = make_node("v2v");
  auto out = run_forward(*mean, {{"pred", pred}, {"target", target}, {"body", body}}, {"v", 0, assets.get()});
  CHECK(out.at("loss")(0, 0, 0) == Approx((1.0 + 1.4) / 2).epsilon(1e-6));
  auto sum = make_node("v2v", "{reduction: sum}");
  out = run_forward(*sum, {{"pred", pred}, {"target", target}, {"body", body}}, {"v", 0, assets.get()});
  CHECK(out.at("loss")(0, 0, 0) == Approx(2.4).epsilon(1e-6));

  // The body is an input: on the cube of half-size 1.1, vertex 0 keeps 0.7 + 0.3, vertex 1
  // has c_x = (1.1, 0.5, 0), c_y = (0.5, 1.1, 0), d_x = (-0.3, 0, 0), d_y = (0, 0.1, 0): 1.2 + 0.4.
  const Tensor grown = tensor_of(cube_body(1.1).vertices);
  out = run_forward(*mean, {{"pred", pred}, {"target", target}, {"body", grown}}, {"v", 0, assets.get()});
  CHECK(out.at("loss")(0, 0, 0) == Approx((1.0 + 1.6) / 2).epsilon(1e-5));
  // Two samples in one batch, and pred == target gives zero.
  const Tensor both_pred = tensor_of(std::vector<Eigen::MatrixX3d>{pred.mat(0).cast<double>(), target.mat(0).cast<double>()});
  const Tensor both_target = tensor_of(std::vector<Eigen::MatrixX3d>{target.mat(0).cast<double>(), target.mat(0).cast<double>()});
  const Tensor both_body = tensor_of(std::vector<Eigen::MatrixX3d>{assets->body.vertices, assets->body.vertices});
  out = run_forward(*mean, {{"pred", both_pred}, {"target", both_target}, {"body", both_body}}, {"v", 0, assets.get()});
  CHECK(out.at("loss")(0, 0, 0) == Approx(1.2).epsilon(1e-6));
  CHECK(out.at("loss")(1, 0, 0) == 0.0f);
}

TEST_CASE("v2v backward matches finite differences for pred, target and body", "[losses][v2v][gradcheck]") {
  const Mesh sphere = geometry::icosphere(1, 0.5);
  const auto assets = body_assets(sphere);
  // Two samples on two bodies: points in a shell around the sphere, some inside.
  std::vector<Eigen::MatrixX3d> x, y, bodies;
  for (int b = 0; b < 2; ++b) {
    const Tensor rx = random_tensor(1, 8, 3, 40 + b), ry = random_tensor(1, 8, 3, 50 + b);
    Eigen::MatrixX3d xb(8, 3), yb(8, 3);
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d dir = rx.mat(0).row(i).cast<double>().normalized();
      xb.row(i) = (0.35 + 0.1 * i) * dir;
      yb.row(i) = (0.55 + 0.02 * i) * (dir + 0.4 * ry.mat(0).row(i).cast<double>().transpose()).normalized();
    }
    x.push_back(xb);
    y.push_back(yb);
    bodies.push_back(sphere.vertices * (1.0 + 0.1 * b));
  }
  auto node = make_node("v2v", "{reduction: sum}");
  const GradCheckReport r = check_node_gradients(
      *node, {{"pred", tensor_of(x)}, {"target", tensor_of(y)}, {"body", tensor_of(bodies)}}, {"v", 0, assets.get()});
  INFO(r.str());
  CHECK(r.entries.size() == 3);
  CHECK(r.ok(1e-2));
}
