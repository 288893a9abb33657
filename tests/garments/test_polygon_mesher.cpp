// 2D polygon helpers and the lattice mesher used for sewing-pattern panels.
#include <drape/errors.hpp>
#include <drape/geometry/polygon2d.hpp>
#include <drape/geometry/polygon_mesher.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <map>

using namespace drape;
using namespace drape::geometry;

namespace {

// An L-shaped loop with a concave corner, sampled about `h` apart.
Polygon2 l_shape(double h) {
  const Polygon2 corners{{0, 0}, {0.4, 0}, {0.4, 0.2}, {0.2, 0.2}, {0.2, 0.5}, {0, 0.5}};
  Polygon2 loop;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Polygon2 piece = resample_polyline({corners[i], corners[(i + 1) % corners.size()]},
                                             static_cast<int>(std::ceil((corners[(i + 1) % corners.size()] - corners[i]).norm() / h)));
    loop.insert(loop.end(), piece.begin(), piece.end() - 1);
  }
  return loop;
}

}  // namespace

TEST_CASE("signed area and point in polygon", "[geometry][polygon2d]") {
  const Polygon2 square{{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  CHECK(signed_area(square) == Approx(2.0));
  CHECK(signed_area(Polygon2(square.rbegin(), square.rend())) == Approx(-2.0));
  CHECK(point_in_polygon(square, {1.0, 0.5}));
  CHECK_FALSE(point_in_polygon(square, {2.5, 0.5}));
  CHECK_FALSE(point_in_polygon(l_shape(0.05), {0.3, 0.3}));  // in the notch of the L
  CHECK(point_in_polygon(l_shape(0.05), {0.1, 0.4}));
  CHECK(distance_to_boundary(square, {1.0, 0.25}) == Approx(0.25));
}

TEST_CASE("resampling keeps both ends exactly and spaces points evenly", "[geometry][polygon2d]") {
  const Polygon2 line{{0, 0}, {1, 0}, {1, 1}};
  const Polygon2 r = resample_polyline(line, 4);
  REQUIRE(r.size() == 5);
  CHECK(r.front() == line.front());
  CHECK(r.back() == line.back());
  for (std::size_t i = 1; i < r.size(); ++i) CHECK(polyline_length({r[i - 1], r[i]}) <= 0.5 + 1e-12);
  CHECK(r[2].isApprox(Eigen::Vector2d(1, 0)));
}

TEST_CASE("a flat coordinate list needs pairs of at least three points", "[geometry][polygon2d]") {
  CHECK(polygon_from_flat({0, 0, 1, 0, 1, 1}, "print").size() == 3);
  CHECK_THROWS_AS(polygon_from_flat({0, 0, 1, 0, 1}, "print"), ConfigError);
  CHECK_THROWS_AS(polygon_from_flat({0, 0, 1, 0}, "print"), ConfigError);
}

TEST_CASE("the mesher tiles a concave polygon with well-shaped triangles", "[geometry][mesher]") {
  const double h = 0.03;
  const Polygon2 loop = l_shape(h);
  const PlanarMesh mesh = mesh_polygon(loop, h);
  REQUIRE(mesh.num_boundary == static_cast<int>(loop.size()));
  for (int i = 0; i < mesh.num_boundary; ++i) CHECK(mesh.points[i] == loop[i]);  // boundary kept bit for bit
  double area = 0;
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector2d a = mesh.points[t[1]] - mesh.points[t[0]], b = mesh.points[t[2]] - mesh.points[t[0]];
    const double twice = a.x() * b.y() - a.y() * b.x();
    CHECK(twice > 0);
    area += twice / 2;
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  // Exact cover: the triangles add up to the polygon and every boundary edge is used once.
  CHECK(area == Approx(signed_area(loop)).epsilon(1e-9));
  for (int i = 0; i < mesh.num_boundary; ++i) CHECK(directed.count({i, (i + 1) % mesh.num_boundary}) == 1);
  for (const auto& [e, n] : directed) CHECK(n == 1);  // no edge twice in one direction: no overlap
  const double angle = min_angle_degrees(mesh.points, mesh.triangles);
  INFO("min angle " << angle);
  CHECK(angle > 20);
  // Lattice density: about one point per sqrt(3)/2 h^2.
  const double expected = signed_area(loop) / (std::sqrt(3.0) / 2 * h * h);
  CHECK(static_cast<double>(mesh.points.size()) == Approx(expected).epsilon(0.25));
}

TEST_CASE("the mesher refuses a clockwise loop", "[geometry][mesher]") {
  Polygon2 loop = l_shape(0.05);
  std::reverse(loop.begin(), loop.end());
  CHECK_THROWS_AS(mesh_polygon(loop, 0.05), Error);
}
