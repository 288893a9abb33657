// push_out: vertices inside or too near a body end `margin` outside it,
// checked with the box's signed distance written out by hand (no BodySurface).
#include <drape/geometry/push_out.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace drape;
using namespace drape::geometry;

namespace {

// The cube [-1, 1]^3 as 12 outward triangles.
BodySurface unit_cube() {
  Eigen::MatrixX3d v(8, 3);
  v << -1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1;
  Eigen::MatrixX3i f(12, 3);
  f << 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2, 4, 5, 6, 4, 6, 7, 0, 3, 2, 0, 2, 1, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3;
  return BodySurface(v, f);
}

// The exact signed distance to the box [-1, 1]^3 (Quilez's sdBox).
double pushed_box_distance(const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p.cwiseAbs() - Eigen::Vector3d::Ones();
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

}  // namespace

TEST_CASE("push_out moves the vertices inside or within the margin to the margin, and no other", "[geometry][push_out]") {
  const BodySurface cube = unit_cube();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.3, 1.3);
  Eigen::MatrixX3d x(400, 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int k = 0; k < 3; ++k) x(i, k) = coordinate(rng);
  const Eigen::MatrixX3d before = x;
  const double margin = 0.01;
  const PushOutReport report = push_out(cube, x, margin);
  int inside_before = 0, moved = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const double d0 = pushed_box_distance(before.row(i).transpose()), d1 = pushed_box_distance(x.row(i).transpose());
    inside_before += d0 < 0;
    INFO("vertex " << i << " from distance " << d0);
    if (d0 >= margin) {
      CHECK(x.row(i) == before.row(i));
    } else {
      ++moved;
      // Inside: straight out through the nearest face, to the margin. Outside
      // within it: away from the closest point (face, edge or corner), to the margin.
      CHECK(d1 == Approx(margin).margin(1e-9));
    }
  }
  CHECK(inside_before > 100);
  CHECK(report.moved == moved);
  CHECK(report.still_within == 0);
  CHECK(report.passes == 2);  // one to move, one to find nothing left
  CHECK(report.largest_move <= 1.0 + margin + 1e-9);
  CHECK(report.largest_move > 0.5);

  Eigen::MatrixX3d bad = before;
  bad(3, 1) = NAN;
  CHECK_THROWS_WITH(push_out(cube, bad, margin), Catch::Contains("non-finite"));
  CHECK_THROWS_WITH(push_out(cube, x, -1.0), Catch::Contains("margin"));
}

TEST_CASE("push_out: a vertex under a tent's ridge goes out through the nearer roof", "[geometry][push_out]") {
  Eigen::MatrixX3d v(6, 3);
  // A triangular prism (tent): ridge along z at y = 1, feet at x = +-1, y = 0.
  v << -1, 0, -1, 1, 0, -1, 0, 1, -1, -1, 0, 1, 1, 0, 1, 0, 1, 1;
  Eigen::MatrixX3i f(8, 3);
  f << 0, 2, 1, 3, 4, 5,  // the two ends (z = -1 facing -z, z = 1 facing +z)
      0, 1, 4, 0, 4, 3,   // the floor, facing -y
      1, 2, 5, 1, 5, 4,   // the right roof
      2, 0, 3, 2, 3, 5;   // the left roof
  const BodySurface tent(v, f);
  // Inside, just under the ridge and right of it: the right roof (y = 1 - x)
  // is nearest; pushed along its normal (1, 1, 0) / sqrt(2) to 1 cm outside it.
  Eigen::MatrixX3d x(1, 3);
  x << 0.05, 0.9, 0.0;
  const PushOutReport r = push_out(tent, x, 0.01);
  CHECK(r.still_within == 0);
  const double right_roof = (x(0, 0) + x(0, 1) - 1.0) / std::sqrt(2.0);  // signed distance to the plane x + y = 1
  CHECK(right_roof == Approx(0.01).margin(1e-12));
  CHECK(x(0, 0) - x(0, 1) == Approx(0.05 - 0.9).margin(1e-12));  // moved along the normal only
  CHECK(x(0, 2) == 0.0);
}

// A garment pushed out of body after body: the closest faces of the last body
// start the next body's searches (hints right, stale, wrong or of the wrong
// count) and the normals are left to the queries; the vertices end on the
// same bits as a push-out from a fresh surface without hints.
TEST_CASE("push_out with the last body's faces as hints moves the vertices to the same bits", "[geometry][push_out]") {
  const BodySurface fresh = unit_cube();
  BodySurface kept = unit_cube();
  Eigen::MatrixX3d stretched = fresh.vertices();
  stretched.col(1) *= 1.2;
  kept.update(stretched);  // another body first, so the hints are stale
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.3, 1.3);
  Eigen::MatrixX3d x(300, 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int k = 0; k < 3; ++k) x(i, k) = coordinate(rng);
  std::vector<int> hints;
  Eigen::MatrixX3d first = x;
  push_out(kept, first, 0.01, 4, &hints);  // the stretched body's faces
  REQUIRE(hints.size() == 300);
  kept.update(fresh.vertices(), BodySurface::Normals::on_demand);
  Eigen::MatrixX3d expected = x;
  const PushOutReport plain = push_out(fresh, expected, 0.01);
  std::uniform_int_distribution<int> any_face(-1, 11);
  std::vector<int> wrong(300);
  for (int& f : wrong) f = any_face(rng);
  for (std::vector<int> given : {hints, wrong, std::vector<int>(7, 3)}) {
    Eigen::MatrixX3d y = x;
    const PushOutReport r = push_out(kept, y, 0.01, 4, &given);
    CHECK(y == expected);
    CHECK(r.moved == plain.moved);
    CHECK(r.passes == plain.passes);
    REQUIRE(given.size() == 300);
    for (Eigen::Index i = 0; i < y.rows(); ++i) CHECK(given[static_cast<std::size_t>(i)] == fresh.locate(y.row(i).transpose()).face);
  }
}
