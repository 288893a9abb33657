// geometry::closest_point_backward against central differences of
// BodySurface::locate in double, for the query point and the body vertices,
// on face interiors, edges and vertices.
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/closest_point_gradient.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::geometry;

namespace {

// The mesh vertices spanning the feature a closest point lies on, sorted (a
// vertex or an edge is shared by several faces: any of them may report it).
std::vector<int> feature_vertices(const Mesh& body, const SurfacePoint& s) {
  using F = TriangleFeature;
  const auto f = body.faces.row(s.face);
  std::vector<int> v;
  switch (s.feature) {
    case F::vertex_a: v = {f[0]}; break;
    case F::vertex_b: v = {f[1]}; break;
    case F::vertex_c: v = {f[2]}; break;
    case F::edge_ab: v = {f[0], f[1]}; break;
    case F::edge_bc: v = {f[1], f[2]}; break;
    case F::edge_ca: v = {f[2], f[0]}; break;
    default: v = {f[0], f[1], f[2]}; break;
  }
  std::sort(v.begin(), v.end());
  return v;
}

// g . c(p, V), or NaN when the closest feature differs from `hit` (then a
// difference would straddle a switch of feature, where c is not differentiable).
double projected(const Mesh& body, const Eigen::Vector3d& p, const SurfacePoint& hit, const Eigen::Vector3d& g) {
  const SurfacePoint s = BodySurface(body).locate(p);
  if (feature_vertices(body, s) != feature_vertices(body, hit)) return std::numeric_limits<double>::quiet_NaN();
  return g.dot(s.point);
}

}  // namespace

TEST_CASE("closest_point_backward matches finite differences on every kind of feature", "[losses][closest_point]") {
  const Mesh body = icosphere(1, 0.5);
  const BodySurface surface(body);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int seen[3] = {0, 0, 0};  // vertex, edge, interior
  int skipped = 0;
  double worst = 0.0;
  const double h = 1e-6;
  for (int trial = 0; trial < 300; ++trial) {
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    p *= (0.3 + 0.5 * std::abs(u(rng))) / p.norm();  // inside and outside the sphere
    const SurfacePoint hit = surface.locate(p);
    const Eigen::Vector3d g(u(rng), u(rng), u(rng));
    const ClosestPointGradient r = closest_point_backward(body.vertices, body.faces, p, hit, g);
    CHECK((r.query + r.corner[0] + r.corner[1] + r.corner[2] - g).norm() < 1e-12);  // translation moves c along
    bool ok = true;
    Eigen::Vector3d fd_p;
    for (int k = 0; k < 3 && ok; ++k) {
      const double plus = projected(body, p + h * Eigen::Vector3d::Unit(k), hit, g);
      const double minus = projected(body, p - h * Eigen::Vector3d::Unit(k), hit, g);
      ok = std::isfinite(plus) && std::isfinite(minus);
      fd_p[k] = (plus - minus) / (2 * h);
    }
    double error = (fd_p - r.query).norm() / g.norm();
    for (int c = 0; c < r.count && ok; ++c)
      for (int k = 0; k < 3 && ok; ++k) {
        Mesh moved = body;
        moved.vertices(r.vertex[c], k) += h;
        const double plus = projected(moved, p, hit, g);
        moved.vertices(r.vertex[c], k) -= 2 * h;
        const double minus = projected(moved, p, hit, g);
        ok = std::isfinite(plus) && std::isfinite(minus);
        error = std::max(error, std::abs((plus - minus) / (2 * h) - r.corner[c][k]) / g.norm());
      }
    if (!ok) {  // within a step of a feature switch
      ++skipped;
      continue;
    }
    worst = std::max(worst, error);
    ++seen[r.count == 1 ? 0 : r.count == 2 ? 1 : 2];
  }
  INFO("vertex " << seen[0] << ", edge " << seen[1] << ", interior " << seen[2] << ", skipped " << skipped
                  << ", worst " << worst);
  CHECK(skipped < 10);
  CHECK(seen[0] > 5);
  CHECK(seen[1] > 5);
  CHECK(seen[2] > 5);
  CHECK(worst < 1e-6);
}

TEST_CASE("closest_point_backward: the query gradient is the projection onto the feature", "[losses][closest_point]") {
  const Mesh cube = test::cube_body();
  const BodySurface surface(cube);
  const Eigen::Vector3d g(0.3, -0.7, 0.2);
  // Above the top face: c = (x, 1, z) follows x and z only.
  const Eigen::Vector3d above(0.3, 1.4, -0.5);
  auto r = closest_point_backward(cube.vertices, cube.faces, above, surface.locate(above), g);
  CHECK((r.query - Eigen::Vector3d(0.3, 0.0, 0.2)).norm() < 1e-12);
  // Beyond the edge x = y = 1: c = (1, 1, z) follows z only.
  const Eigen::Vector3d beyond_edge(1.5, 1.2, 0.4);
  r = closest_point_backward(cube.vertices, cube.faces, beyond_edge, surface.locate(beyond_edge), g);
  CHECK((r.query - Eigen::Vector3d(0.0, 0.0, 0.2)).norm() < 1e-12);
  // Beyond a corner: c is the corner, which carries the whole gradient.
  const Eigen::Vector3d beyond_corner(1.5, 1.2, 1.1);
  const SurfacePoint corner = surface.locate(beyond_corner);
  r = closest_point_backward(cube.vertices, cube.faces, beyond_corner, corner, g);
  CHECK(r.query.norm() == 0.0);
  REQUIRE(r.count == 1);
  CHECK(r.vertex[0] == 6);
  CHECK((r.corner[0] - g).norm() < 1e-12);
  SurfacePoint bad = corner;
  bad.face = 99;
  CHECK_THROWS_AS(closest_point_backward(cube.vertices, cube.faces, beyond_corner, bad, g), Error);
}
