// penetration (L_pen = mean (R(eps - s) / eps)^2): values by hand on a cube
// body, the margin, finite differences for pred, and the inputs it refuses.
#include <catch2/catch.hpp>

#include <cmath>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

double penetration(const std::string& yaml, const Mesh& body_mesh, const Eigen::MatrixX3d& pred,
                   const Eigen::MatrixX3d& target, const Eigen::MatrixX3d& body) {
  const auto assets = body_assets(body_mesh);
  auto node = make_node("penetration", yaml);
  return run_forward(*node, {{"pred", tensor_of(pred)}, {"target", tensor_of(target)}, {"body", tensor_of(body)}},
                     {"p", 0, assets.get()})
      .at("loss")(0, 0, 0);
}

}  // namespace

TEST_CASE("penetration loads as a loss and checks its inputs", "[losses][penetration]") {
  CHECK(plugins().get("penetration").kind == "loss");
  auto node = make_node("penetration");
  const ShapeMap shapes{{"pred", {2, 3}}, {"target", {2, 3}}, {"body", {8, 3}}};
  CHECK_THROWS_WITH(node->setup(shapes, {}), Catch::Contains("body's faces"));
  const auto assets = body_assets(cube_body());
  CHECK(node->setup(shapes, {"p", 0, assets.get()}).at("loss") == Shape{1, 1});
  CHECK_THROWS_WITH(node->setup({{"pred", {2, 3}}, {"target", {2, 3}}, {"body", {7, 3}}}, {"p", 0, assets.get()}),
                    Catch::Contains("[8, 3]"));
  CHECK_THROWS_AS(node->setup({{"pred", {2, 3}}, {"target", {3, 3}}, {"body", {8, 3}}}, {"p", 0, assets.get()}), ConfigError);
  CHECK_THROWS_WITH(make_node("penetration", "{margin: 0}"), Catch::Contains("margin"));
}

TEST_CASE("penetration is the mean squared depth inside the margin, over the margin", "[losses][penetration]") {
  const Mesh cube = cube_body();  // [-1, 1]^3
  // Vertex 0: 0.1 inside the top face (s = -0.1); vertex 1: 0.002 above the
  // right face (s = 0.002); vertex 2: 0.5 above the top (beyond any margin);
  // vertex 3: past the corner (1.01, 1.01, 1.01), s = sqrt(3) 0.01.
  const Eigen::MatrixX3d pred = rows3({{0.2, 0.9, 0.1}, {1.002, 0.3, -0.4}, {0.0, 1.5, 0.0}, {1.01, 1.01, 1.01}});
  const Eigen::MatrixX3d target = rows3({{0.2, 1.1, 0.1}, {1.1, 0.3, -0.4}, {0.0, 1.4, 0.0}, {1.1, 1.1, 1.1}});
  const double eps = 0.003;
  const double by_hand = (std::pow((eps + 0.1) / eps, 2) + std::pow((eps - 0.002) / eps, 2)) / 4.0;
  CHECK(penetration("{}", cube, pred, target, cube.vertices) == Approx(by_hand).epsilon(1e-5));
  // A margin of 2 cm reaches vertex 3 too (its distance is 0.01732).
  const double wide = 0.02;
  const double by_hand_wide = (std::pow((wide + 0.1) / wide, 2) + std::pow((wide - 0.002) / wide, 2) +
                               std::pow((wide - std::sqrt(3.0) * 0.01) / wide, 2)) /
                              4.0;
  CHECK(penetration("{margin: 0.02}", cube, pred, target, cube.vertices) == Approx(by_hand_wide).epsilon(1e-4));
  // All outside by more than the margin: zero.
  const Eigen::MatrixX3d clear = rows3({{0.2, 1.1, 0.1}, {1.1, 0.3, -0.4}, {0.0, 1.5, 0.0}, {1.1, 1.1, 1.1}});
  CHECK(penetration("{}", cube, clear, target, cube.vertices) == 0.0);
  // The sample's own body counts, not the assets' mean body: a cube twice as
  // large swallows every vertex (depths 1.1, 0.998, 0.5, 0.99 inside faces).
  const double big = (std::pow((eps + 1.1) / eps, 2) + std::pow((eps + 0.998) / eps, 2) + std::pow((eps + 0.5) / eps, 2) +
                      std::pow((eps + 0.99) / eps, 2)) /
                     4.0;
  CHECK(penetration("{}", cube, pred, target, 2.0 * cube.vertices) == Approx(big).epsilon(1e-4));
}

TEST_CASE("penetration backward matches finite differences for pred", "[losses][penetration][gradcheck]") {
  const Mesh sphere = geometry::icosphere(2, 0.5);
  const auto assets = body_assets(sphere);
  // Vertices at radii 0.44-0.55 around a sphere of radius ~0.5 (inside, in
  // the margin, outside it), in double; the loss in float.
  const Tensor r = random_tensor(1, 12, 3, 91);
  Eigen::MatrixX3d x(12, 3);
  for (int i = 0; i < 12; ++i) x.row(i) = (0.44 + 0.01 * i) * r.mat(0).row(i).cast<double>().normalized();
  const Eigen::MatrixX3d y = 1.05 * x;
  const double eps = 0.02;
  auto node = make_node("penetration", "{margin: 0.02}");
  const NodeContext ctx{"p", 0, assets.get()};
  const Tensor body = tensor_of(sphere.vertices);
  REQUIRE(node->setup({{"pred", {12, 3}}, {"target", {12, 3}}, {"body", {sphere.num_vertices(), 3}}}, ctx).at("loss") ==
          Shape{1, 1});
  Tensor loss(1, 1, 1), gloss(1, 1, 1, 1.0f), gpred(1, 12, 3);
  const Tensor pred = tensor_of(x), target = tensor_of(y);
  node->forward({{"pred", &pred}, {"target", &target}, {"body", &body}}, {{"loss", &loss}});
  node->backward({{"pred", &pred}, {"target", &target}, {"body", &body}}, {{"loss", &loss}}, {{"loss", &gloss}},
                 {{"pred", &gpred}});
  CHECK(loss(0, 0, 0) > 0.0f);
  int inside = 0;
  for (int i = 0; i < 12; ++i) {
    inside += gpred.mat(0).row(i).norm() > 0;
    for (int k = 0; k < 3; ++k) {
      const double h = 2e-4;  // well above float rounding, below the curvature of the faces' pieces
      auto at = [&](double dx) {
        Eigen::MatrixX3d moved = x;
        moved(i, k) += dx;
        Tensor l(1, 1, 1);
        const Tensor p = tensor_of(moved);
        node->forward({{"pred", &p}, {"target", &target}, {"body", &body}}, {{"loss", &l}});
        return static_cast<double>(l(0, 0, 0));
      };
      const double fd = (at(h) - at(-h)) / (2 * h);
      INFO("vertex " << i << " axis " << k);
      CHECK(gpred(0, i, k) == Approx(fd).epsilon(2e-2).margin(2e-2 * (1.0 / (eps * 12))));
    }
  }
  CHECK(inside >= 6);
  CHECK(inside < 12);
  // A body or target gradient is refused: only pred's is given.
  Tensor gbody(1, sphere.num_vertices(), 3);
  CHECK_THROWS_WITH(node->backward({{"pred", &pred}, {"target", &target}, {"body", &body}}, {{"loss", &loss}},
                                   {{"loss", &gloss}}, {{"pred", &gpred}, {"body", &gbody}}),
                    Catch::Contains("pred only"));
}
