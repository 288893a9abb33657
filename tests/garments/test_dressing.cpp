// drape::dress: fitting a placed garment to a body without intersections.
#include "test_support.hpp"
#include "tshirt_support.hpp"

#include <drape/energy.hpp>
#include <drape/bodies/body.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/geometry/closest_point.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

using namespace drape;

namespace {

// Ray-parity inside test (+x ray), independent of the query's pseudo-normals.
bool inside_by_parity(const Mesh& body, const Eigen::Vector3d& p) {
  int crossings = 0;
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 1e-4, 2e-4).normalized();  // avoids edge-on hits
  for (Eigen::Index f = 0; f < body.faces.rows(); ++f) {
    const Eigen::Vector3d a = body.vertices.row(body.faces(f, 0)), b = body.vertices.row(body.faces(f, 1)),
                          c = body.vertices.row(body.faces(f, 2));
    const Eigen::Vector3d e1 = b - a, e2 = c - a, h = dir.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-15) continue;
    const Eigen::Vector3d s = p - a;
    const double u = s.dot(h) / det;
    if (u < 0 || u > 1) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = dir.dot(q) / det;
    if (v < 0 || u + v > 1) continue;
    if (e2.dot(q) / det > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

}  // namespace

TEST_CASE("dress pushes a garment out of a sphere and keeps it smooth", "[garments][dressing]") {
  const Mesh ball = test::uv_sphere(0.3, 30, 60);
  // A flat sheet through the sphere's middle plays the garment.
  Garment g;
  const int n = 30;
  g.mesh.vertices.resize(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g.mesh.vertices.row(i * n + j) << -0.5 + i / (n - 1.0), -0.5 + j / (n - 1.0), 0.05;
  g.mesh.faces.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      g.mesh.faces.row(f++) << i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1;
      g.mesh.faces.row(f++) << i * n + j, (i + 1) * n + j + 1, i * n + j + 1;
    }
  int inside = 0;
  for (int v = 0; v < g.mesh.num_vertices(); ++v) inside += inside_by_parity(ball, g.mesh.vertices.row(v));
  REQUIRE(inside > 100);
  const Eigen::MatrixX3d cut = g.mesh.vertices;
  const DressReport r = dress(g, ball, {0.01, 30, 3});
  // Where it was cut is kept (Garment::cut_vertices: the self-contact's rest neighbours), and a second dressing keeps the first's.
  CHECK(g.cut_vertices == cut);
  CHECK_FALSE(g.mesh.vertices.isApprox(cut));
  dress(g, ball, {0.02, 30, 3});
  CHECK(g.cut_vertices == cut);
  CHECK(r.inside_before == inside);
  CHECK(r.min_distance_after >= 0.01 - 2e-6);
  for (int v = 0; v < g.mesh.num_vertices(); ++v) REQUIRE_FALSE(inside_by_parity(ball, g.mesh.vertices.row(v)));
  // Vertices that started outside with clearance and far from the ball stay put.
  CHECK(g.mesh.vertices.row(0).isApprox(Eigen::RowVector3d(-0.5, -0.5, 0.05)));
}

TEST_CASE("tshirt dressed on the mean parametric body: outside, and close around the torso", "[garments][dressing]") {
  const PluginDescriptor* d = test::plugins().find("parametric");
  if (!d) {
    WARN("SKIPPED: the 'parametric' body plugin is not in this build; the dressing check needs it");
    return;
  }
  const auto model = test::plugins().create_body("parametric", Params(d->params, {}, "parametric"));
  Mesh body;
  body.vertices = model->vertices(model->mean_shape());
  body.faces = model->faces();
  Garment g = test::build_tshirt();
  const DressReport r = dress(g, body);
  WARN("dress on the mean body: " << r.inside_before << " vertices inside before (deepest " << r.deepest_before
                                  << " m), " << r.pushed << " moved, " << r.iterations << " rounds, min distance after "
                                  << r.min_distance_after << " m");
  const geometry::BodySurface surface(body);
  int inside = 0, far = 0;
  double farthest = 0;
  for (int v = 0; v < g.mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = g.mesh.vertices.row(v);
    inside += inside_by_parity(body, p);
    const double dist = std::abs(surface.closest(p).signed_distance);
    farthest = std::max(farthest, dist);
    far += dist > 0.10;
  }
  // Faces point away from the body: the normal and the way from the body to the face agree.
  // Consistency is the topology test's job; this checks the global sign (a few faces in
  // the armpit folds and at the collar see the body sideways, hence not 100%).
  int outward = 0;
  for (int f = 0; f < g.mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = g.mesh.vertices.row(g.mesh.faces(f, 0)), b = g.mesh.vertices.row(g.mesh.faces(f, 1)),
                          c = g.mesh.vertices.row(g.mesh.faces(f, 2));
    const Eigen::Vector3d centre = (a + b + c) / 3;
    outward += (b - a).cross(c - a).dot(centre - surface.closest(centre).point) > 0;
  }
  const double outward_fraction = static_cast<double>(outward) / g.mesh.num_faces();
  WARN("after dress: farthest vertex " << farthest << " m from the body, " << 100 * outward_fraction
                                       << "% of faces facing away from it");
  CHECK(inside == 0);
  CHECK(far == 0);
  CHECK(outward_fraction > 0.9);
}

TEST_CASE("check_garment_around_body refuses a garment in other units or apart from the body and passes a long gown",
          "[garments][dressing]") {
  // A body 1.0 m across (a sphere of radius 0.5), garments around it.
  const Mesh body = test::uv_sphere(0.5, 12, 16);
  Mesh garment = test::uv_sphere(0.55, 8, 12);
  CHECK_NOTHROW(check_garment_around_body(garment, body, "shell"));
  // A gown twice the body's size, hanging far below it, is still a garment of this body.
  Mesh gown = garment;
  gown.vertices.col(1) *= 2.0;
  gown.vertices.col(1).array() -= 0.5;
  CHECK_NOTHROW(check_garment_around_body(gown, body, "gown"));
  // The same shell in centimetres: 110 m across against 1 m, and the factor that fits it.
  Mesh cm = garment;
  cm.vertices *= 100.0;
  const std::string message = test::message_of([&] { check_garment_around_body(cm, body, "garment 'x' (shell.obj)"); });
  CHECK_THAT(message, Catch::Contains("garment 'x' (shell.obj) is 110 m across, the body 1 m") &&
                          Catch::Contains("scaled by 0.01 it would be 1.1 m"));
  // The other way (an outside check: decimetres read as metres, 7 cm across
  // at the feet, simulated until it "fell off"): refused with the factor.
  Mesh dm = garment;
  dm.vertices *= 0.04;
  CHECK_THAT(test::message_of([&] { check_garment_around_body(dm, body, "shell"); }),
             Catch::Contains("shell is 0.044 m across, the body 1 m") && Catch::Contains("scaled by 10 it would be 0.44 m"));
  Mesh glove = garment;  // a tenth of the body across: a glove's share, still a garment
  glove.vertices *= 0.1;
  CHECK_NOTHROW(check_garment_around_body(glove, body, "glove"));
  // Moved 0.2 m clear of the body's box: refused, with both boxes; 5 cm is within the slack.
  Mesh apart = garment;
  apart.vertices.col(0).array() += 1.3;
  CHECK_THAT(test::message_of([&] { check_garment_around_body(apart, body, "shell"); }),
             Catch::Contains("shell lies 0.25 m away from the body") && Catch::Contains("x 0.750..1.850"));
  Mesh near = garment;
  near.vertices.col(0).array() += 1.1;
  CHECK_NOTHROW(check_garment_around_body(near, body, "shell"));
}

TEST_CASE("check_garment_around_body refuses a garment turned about the vertical, and passes one round across",
          "[garments][dressing]") {
  // A body wider along x than deep (an A-pose body: its shoulders and arms), and a shirt-like shell wider still
  // along x (its sleeves). Scaled spheres: the ratios of their widest to narrowest ways are 2.5 and 2.
  Mesh body = test::uv_sphere(0.5, 12, 16);
  body.vertices.col(2) *= 0.4;
  Mesh shirt = test::uv_sphere(0.5, 8, 12);
  shirt.vertices.col(0) *= 1.2;
  shirt.vertices.col(2) *= 0.6;
  CHECK_NOTHROW(check_garment_around_body(shirt, body, "shirt"));
  const auto turned = [&](double degrees) {
    const double t = degrees * std::numbers::pi / 180.0;
    Mesh m = shirt;
    for (Eigen::Index i = 0; i < m.vertices.rows(); ++i) {
      const double x = shirt.vertices(i, 0), z = shirt.vertices(i, 2);
      m.vertices(i, 0) = std::cos(t) * x + std::sin(t) * z;
      m.vertices(i, 2) = -std::sin(t) * x + std::cos(t) * z;
    }
    return m;
  };
  CHECK_NOTHROW(check_garment_around_body(turned(30.0), body, "shirt"));   // within 45 degrees: a garment cut at a slant
  CHECK_NOTHROW(check_garment_around_body(turned(180.0), body, "shirt"));  // its widest way along x again
  CHECK_THAT(test::message_of([&] { check_garment_around_body(turned(90.0), body, "garment 'mesh' (shirt.obj)"); }),
             Catch::Contains("garment 'mesh' (shirt.obj) is widest across 90 degrees from the way the body is") &&
                 Catch::Contains("turned about the vertical"));
  CHECK_THROWS_AS(check_garment_around_body(turned(-60.0), body, "shirt"), ConfigError);
  // Round across (a skirt, a tube): no way to be turned, whichever way it is.
  const Mesh tube = test::uv_sphere(0.55, 8, 12);
  CHECK_NOTHROW(check_garment_around_body(tube, body, "tube"));
}
