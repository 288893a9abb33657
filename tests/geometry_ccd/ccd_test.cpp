// Primitive distances against values worked out by hand and an independent
// long-double search; continuous collision detection against hand-computed
// times of impact and dense sampling of random trajectories; and the broad
// phase's box pairs against a double loop.
#include <drape/geometry/box_pairs.hpp>
#include <drape/geometry/ccd.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

using namespace drape::geometry;
using V = Eigen::Vector3d;

namespace {

// The triangle most cases use: the unit right triangle in the plane z = 0.
const V A(0, 0, 0), B(1, 0, 0), C(0, 1, 0);
const V zero = V::Zero();

// ---- Independent references (share no code with the library) ----

using VL = Eigen::Matrix<long double, 3, 1>;

long double point_segment_distance2(const VL& p, const VL& a, const VL& b) {
  const VL e = b - a;
  const long double len2 = e.squaredNorm();
  const long double t = len2 > 0 ? std::clamp((p - a).dot(e) / len2, 0.0L, 1.0L) : 0.0L;
  return (a + t * e - p).squaredNorm();
}

// The distance from a(s) to segment b is convex in s (the distance to a convex
// set along a line), so a golden-section search over s finds the minimum.
long double segment_distance2_reference(const V& a0, const V& a1, const V& b0, const V& b1) {
  const VL p = a0.cast<long double>(), q = a1.cast<long double>(), r = b0.cast<long double>(), s = b1.cast<long double>();
  auto f = [&](long double t) { return point_segment_distance2(p + t * (q - p), r, s); };
  const long double g = (std::sqrt(5.0L) - 1) / 2;
  long double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const long double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (f(m1) < f(m2)) hi = m2;
    else lo = m1;
  }
  return std::min({f(0), f(1), f((lo + hi) / 2)});
}

// Positions at time t of a linear trajectory.
V at(const V& x, const V& dx, double t) { return x + t * dx; }

double pt_distance(const V& p, const V& dp, const V& a, const V& da, const V& b, const V& db, const V& c, const V& dc,
                   double t) {
  return std::sqrt(point_triangle_distance2(at(p, dp, t), at(a, da, t), at(b, db, t), at(c, dc, t)));
}

double ee_distance(const V& a0, const V& da0, const V& a1, const V& da1, const V& b0, const V& db0, const V& b1,
                   const V& db1, double t) {
  return std::sqrt(edge_edge_distance2(at(a0, da0, t), at(a1, da1, t), at(b0, db0, t), at(b1, db1, t)));
}

}  // namespace

// ---------------------------------------------------------------- distances

TEST_CASE("point-triangle distance: interior, edge, vertex and degenerate triangles") {
  // Above the interior: straight down to (0.25, 0.25, 0).
  CHECK(point_triangle_distance2({0.25, 0.25, 2}, A, B, C) == Approx(4.0));
  // Beyond edge bc: the projection (1, 1, 0) is outside, the nearest point is
  // the edge's midpoint (0.5, 0.5, 0): 0.25 + 0.25 + 1.
  CHECK(point_triangle_distance2({1, 1, 1}, A, B, C) == Approx(1.5));
  // Below edge ab: nearest (0.5, 0, 0): 1 + 0.25.
  CHECK(point_triangle_distance2({0.5, -1, 0.5}, A, B, C) == Approx(1.25));
  // Behind vertex a: 1 + 4 + 4.
  CHECK(point_triangle_distance2({-1, -2, 2}, A, B, C) == Approx(9.0));
  // In the plane, inside: 0 (to rounding of the barycentric weights).
  CHECK(point_triangle_distance2({0.2, 0.3, 0}, A, B, C) < 1e-30);
  // Collinear corners: the segment from (0,0,0) to (2,0,0), nearest (1.5,0,0).
  CHECK(point_triangle_distance2({1.5, 1, 1}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}) == Approx(2.0));
  // All corners in one point: 0 + 1 + 4.
  CHECK(point_triangle_distance2({1, 2, 3}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}) == Approx(5.0));
}

TEST_CASE("edge-edge distance: crossing, skew, parallel, collinear and zero-length segments") {
  // Crossing at the origin.
  CHECK(edge_edge_distance2({-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}) == 0.0);
  // Skew, closest inside both: a(s) = (2s, 2s, 0), b(t) = (2 - 2t, 2t, 1 + 2t).
  // n = u x v = (4, -4, 8), w = b0 - a0 = (2, 0, 1): distance |w.n| / |n| =
  // 16 / sqrt(96), squared 8/3, at s = 1/2 (1, 1, 0) and t = 1/6 (5/3, 1/3, 4/3).
  {
    const V a0(0, 0, 0), a1(2, 2, 0), b0(2, 0, 1), b1(0, 2, 3);
    CHECK(edge_edge_distance2(a0, a1, b0, b1) == Approx(8.0 / 3));
    const SegmentPoints q = closest_points_on_segments(a0, a1, b0, b1);
    CHECK(q.s == Approx(0.5));
    CHECK(q.t == Approx(1.0 / 6));
    CHECK((q.on_a - V(1, 1, 0)).norm() < 1e-12);
    CHECK((q.on_b - V(5.0 / 3, 1.0 / 3, 4.0 / 3)).norm() < 1e-12);
  }
  // Skew with the closest point of one at its endpoint: b(t) = (1, 1 - 2t, 1 + 2t)
  // is at squared distance (1 - 2t)^2 + (1 + 2t)^2 = 2 + 8 t^2 from the x axis.
  CHECK(edge_edge_distance2({0, 0, 0}, {2, 0, 0}, {1, 1, 1}, {1, -1, 3}) == Approx(2.0));
  // Parallel, overlapping in x over [1, 2], one apart.
  CHECK(edge_edge_distance2({0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {3, 1, 0}) == Approx(1.0));
  // The same, antiparallel.
  CHECK(edge_edge_distance2({0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {1, 1, 0}) == Approx(1.0));
  // Parallel, disjoint: (1,0,0) to (3,1,0).
  CHECK(edge_edge_distance2({0, 0, 0}, {1, 0, 0}, {3, 1, 0}, {4, 1, 0}) == Approx(5.0));
  // Collinear, disjoint and overlapping.
  CHECK(edge_edge_distance2({0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {5, 0, 0}) == Approx(4.0));
  CHECK(edge_edge_distance2({0, 0, 0}, {1, 0, 0}, {0.5, 0, 0}, {3, 0, 0}) == 0.0);
  // A zero-length segment is a point: (1,1,1) to the segment on the x axis.
  CHECK(edge_edge_distance2({1, 1, 1}, {1, 1, 1}, {0, 0, 0}, {2, 0, 0}) == Approx(2.0));
  CHECK(edge_edge_distance2({0, 0, 0}, {2, 0, 0}, {3, 1, 1}, {3, 1, 1}) == Approx(3.0));
  // Two points.
  CHECK(edge_edge_distance2({0, 0, 0}, {0, 0, 0}, {1, 2, 2}, {1, 2, 2}) == Approx(9.0));
}

TEST_CASE("edge-edge distance matches a long-double search on random and near-parallel segments") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  auto point = [&] { return V(u(rng), u(rng), u(rng)); };
  for (int i = 0; i < 4000; ++i) {
    const V a0 = point(), a1 = point(), b0 = point();
    V b1 = point();
    switch (i % 4) {
      case 1: b1 = b0 + (a1 - a0) * (2 * unit(rng)) + std::pow(10.0, -4 - 10 * unit(rng)) * point(); break;  // near-parallel
      case 2: b1 = b0 + (a0 - a1) * unit(rng); break;                                                      // exactly parallel
      case 3: b1 = b0; break;                                                                             // a point
      default: break;
    }
    const double got = std::sqrt(edge_edge_distance2(a0, a1, b0, b1));
    const double want = static_cast<double>(std::sqrt(segment_distance2_reference(a0, a1, b0, b1)));
    INFO("case " << i);
    CHECK(std::abs(got - want) <= 1e-9);
    // The pair reported is a pair of points of the segments at that distance.
    const SegmentPoints q = closest_points_on_segments(a0, a1, b0, b1);
    CHECK((q.on_a - (a0 + q.s * (a1 - a0))).norm() < 1e-12);
    CHECK((q.on_b - (b0 + q.t * (b1 - b0))).norm() < 1e-12);
    CHECK(std::abs((q.on_a - q.on_b).norm() - got) < 1e-12);
  }
}

// ---------------------------------------------------------------- point-triangle CCD

TEST_CASE("point-triangle CCD: a point moving straight through the interior stops before impact") {
  // From height 1 down by 2: impact at t = 0.5, 10% of the start distance left at t = 0.45.
  const V p(0.25, 0.25, 1), dp(0, 0, -2);
  const double t = point_triangle_ccd(p, dp, A, zero, B, zero, C, zero);
  CHECK(t <= 0.5);
  CHECK(t >= 0.25);
  CHECK(pt_distance(p, dp, A, zero, B, zero, C, zero, t) >= 0.1 * (1 - 1e-9));
  // A stricter separation ratio stops earlier: 50% of the distance left at t = 0.25.
  const double strict = point_triangle_ccd(p, dp, A, zero, B, zero, C, zero, 0.5);
  CHECK(strict <= 0.25 + 1e-12);
  CHECK(strict > 0);
}

TEST_CASE("point-triangle CCD: a point passing beside the triangle returns 1") {
  // Straight down through (2, 2, 0): never nearer than the distance from
  // (2, 2, 0) to edge bc's midpoint, sqrt(4.5) = 2.12, against 0.1 * sqrt(29.5) = 0.54.
  CHECK(point_triangle_ccd({2, 2, 5}, {0, 0, -10}, A, zero, B, zero, C, zero) == 1.0);
  // Moving away.
  CHECK(point_triangle_ccd({0.2, 0.2, 0.1}, {0, 0, 5}, A, zero, B, zero, C, zero) == 1.0);
  // Not moving relative to the triangle: a common translation.
  const V shift(3, -1, 7);
  CHECK(point_triangle_ccd({0.2, 0.2, 0.1}, shift, A, shift, B, shift, C, shift) == 1.0);
}

TEST_CASE("point-triangle CCD: a triangle moving onto a static point") {
  // The triangle at z = 1 moves down by 3 onto (0.2, 0.2, 0): impact at t = 1/3.
  const V p(0.2, 0.2, 0), up(0, 0, 1), d(0, 0, -3);
  const double t = point_triangle_ccd(p, zero, A + up, d, B + up, d, C + up, d);
  CHECK(t <= 1.0 / 3);
  CHECK(t >= 1.0 / 6);
  CHECK(pt_distance(p, zero, A + up, d, B + up, d, C + up, d, t) > 0);
}

TEST_CASE("point-triangle CCD: both moving, with a common sideways drift") {
  // Point at z = 1 moving down by 1, triangle at z = -1 moving up by 3, both
  // drifting by (1, 0.5, 0): the gap 2 - 4t closes at t = 0.5 above the same spot.
  const V drift(1, 0.5, 0), p(0.25, 0.25, 1), dp = V(0, 0, -1) + drift, down(0, 0, -1), dt = V(0, 0, 3) + drift;
  const double t = point_triangle_ccd(p, dp, A + down, dt, B + down, dt, C + down, dt);
  CHECK(t <= 0.5);
  CHECK(t >= 0.25);
  CHECK(pt_distance(p, dp, A + down, dt, B + down, dt, C + down, dt, t) > 0);
}

TEST_CASE("point-triangle CCD: grazing at 1e-6 over the triangle") {
  // Sliding over the interior at constant height 1e-6: the distance never
  // falls, so the whole step is safe. (Additive CCD alone would step 0.9e-6 /
  // 0.5 at a time and run out of iterations; a certificate settles it.)
  CHECK(point_triangle_ccd({0.1, 0.25, 1e-6}, {0.5, 0, 0}, A, zero, B, zero, C, zero) == 1.0);
  // Sliding over and off the far edge: the distance only grows.
  CHECK(point_triangle_ccd({0.1, 0.25, 1e-6}, {1.5, 0, 0}, A, zero, B, zero, C, zero) == 1.0);
  // Underneath, sliding the other way while the triangle drifts too.
  const V drift(0.3, 0.1, 0);
  CHECK(point_triangle_ccd({0.4, 0.3, -1e-6}, {-0.3, -0.2, 0}, A, drift, B, drift, C, drift) == 1.0);
  // Sliding at 1e-6 while the triangle tilts about its diagonal (b rises and c
  // sinks by 1e-3), the point staying over the sinking half: its plane at the
  // point is at z = 1e-3 t (x - y) = -1e-4 t, always below. No fixed plane
  // separates them all step (b rises above the point), and Additive CCD would
  // take thousands of steps, but the point never reaches the triangle's plane.
  CHECK(point_triangle_ccd({0.1, 0.2, 1e-6}, {0.1, 0.1, 0}, A, zero, B, {0, 0, 1e-3}, C, {0, 0, -1e-3}) == 1.0);
  // Coming from afar at 1e-6 over the plane, x from -1 to 2, passing over the
  // whole triangle at 1e-6 and leaving it far behind (distance 1.2 at the
  // end, more than 10% of the start distance 1): the point never touches, so
  // the whole step is safe, however close it passes in between. That is what
  // a barrier's line search needs: no crossing along the way, separation at
  // the end.
  CHECK(point_triangle_ccd({-1, 0.25, 1e-6}, {3, 0, 0}, A, zero, B, zero, C, zero) == 1.0);
  // The same, but sinking by 2e-6: it goes through the triangle at t = 0.5
  // (x = 0.5). Its distance, about |x| before the edge at x = 0, reaches 10%
  // of the start at x = -0.1, t = 0.3: the answer must stop there, separated.
  const V p(-1, 0.25, 1e-6), dp(3, 0, -2e-6);
  const double t = point_triangle_ccd(p, dp, A, zero, B, zero, C, zero);
  CHECK(t <= 0.3 + 1e-9);
  CHECK(t >= 0.15);
  CHECK(pt_distance(p, dp, A, zero, B, zero, C, zero, t) >= 0.1 * (1 - 1e-9));
}

TEST_CASE("point-triangle CCD: sinking slowly from 1e-6 is stopped before contact") {
  // From 1e-6 above down by 2e-6 while sliding by 0.5: contact at t = 0.5, 10%
  // of the distance left at t = 0.45. (Additive CCD alone would crawl at
  // steps of ~2e-6 and stop at its iteration limit near t = 0.002.)
  const V p(0.1, 0.25, 1e-6), dp(0.5, 0, -2e-6);
  const double t = point_triangle_ccd(p, dp, A, zero, B, zero, C, zero);
  CHECK(t < 0.5);
  CHECK(t >= 0.25);
  CHECK(pt_distance(p, dp, A, zero, B, zero, C, zero, t) >= 0.1e-6 * (1 - 1e-6));
}

TEST_CASE("point-triangle CCD: touching at the start returns 0") {
  CHECK(point_triangle_ccd({0.25, 0.25, 0}, {0, 0, 1}, A, zero, B, zero, C, zero) == 0.0);
  CHECK(point_triangle_ccd({0.5, 0.5, 0}, {0, 0, -1}, A, zero, B, zero, C, zero) == 0.0);  // on edge bc
  CHECK(point_triangle_ccd(B, {1, 1, 1}, A, zero, B, zero, C, zero) == 0.0);                // on a corner
  CHECK(edge_edge_ccd({-1, 0, 0}, zero, {1, 0, 0}, zero, {0, -1, 0}, {0, 0, 1}, {0, 1, 0}, {0, 0, 1}) == 0.0);
}

TEST_CASE("CCD: the separation ratio must lie in (0, 1)") {
  CHECK_THROWS_AS(point_triangle_ccd({0, 0, 1}, zero, A, zero, B, zero, C, zero, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(edge_edge_ccd(A, zero, B, zero, C, zero, {0, 0, 1}, zero, 1.0), std::invalid_argument);
}

TEST_CASE("CCD: running out of iterations returns a safe, separated time") {
  // Passing beside the triangle (as above) takes a few steps; after one the
  // answer is short of 1 but safe, and with none it is 0.
  const V p(2, 2, 5), dp(0, 0, -10);
  const double d0 = pt_distance(p, dp, A, zero, B, zero, C, zero, 0);
  CHECK(point_triangle_ccd(p, dp, A, zero, B, zero, C, zero) == 1.0);
  const double t = point_triangle_ccd(p, dp, A, zero, B, zero, C, zero, 0.1, 1);
  CHECK(t > 0);
  CHECK(t < 1);
  CHECK(pt_distance(p, dp, A, zero, B, zero, C, zero, t) >= 0.1 * d0);
  CHECK(point_triangle_ccd(p, dp, A, zero, B, zero, C, zero, 0.1, 0) == 0.0);
}

// ---------------------------------------------------------------- edge-edge CCD

TEST_CASE("edge-edge CCD: two edges crossing") {
  // Edge b, along y at height 1, comes down by 2 onto edge a along x: impact at t = 0.5.
  const V a0(-1, 0, 0), a1(1, 0, 0), b0(0.3, -1, 1), b1(0.3, 1, 1), d(0, 0, -2);
  const double t = edge_edge_ccd(a0, zero, a1, zero, b0, d, b1, d);
  CHECK(t <= 0.5);
  CHECK(t >= 0.25);
  CHECK(ee_distance(a0, zero, a1, zero, b0, d, b1, d, t) >= 0.1 * (1 - 1e-9));
  // A diagonal approach: c, parallel to y, moves by (-2, -2, -2) from x = 1.3,
  // z = 1. It can only meet a (on the x axis) at z = 0, t = 0.5, where it
  // spans y in [-1, 1] at x = 0.3: it crosses a at (0.3, 0, 0).
  const V c0(1.3, 0, 1), c1(1.3, 2, 1), dc(-2, -2, -2);
  const double u = edge_edge_ccd(a0, zero, a1, zero, c0, dc, c1, dc);
  CHECK(u <= 0.5);
  CHECK(u >= 0.2);
  CHECK(ee_distance(a0, zero, a1, zero, c0, dc, c1, dc, u) > 0);
}

TEST_CASE("edge-edge CCD: parallel edges moving toward each other") {
  // a along x at z = 0 rising by 0.5, b along x over [0.5, 1.5] at z = 1
  // falling by 1.5: the gap 1 - 2t closes at t = 0.5 (over x in [0.5, 1]).
  const V up(0, 0, 0.5), down(0, 0, -1.5);
  const V a0(0, 0, 0), a1(1, 0, 0), b0(0.5, 0, 1), b1(1.5, 0, 1);
  const double t = edge_edge_ccd(a0, up, a1, up, b0, down, b1, down);
  CHECK(t <= 0.5);
  CHECK(t >= 0.25);
  CHECK(ee_distance(a0, up, a1, up, b0, down, b1, down, t) >= 0.1 * (1 - 1e-9));
  // Collinear, end to end: a = [0, 1] on x, b = [2, 3] moving by -2: contact at t = 0.5.
  const V left(-2, 0, 0);
  const double u = edge_edge_ccd(a0, zero, a1, zero, {2, 0, 0}, left, {3, 0, 0}, left);
  CHECK(u <= 0.5);
  CHECK(u >= 0.25);
}

TEST_CASE("edge-edge CCD: edges sliding past each other without touching return 1") {
  // b, along y at height 1, passes over a from x = 2 to x = -2: the distance
  // never drops below 1, against 0.1 of the start distance sqrt(2).
  const V left(-4, 0, 0);
  CHECK(edge_edge_ccd({0, 0, 0}, zero, {1, 0, 0}, zero, {2, -1, 1}, left, {2, 1, 1}, left) == 1.0);
  // Parallel edges one apart, sliding along their length past each other.
  const V along(3, 0, 0);
  CHECK(edge_edge_ccd({0, 0, 0}, zero, {1, 0, 0}, zero, {-2, 1, 0}, along, {-1, 1, 0}, along) == 1.0);
}

TEST_CASE("edge-edge CCD: grazing at 1e-6") {
  // A crossing edge sliding over a at height 1e-6.
  const V slide(0.6, 0, 0);
  CHECK(edge_edge_ccd({0, 0, 0}, zero, {1, 0, 0}, zero, {0.2, -1, 1e-6}, slide, {0.2, 1, 1e-6}, slide) == 1.0);
  // A parallel edge sliding along a at 1e-6 above it: the four points are
  // always coplanar, yet the plane z = 1e-6 / 2 separates them all step.
  const V back(-1, 0, 0);
  CHECK(edge_edge_ccd({0, 0, 0}, zero, {1, 0, 0}, zero, {0.5, 0, 1e-6}, back, {1.5, 0, 1e-6}, back) == 1.0);
  // Sinking from 1e-6 through a while sliding: contact at t = 0.5, 10% left at t = 0.45.
  const V sink(0.6, 0, -2e-6);
  const V b0(0.2, -1, 1e-6), b1(0.2, 1, 1e-6);
  const double t = edge_edge_ccd({0, 0, 0}, zero, {1, 0, 0}, zero, b0, sink, b1, sink);
  CHECK(t < 0.5);
  CHECK(t >= 0.25);
  CHECK(ee_distance({0, 0, 0}, zero, {1, 0, 0}, zero, b0, sink, b1, sink, t) >= 0.1e-6 * (1 - 1e-6));
}

// ---------------------------------------------------------------- random trajectories

namespace {

// The first contact time in [0, 1] found by dense sampling: a sign change of
// the four points' orientation det(x1 - x0, x2 - x0, x3 - x0) (coplanarity,
// which contact needs) refined by bisection, where the distance is ~0.
// Infinity when there is none.
template <class Distance>
double first_contact(const std::array<V, 4>& x, const std::array<V, 4>& dx, const Distance& distance, int samples) {
  auto orientation = [&](double t) {
    const V p0 = at(x[0], dx[0], t);
    return (at(x[1], dx[1], t) - p0).dot((at(x[2], dx[2], t) - p0).cross(at(x[3], dx[3], t) - p0));
  };
  double previous = orientation(0);
  for (int k = 1; k <= samples; ++k) {
    double lo = double(k - 1) / samples, hi = double(k) / samples;
    const double now = orientation(hi);
    if ((previous < 0) != (now < 0)) {
      const bool lo_negative = previous < 0;
      for (int i = 0; i < 60; ++i) {
        const double mid = (lo + hi) / 2;
        ((orientation(mid) < 0) == lo_negative ? lo : hi) = mid;
      }
      if (distance(lo) < 1e-9 || distance(hi) < 1e-9) return lo;
    }
    previous = now;
  }
  return INFINITY;
}

struct Trajectory {
  std::array<V, 4> x, dx;
};

// Four random points and motions of three kinds: random; aimed through the
// other primitive (mostly colliding); and grazing, sliding at a height of
// 10^-3..10^-8 over the other primitive, sinking or rising a little, while it
// turns slightly. `edges`: (a0, a1, b0, b1), else (p, a, b, c).
Trajectory random_trajectory(std::mt19937& rng, int kind, bool edges) {
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  auto point = [&] { return V(u(rng), u(rng), u(rng)); };
  Trajectory r;
  for (V& p : r.x) p = point();
  for (V& d : r.dx) d = 0.3 * point();
  if (kind == 0) return r;
  // The spot aimed at or slid over, and the moving side's reference point.
  const V target = edges ? V(r.x[2] + unit(rng) * (r.x[3] - r.x[2]))
                         : V(r.x[1] + 0.45 * unit(rng) * (r.x[2] - r.x[1]) + 0.45 * unit(rng) * (r.x[3] - r.x[1]));
  const V from = edges ? V(r.x[0] + unit(rng) * (r.x[1] - r.x[0])) : r.x[0];
  const std::size_t moving = edges ? 2 : 1;  // the first `moving` points form the moving primitive
  if (kind == 1) {
    const V aim = (target - from) * (1 + unit(rng));
    for (std::size_t k = 0; k < moving; ++k) r.dx[k] = 0.1 * r.dx[k] + aim;
    return r;
  }
  // Grazing: put the moving primitive at height h over `target` along a
  // normal of the other one, then slide it across that normal.
  const V n = edges ? V((r.x[3] - r.x[2]).cross(r.x[1] - r.x[0]).normalized())
                    : V((r.x[2] - r.x[1]).cross(r.x[3] - r.x[1]).normalized());
  const double h = std::pow(10.0, -3 - 5 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
  const V shift = target + h * n - from;
  V slide = point();
  slide -= slide.dot(n) * n;
  for (std::size_t k = 0; k < 4; ++k) {
    if (k < moving) r.x[k] += shift;
    r.dx[k] = k < moving ? V(slide + 1.5 * u(rng) * h * n) : V(1e-4 * point());
  }
  return r;
}

}  // namespace

TEST_CASE("point-triangle CCD on random trajectories: safe up to t, and before every contact") {
  std::mt19937 rng(17);
  int contacts = 0, ones = 0;
  for (int i = 0; i < 600; ++i) {
    const Trajectory r = random_trajectory(rng, i % 3, false);
    const auto& x = r.x;
    const auto& dx = r.dx;
    auto distance = [&](double t) { return pt_distance(x[0], dx[0], x[1], dx[1], x[2], dx[2], x[3], dx[3], t); };
    const double d0 = distance(0);
    const double t = point_triangle_ccd(x[0], dx[0], x[1], dx[1], x[2], dx[2], x[3], dx[3]);
    INFO("case " << i << " t " << t << " d0 " << d0);
    REQUIRE(t >= 0);
    REQUIRE(t <= 1);
    ones += t == 1;
    CHECK(distance(t) >= 0.1 * d0 * (1 - 1e-9));
    double closest = INFINITY;
    for (int k = 0; k <= 10000; ++k) closest = std::min(closest, distance(t * k / 10000));
    CHECK(closest > 0);
    const double contact = first_contact(x, dx, distance, 2000);
    if (std::isfinite(contact)) {
      ++contacts;
      CHECK(t < contact);
    }
  }
  // The kinds of motion above do produce contacts and free steps both.
  CHECK(contacts > 100);
  CHECK(ones > 100);
}

TEST_CASE("edge-edge CCD on random trajectories: safe up to t, and before every contact") {
  std::mt19937 rng(23);
  int contacts = 0, ones = 0;
  for (int i = 0; i < 600; ++i) {
    Trajectory r = random_trajectory(rng, i % 3, true);
    if (i % 7 == 0) r.x[3] = r.x[2], r.dx[3] = r.dx[2];                   // a zero-length edge
    if (i % 11 == 0) r.x[3] = r.x[2] + (r.x[1] - r.x[0]), r.dx[3] = r.dx[2];  // parallel edges
    const auto& x = r.x;
    const auto& dx = r.dx;
    auto distance = [&](double t) { return ee_distance(x[0], dx[0], x[1], dx[1], x[2], dx[2], x[3], dx[3], t); };
    const double d0 = distance(0);
    const double t = edge_edge_ccd(x[0], dx[0], x[1], dx[1], x[2], dx[2], x[3], dx[3]);
    INFO("case " << i << " t " << t << " d0 " << d0);
    REQUIRE(t >= 0);
    REQUIRE(t <= 1);
    ones += t == 1;
    CHECK(distance(t) >= 0.1 * d0 * (1 - 1e-9));
    double closest = INFINITY;
    for (int k = 0; k <= 10000; ++k) closest = std::min(closest, distance(t * k / 10000));
    CHECK(closest > 0);
    const double contact = first_contact(x, dx, distance, 2000);
    if (std::isfinite(contact)) {
      ++contacts;
      CHECK(t < contact);
    }
  }
  CHECK(contacts > 50);
  CHECK(ones > 100);
}

// ---------------------------------------------------------------- box pairs

namespace {

// The definition: every (i, j) whose closed boxes overlap, in order. A box
// with lo > hi on an axis, or a non-finite coordinate, is empty.
std::vector<std::pair<int, int>> overlapping_boxes_reference(const std::vector<Box>& a, const std::vector<Box>& b) {
  auto valid = [](const Box& x) {
    return x.lo.allFinite() && x.hi.allFinite() && x.lo.x() <= x.hi.x() && x.lo.y() <= x.hi.y() && x.lo.z() <= x.hi.z();
  };
  std::vector<std::pair<int, int>> out;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (!valid(a[i]) || !valid(b[j])) continue;
      bool overlap = true;
      for (int k = 0; k < 3; ++k) overlap = overlap && a[i].lo[k] <= b[j].hi[k] && b[j].lo[k] <= a[i].hi[k];
      if (overlap) out.emplace_back(static_cast<int>(i), static_cast<int>(j));
    }
  return out;
}

// Boxes of several kinds: small ones of varied size (most), points (zero
// extent), a few large ones, boxes on an integer lattice (so that many
// exactly touch), exact duplicates, and some empty or broken ones.
std::vector<Box> random_boxes(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  std::uniform_int_distribution<int> lattice(-4, 4), kind(0, 19);
  std::vector<Box> boxes;
  for (int i = 0; i < count; ++i) {
    const V centre(u(rng), u(rng), u(rng));
    const int k = kind(rng);
    if (k < 10) {
      const V half = 0.05 * std::pow(10.0, u(rng)) * V(unit(rng), unit(rng), unit(rng));
      boxes.push_back({centre - half, centre + half});
    } else if (k < 13) {
      boxes.push_back({centre, centre});
    } else if (k < 14) {
      boxes.push_back({centre - V::Constant(0.6), centre + V(0.6, 0.2, 0.9)});
    } else if (k < 17) {
      const V lo(lattice(rng), lattice(rng), lattice(rng));
      boxes.push_back({0.25 * lo, 0.25 * (lo + V(lattice(rng) % 2 == 0, 1, lattice(rng) % 3 == 0))});
    } else if (k < 19 && !boxes.empty()) {
      boxes.push_back(boxes[static_cast<std::size_t>(i) / 2]);
    } else {
      Box broken{centre, centre - V(0.1, 0, 0)};  // lo > hi in x
      if (unit(rng) < 0.5) broken = {V(std::numeric_limits<double>::quiet_NaN(), 0, 0), centre};
      boxes.push_back(broken);
    }
  }
  return boxes;
}

}  // namespace

TEST_CASE("overlapping boxes match a double loop, sorted and without duplicates") {
  std::mt19937 rng(5);
  const std::pair<int, int> sizes[] = {{0, 0}, {0, 20}, {20, 0}, {1, 1}, {1, 300}, {300, 1}, {60, 90}, {800, 1500}, {2500, 1200}};
  for (auto [na, nb] : sizes) {
    const std::vector<Box> a = random_boxes(rng, na), b = random_boxes(rng, nb);
    const auto want = overlapping_boxes_reference(a, b);
    INFO(na << " x " << nb << " boxes, " << want.size() << " pairs");
    CHECK(overlapping_boxes(a, b) == want);
    // Any cell size gives the same pairs: tiny cells (capped to a few per
    // box), huge cells (one cell), and about the boxes' size.
    CHECK(overlapping_boxes(a, b, 1e-9) == want);
    CHECK(overlapping_boxes(a, b, 1e9) == want);
    CHECK(overlapping_boxes(a, b, 0.07) == want);
  }
}

TEST_CASE("a box grid built once answers many queries as a fresh search would") {
  // The barrier keeps the still body's grid across line-search trials: every
  // query, including boxes far outside the grid's bounds, an empty query and
  // queries after others, must match the double loop.
  std::mt19937 rng(11);
  const std::vector<Box> b = random_boxes(rng, 900);
  const BoxGrid grid(b, 0.05);
  CHECK(grid.boxes().size() == b.size());
  for (int query = 0; query < 6; ++query) {
    std::vector<Box> a = random_boxes(rng, 40 + 150 * query);
    if (query == 3) a.clear();
    if (query == 4)
      for (Box& box : a) box = {box.lo * 5 + V(3, 0, 0), box.hi * 5 + V(3, 0, 0)};  // mostly outside b's bounds
    INFO("query " << query << ", " << a.size() << " boxes");
    CHECK(grid.overlapping(a) == overlapping_boxes_reference(a, b));
  }
  // A grid of no boxes overlaps nothing.
  CHECK(BoxGrid(std::vector<Box>{}).overlapping(random_boxes(rng, 30)).empty());
}

// What max_step relies on to take its pairs from a Verlet list: the box test
// the grid reports by, and the reach of a list found with grown boxes.
TEST_CASE("boxes_overlap and sweep_within: the box test and a Verlet list's reach") {
  const Box unit{V(0, 0, 0), V(1, 1, 1)};
  CHECK(boxes_overlap(unit, {V(1, 1, 1), V(2, 2, 2)}));               // a shared corner counts
  CHECK_FALSE(boxes_overlap(unit, {V(1 + 1e-12, 0, 0), V(2, 1, 1)}));  // just apart
  CHECK_FALSE(boxes_overlap(unit, {V(0.5, 0, 0), V(0.4, 1, 1)}));      // lo > hi: no box
  CHECK_FALSE(boxes_overlap(unit, {V(NAN, 0, 0), V(0.5, 1, 1)}));
  // Drift 0.4 mm on one coordinate, step 0.5 mm on another: 0.9 mm of a 1 mm growth.
  Eigen::MatrixX3d x0 = Eigen::MatrixX3d::Random(20, 3), x = x0, dx = Eigen::MatrixX3d::Zero(20, 3);
  x(3, 1) += 4e-4;
  dx(7, 2) = -5e-4;
  CHECK(sweep_within(x0, x, dx, 1e-3));
  CHECK_FALSE(sweep_within(x0, x, dx, 0.9e-3));  // exactly at the reach: the nanometre in hand refuses
  CHECK(sweep_within(x0, x, dx, 0.9e-3 + 2e-9));
  dx(7, 2) = -6.1e-4;
  CHECK_FALSE(sweep_within(x0, x, dx, 1e-3));
  dx(7, 2) = NAN;
  CHECK_FALSE(sweep_within(x0, x, dx, 1e-3));
  CHECK_FALSE(sweep_within(Eigen::MatrixX3d(19, 3), x, Eigen::MatrixX3d::Zero(20, 3), 1.0));  // another mesh
}

TEST_CASE("overlapping boxes: touching counts, points and degenerate grids") {
  const Box unit{V(0, 0, 0), V(1, 1, 1)};
  // Sharing a face, an edge, a corner; a point on the surface and inside; just apart.
  const std::vector<Box> a = {{V(1, 0, 0), V(2, 1, 1)}, {V(1, 1, 0), V(2, 2, 1)}, {V(1, 1, 1), V(2, 2, 2)},
                              {V(0.5, 1, 0.5), V(0.5, 1, 0.5)}, {V(0.5, 0.5, 0.5), V(0.5, 0.5, 0.5)},
                              {V(1 + 1e-12, 0, 0), V(2, 1, 1)}};
  const std::vector<std::pair<int, int>> want = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}};
  CHECK(overlapping_boxes(a, {unit}) == want);
  // All of b in one point: every grid axis has zero extent.
  const std::vector<Box> points(5, Box{V(0.5, 0.5, 0.5), V(0.5, 0.5, 0.5)});
  const auto hits = overlapping_boxes({unit, {V(2, 2, 2), V(3, 3, 3)}}, points);
  CHECK(hits == std::vector<std::pair<int, int>>{{0, 0}, {0, 1}, {0, 2}, {0, 3}, {0, 4}});
  // Boxes in a plane (zero extent along z), the grid flat along it.
  std::vector<Box> flat;
  for (int i = 0; i < 10; ++i) flat.push_back({V(i, 0, 0), V(i + 1, 1, 0)});
  CHECK(overlapping_boxes({{V(2.5, 0.5, -1), V(4, 0.5, 0)}}, flat) ==
        std::vector<std::pair<int, int>>{{0, 2}, {0, 3}, {0, 4}});
}
