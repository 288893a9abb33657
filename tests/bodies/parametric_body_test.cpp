// The built-in parametric body: fixed topology, BMI/height solve over the whole
// range, mesh validity at the extremes, index locality, determinism, errors.
#include <catch2/catch.hpp>

#include <drape/bodies/body.hpp>
#include <drape/geometry/face_quality.hpp>
#include <drape/geometry/index_locality.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/topology.hpp>
#include <drape/geometry/volume.hpp>
#include <test_support.hpp>

#include <cmath>
#include <iostream>
#include <memory>

namespace {

using namespace drape;

const BodyModel& body() {
  static const std::unique_ptr<BodyModel> model = [] {
    const PluginDescriptor& d = test::plugins().get("parametric");
    return test::plugins().create_body("parametric", Params(d.params, {}, "body parametric"));
  }();
  return *model;
}

double mesh_height(const Eigen::MatrixX3d& v) { return v.col(1).maxCoeff() - v.col(1).minCoeff(); }
double mesh_bmi(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f) {
  const double h = mesh_height(v);
  return geometry::mesh_volume(v, f) * 985.0 / (h * h);
}

// Everything a body mesh must be, whatever its shape.
void require_valid_body(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f, const std::string& what) {
  INFO(what);
  const auto topo = geometry::check_topology(f, static_cast<int>(v.rows()));
  INFO(topo.str());
  REQUIRE(topo.closed_manifold());
  REQUIRE(topo.euler_characteristic == 2);
  REQUIRE(geometry::mesh_volume(v, f) > 0);  // outward orientation
  // No sliver or zero-area faces: nothing thinner than 1 degree or smaller than 0.01 mm^2.
  CHECK(geometry::degenerate_faces(v, f, 1e-8, M_PI / 180).empty());
  // No triangle folded over its neighbour: a flipped face turns by ~180 degrees
  // against it, while the sharpest true creases (armpits of thin tall bodies)
  // turn by about 110.
  CHECK(geometry::folded_edges(v, f, 0.75 * M_PI).empty());
  CHECK(geometry::self_intersections(v, f, 10).empty());
}

TEST_CASE("parametric body: fixed topology in the range of SMPL's resolution") {
  const BodyModel& b = body();
  REQUIRE(b.num_vertices() >= 5000);
  REQUIRE(b.num_vertices() <= 7000);
  REQUIRE(b.faces().rows() == 2 * b.num_vertices() - 4);  // closed genus-0 triangle mesh
  REQUIRE(b.shape_names().size() == static_cast<std::size_t>(b.mean_shape().size()));
  const Eigen::MatrixX3d mean = b.vertices(b.mean_shape());
  REQUIRE(mean.rows() == b.num_vertices());
  require_valid_body(mean, b.faces(), "mean shape");
  // A-pose, Y up, feet at y = 0, facing +Z (the feet point forward).
  CHECK(mean.col(1).minCoeff() == Approx(0).margin(1e-12));
  CHECK(mean.col(2).maxCoeff() > -mean.col(2).minCoeff());
  const Eigen::VectorXd heavy = b.solve({50, 1.9, 0.3});
  CHECK(b.vertices(heavy).rows() == b.num_vertices());
}

TEST_CASE("parametric body: arms hang 45-50 degrees below horizontal") {
  const BodyModel& b = body();
  const Eigen::MatrixX3d v = b.vertices(b.mean_shape());
  // The hand tip is the vertex furthest out in x; the shoulder is where the
  // arm leaves the trunk, approximated by the highest vertex at 60% of that reach.
  Eigen::Index tip;
  v.col(0).maxCoeff(&tip);
  const double reach = v(tip, 0);
  double shoulder_y = 0;
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (std::abs(v(i, 0) - 0.45 * reach) < 0.01) shoulder_y = std::max(shoulder_y, v(i, 1));
  double mid_y = 0;
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (std::abs(v(i, 0) - 0.8 * reach) < 0.01) mid_y = std::max(mid_y, v(i, 1));
  const double angle = std::atan2(shoulder_y - mid_y, 0.35 * reach) * 180 / M_PI;
  INFO("upper arm contour angle " << angle);
  CHECK(angle > 40);
  CHECK(angle < 55);
}

TEST_CASE("parametric body: solve reaches BMI 10-65 and the height, both sexes") {
  const BodyModel& b = body();
  REQUIRE(b.bmi_range().first == 10);
  REQUIRE(b.bmi_range().second == 65);
  const double heights[] = {1.50, 1.62, 1.75, 1.88, 2.00};
  double worst_bmi = 0, worst_height = 0;
  int n = 0;
  for (double sex : {0.0, 1.0})
    for (int i = 0; i < 12; ++i) {
      const BodyRequest req{10.0 + 55.0 * i / 11.0, heights[(i + static_cast<int>(sex)) % 5], sex};
      const Eigen::MatrixX3d v = b.vertices(b.solve(req));
      const double bmi = mesh_bmi(v, b.faces()), h = mesh_height(v);
      INFO("request bmi " << req.bmi << " height " << req.height << " sex " << sex << " -> bmi " << bmi << " height " << h);
      CHECK(std::abs(bmi - req.bmi) <= 0.5);
      CHECK(std::abs(h - req.height) <= 0.01);
      worst_bmi = std::max(worst_bmi, std::abs(bmi - req.bmi));
      worst_height = std::max(worst_height, std::abs(h - req.height));
      require_valid_body(v, b.faces(), "swept body");
      ++n;
    }
  std::cout << "parametric body: " << n << " solves, worst |BMI error| " << worst_bmi << ", worst |height error| "
            << worst_height << " m\n";
}

TEST_CASE("parametric body: the extremes BMI 10 and 65 are valid meshes at the extreme heights") {
  const BodyModel& b = body();
  for (double bmi : {10.0, 65.0})
    for (double height : {1.5, 2.0})
      for (double sex : {0.0, 1.0}) {
        const Eigen::MatrixX3d v = b.vertices(b.solve({bmi, height, sex}));
        CHECK(std::abs(mesh_bmi(v, b.faces()) - bmi) <= 0.5);
        require_valid_body(v, b.faces(), "BMI " + std::to_string(bmi) + " height " + std::to_string(height) +
                                             " sex " + std::to_string(sex));
      }
}

TEST_CASE("parametric body: heavier bodies grow in the trunk more than in the head") {
  const BodyModel& b = body();
  const Eigen::MatrixX3d thin = b.vertices(b.solve({15, 1.75, 1})), heavy = b.vertices(b.solve({45, 1.75, 1}));
  auto width_at = [](const Eigen::MatrixX3d& v, double y0, double y1, double max_x) {
    double w = 0;
    for (Eigen::Index i = 0; i < v.rows(); ++i)
      if (v(i, 1) > y0 && v(i, 1) < y1 && std::abs(v(i, 0)) < max_x) w = std::max(w, std::abs(v(i, 2)));
    return w;
  };
  const double belly_gain = width_at(heavy, 0.95, 1.1, 0.15) / width_at(thin, 0.95, 1.1, 0.15);
  const double head_gain = width_at(heavy, 1.6, 1.7, 0.1) / width_at(thin, 1.6, 1.7, 0.1);
  INFO("belly depth x" << belly_gain << ", head depth x" << head_gain);
  CHECK(belly_gain > 1.5);
  CHECK(head_gain < 1.15);
}

TEST_CASE("parametric body: vertex order keeps mesh neighbours close in index") {
  const BodyModel& b = body();
  const auto loc = geometry::index_locality(b.faces(), b.num_vertices());
  std::cout << "parametric body: consecutive indices are neighbours " << 100 * loc.one_hop << "%, within two hops "
            << 100 * loc.two_hop << "% (SMPL: 91.24%, 94.01%)\n";
  CHECK(loc.one_hop >= 0.85);
  CHECK(loc.two_hop >= loc.one_hop);
}

TEST_CASE("parametric body: the same parameters give bit-identical meshes") {
  // The rig keeps its last bodies (by exact shape vector, shared by its
  // instances): asked again, it must give each shape its own body.
  const BodyModel& b = body();
  const Eigen::VectorXd s = b.solve({33, 1.68, 0.4});
  REQUIRE(b.solve({33, 1.68, 0.4}) == s);
  const Eigen::MatrixX3d v1 = b.vertices(s);
  const Eigen::VectorXd s2 = b.solve({60, 1.9, 1});  // something in between must not leave state behind
  const Eigen::MatrixX3d v2 = b.vertices(s2);
  REQUIRE(b.vertices(s) == v1);
  REQUIRE(b.vertices(s2) == v2);
  // A second model instance (same template) agrees too.
  const PluginDescriptor& d = test::plugins().get("parametric");
  const auto other = test::plugins().create_body("parametric", Params(d.params, {}, "body parametric"));
  REQUIRE(other->faces() == b.faces());
  REQUIRE(other->vertices(s2) == v2);
  REQUIRE(other->vertices(s) == v1);
  CHECK(v2 != v1);
  // A shape one bit away is another body.
  Eigen::VectorXd s3 = s;
  s3[2] = std::nextafter(s3[2], 1.0);
  CHECK(b.vertices(s3) != v1);
}

TEST_CASE("parametric body: unreachable requests and bad shapes are ConfigErrors naming the range") {
  const BodyModel& b = body();
  REQUIRE_THROWS_AS(b.solve({9.5, 1.75, 1}), ConfigError);
  REQUIRE_THROWS_WITH(b.solve({70, 1.75, 1}), Catch::Contains("BMI 70") && Catch::Contains("[10, 65]"));
  REQUIRE_THROWS_WITH(b.solve({25, 2.5, 1}), Catch::Contains("height 2.5") && Catch::Contains("range"));
  REQUIRE_THROWS_AS(b.solve({25, 1.75, 1.5}), ConfigError);
  Eigen::VectorXd s = b.mean_shape();
  s[0] = 0.3;
  REQUIRE_THROWS_WITH(b.vertices(s), Catch::Contains("'height'"));
  REQUIRE_THROWS_AS(b.vertices(Eigen::VectorXd::Zero(2)), ConfigError);
}

}  // namespace
