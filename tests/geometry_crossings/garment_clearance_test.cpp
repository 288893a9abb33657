// The garment clearance (push-out, then untangle with each round's moves
// pushed out again): a strip folded over itself lies just above a body (a
// slab), with a bump of its upper layer pushed through the lower layer and
// into the slab. Undoing the crossing moves the lower layer's disc down
// half the way, into the slab; the clearance must end with no crossing (a
// brute-force count of folded_strip.hpp) and every vertex the margin above
// the slab (its signed distance written out by hand), where the untangle
// alone leaves the disc inside.
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/garment_clearance.hpp>

#include <catch2/catch.hpp>

#include "folded_strip.hpp"

#include <algorithm>
#include <vector>

using namespace drape::geometry;
using namespace drape::test;

namespace {

// The slab [-1, 2] x [-1, 2] x [-1, top] as 12 outward triangles.
BodySurface slab(double top) {
  Eigen::MatrixX3d v(8, 3);
  v << -1, -1, -1, 2, -1, -1, 2, 2, -1, -1, 2, -1, -1, -1, top, 2, -1, top, 2, 2, top, -1, 2, top;
  Eigen::MatrixX3i f(12, 3);
  f << 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2, 4, 5, 6, 4, 6, 7, 0, 3, 2, 0, 2, 1, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3;
  return BodySurface(v, f);
}

// The lowest height above the slab's top over the strip's vertices (they all
// lie over its top face, far from its sides).
double lowest_clearance(const Eigen::MatrixX3d& x, double top) { return x.col(2).minCoeff() - top; }

}  // namespace

TEST_CASE("garment clearance: a bump through the strip's lower layer is undone and both layers kept off the body") {
  const double height = 0.02, depth = 0.006, top = -0.002, margin = 0.001;
  Strip s = folded_strip(41, 21, height);
  push_bump(s, 0.503, 0.497, 0.1, depth, height);  // the bump's tip 4 mm into the slab
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings > 10);
  REQUIRE(lowest_clearance(s.x, top) < 0);
  const BodySurface body = slab(top);

  GarmentClearanceOptions options;
  options.margin = margin;
  GarmentClearance clearance(s.faces, static_cast<int>(s.x.rows()), options);

  SECTION("the push-out alone keeps the body off but leaves the crossing") {
    Eigen::MatrixX3d x = s.x;
    clearance.push_out(body, x);
    CHECK(lowest_clearance(x, top) >= margin - 1e-12);
    CHECK(brute_force_crossings(x, s.faces) > 0);
  }
  SECTION("the untangle without the push-out after its rounds puts the lower layer into the body") {
    Eigen::MatrixX3d x = s.x;
    clearance.push_out(body, x);
    UntangleOptions untangling;
    untangling.gap = options.self_gap;
    untangling.max_rounds = options.untangle_rounds;
    untangle(x, s.faces, untangling);
    CHECK(brute_force_crossings(x, s.faces) == 0);
    CHECK(lowest_clearance(x, top) < 0.5 * margin);
  }
  SECTION("the clearance: no crossing, every vertex the margin off the body") {
    Eigen::MatrixX3d x = s.x;
    const GarmentClearance::Report report = clearance.run(body, x, nullptr);
    CHECK(report.pushed.moved > 0);
    CHECK(report.untangled.crossings_before > 0);
    CHECK(report.untangled.crossings_after == 0);
    CHECK(brute_force_crossings(x, s.faces) == 0);
    // (push_out_moved keeps the margin's promise up to its own last pass.)
    CHECK(lowest_clearance(x, top) >= margin - 1e-12);
    // Far from the bump nothing moved.
    for (int v = 0; v < x.rows(); ++v)
      if (std::hypot(s.x(v, 0) - 0.503, s.x(v, 1) - 0.497) > 0.3) CHECK(x.row(v) == s.x.row(v));
  }
}

TEST_CASE("garment clearance: pushing out what moved needs the whole push-out first") {
  Strip s = folded_strip(5, 3, 0.02);
  GarmentClearance clearance(s.faces, static_cast<int>(s.x.rows()));
  const BodySurface body = slab(-0.01);
  Eigen::MatrixX3d x = s.x;
  std::vector<char> moved(static_cast<std::size_t>(x.rows()), 1);
  CHECK_THROWS_WITH(clearance.push_out_moved(body, x, moved), Catch::Contains("push_out first"));
  clearance.push_out(body, x);
  CHECK_NOTHROW(clearance.push_out_moved(body, x, moved));
  GarmentClearanceOptions bad;
  bad.untangle_rounds = 0;
  CHECK_THROWS_AS(GarmentClearance(s.faces, static_cast<int>(s.x.rows()), bad), drape::Error);
}
