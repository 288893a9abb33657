// winding_numbers: inside and outside of a cube against its exact signed
// distance written out by hand, overlapping and inside-out parts, points on
// the surface, a zero-area face, and the case it was written for: a sphere
// shrunk along its normals past its centre, where the closest face's
// pseudo-normal puts outside points inside.
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/winding.hpp>

#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <cmath>
#include <random>

using namespace drape;
using namespace drape::geometry;

namespace {

// The cube [-1, 1]^3 shifted by `shift` along x, as 12 outward triangles.
void add_cube(Eigen::MatrixX3d& v, Eigen::MatrixX3i& f, double shift = 0) {
  Eigen::MatrixX3d cv(8, 3);
  cv << -1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1;
  cv.col(0).array() += shift;
  Eigen::MatrixX3i cf(12, 3);
  cf << 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2, 4, 5, 6, 4, 6, 7, 0, 3, 2, 0, 2, 1, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3;
  cf.array() += static_cast<int>(v.rows());
  Eigen::MatrixX3d nv(v.rows() + 8, 3);
  nv << v, cv;
  Eigen::MatrixX3i nf(f.rows() + 12, 3);
  nf << f, cf;
  v = nv;
  f = nf;
}

// The exact signed distance to the box [-1, 1]^3 (Quilez's sdBox).
double box_distance(const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p.cwiseAbs() - Eigen::Vector3d::Ones();
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

}  // namespace

TEST_CASE("winding numbers: 1 inside a cube and 0 outside, as its exact signed distance says", "[geometry][winding]") {
  Eigen::MatrixX3d v(0, 3);
  Eigen::MatrixX3i f(0, 3);
  add_cube(v, f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  Eigen::MatrixX3d points(2000, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (int k = 0; k < 3; ++k) points(i, k) = coordinate(rng);
  const std::vector<int> w = winding_numbers(points, v, f);
  int inside = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double d = box_distance(points.row(i).transpose());
    INFO("point " << points.row(i) << ", signed distance " << d);
    CHECK(w[static_cast<std::size_t>(i)] == (d < 0 ? 1 : 0));
    inside += d < 0;
  }
  CHECK(inside > 400);  // both sides were sampled (8/27 of the box is the cube)
}

TEST_CASE("winding numbers count overlapping parts, inside-out parts and points on the surface", "[geometry][winding]") {
  Eigen::MatrixX3d v(0, 3);
  Eigen::MatrixX3i f(0, 3);
  add_cube(v, f);
  add_cube(v, f, 1.0);  // a second cube over x in [0, 2]: the mesh passes through itself
  Eigen::MatrixX3d p(4, 3);
  p << 0.5, 0.1, 0.2, -0.5, 0.1, 0.2, 1.5, 0.1, 0.2, 3.0, 0.1, 0.2;
  CHECK(winding_numbers(p, v, f) == std::vector<int>{2, 1, 1, 0});

  Eigen::MatrixX3d cube(0, 3);
  Eigen::MatrixX3i faces(0, 3);
  add_cube(cube, faces);
  const Eigen::MatrixX3i reversed = faces.rowwise().reverse();  // clockwise: turned inside out
  Eigen::MatrixX3d q(2, 3);
  q << 0.3, -0.2, 0.1, 1.2, 0.0, 0.0;
  CHECK(winding_numbers(q, cube, reversed) == std::vector<int>{-1, 0});

  // On a face, on an edge and on a corner: on the surface, whatever the ray.
  Eigen::MatrixX3d s(3, 3);
  s << 1.0, 0.2, 0.3, 1.0, 1.0, 0.3, -1.0, -1.0, 1.0;
  CHECK(winding_numbers(s, cube, faces) == std::vector<int>{kOnSurface, kOnSurface, kOnSurface});

  // A zero-area face added across the cube changes nothing.
  Eigen::MatrixX3d with_sliver(cube.rows() + 3, 3);
  with_sliver << cube, -2.0, 0.1, 0.2, 0.0, 0.1, 0.2, 2.0, 0.1, 0.2;
  Eigen::MatrixX3i sliver_faces(faces.rows() + 1, 3);
  sliver_faces << faces, 8, 9, 10;
  Eigen::MatrixX3d r(2, 3);
  r << -0.5, 0.1, 0.2, -1.5, 0.1, 0.2;
  CHECK(winding_numbers(r, with_sliver, sliver_faces) == std::vector<int>{1, 0});
}

TEST_CASE("winding numbers on a sphere shrunk past its centre, where the pseudo-normal sign is wrong", "[geometry][winding]") {
  const Mesh ball = test::uv_sphere(1.0, 16, 24);
  const Eigen::MatrixX3d& v = ball.vertices;
  const Eigen::MatrixX3i& f = ball.faces;
  const BodySurface sphere(v, f);
  // Moved 1.5 along the inward normals every vertex lands at half the radius
  // on the far side: a sphere of radius 0.5, inside out.
  const Eigen::MatrixX3d shrunk = v - 1.5 * sphere.vertex_normals();
  const BodySurface shrunk_surface(shrunk, f);
  Eigen::MatrixX3d p(3, 3);
  p << 0.7, 0.05, 0.02, 0.0, 0.2, 0.1, 2.0, 0.3, 0.0;
  // A point outside the small sphere's volume: its closest face faces the
  // centre, so the pseudo-normal sign calls it inside...
  CHECK(shrunk_surface.signed_distances(p)[0] < 0);
  // ...while the surface does not wrap it at all.
  CHECK(winding_numbers(p, shrunk, f) == std::vector<int>{0, -1, 0});
  CHECK(winding_numbers(p, v, f) == std::vector<int>{1, 1, 0});
}

TEST_CASE("winding numbers: a face naming a missing vertex and a non-finite point are refused", "[geometry][winding]") {
  Eigen::MatrixX3d v(0, 3);
  Eigen::MatrixX3i f(0, 3);
  add_cube(v, f);
  Eigen::MatrixX3i bad = f;
  bad(3, 1) = 8;
  Eigen::MatrixX3d p(1, 3);
  p << 0, 0, 0;
  CHECK_THROWS_WITH(winding_numbers(p, v, bad), Catch::Contains("face 3 names vertex 8 of a surface with 8"));
  p(0, 2) = NAN;
  CHECK_THROWS_WITH(winding_numbers(p, v, f), Catch::Contains("query point is not finite"));
}
