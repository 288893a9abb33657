// Primitive distances and Additive CCD (Li, Kaufman & Jiang 2021, Algorithm 1),
// with steps along the closest direction and two no-contact certificates for
// grazing motion.
#include <drape/geometry/ccd.hpp>
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace drape::geometry {
namespace {

// n / d clamped to [0, 1]; 0 when d vanishes (a zero-length segment), where
// every parameter names the same point, so degenerate input never gives NaN.
double clamped_ratio(double n, double d) { return d > 0 ? std::clamp(n / d, 0.0, 1.0) : 0.0; }

// The parameter of the point of segment [from, from + e] closest to p.
double project_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& from, const Eigen::Vector3d& e) {
  return clamped_ratio(e.dot(p - from), e.squaredNorm());
}

}  // namespace

double point_triangle_distance2(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c) {
  return (closest_point_on_triangle(p, a, b, c).point - p).squaredNorm();
}

// The minimum of |a(s) - b(t)|^2 over the unit square lies either where both
// lines are closest (a critical point inside) or on the square's border, where
// one parameter is 0 or 1: an endpoint against the other segment. Ericson's
// 5.1.9 walks these cases with a branch per region; here every case is a
// candidate pair of actual segment points and the nearest pair wins. Its
// accuracy needs no parallel-or-not branch: for parallel segments (where the
// inner solution is undefined) the border always holds a closest pair, and a
// badly rounded inner solution is still a pair of segment points, so it can
// only lose to the border candidates, never undercut the true distance.
SegmentPoints closest_points_on_segments(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                                         const Eigen::Vector3d& b1) {
  const Eigen::Vector3d u = a1 - a0, v = b1 - b0, w = b0 - a0;
  SegmentPoints best;
  double best_d2 = std::numeric_limits<double>::infinity();
  auto consider = [&](double s, double t) {
    const Eigen::Vector3d on_a = a0 + s * u, on_b = b0 + t * v;
    const double d2 = (on_a - on_b).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = {s, t, on_a, on_b};
  };
  // Inner critical point of the two lines, from a(s) - b(t) parallel to
  // n = u x v: s = (w x v).n / |n|^2, t = (w x u).n / |n|^2. The cross
  // products keep their relative accuracy for nearly parallel lines, where
  // the Gram determinant |u|^2 |v|^2 - (u.v)^2 of the textbook form cancels.
  // Below sin(angle) ~ 1e-12 the border candidates are within ~1e-12 of the
  // segments' length of the true minimum, and s, t would be meaningless.
  const Eigen::Vector3d n = u.cross(v);
  const double nn = n.squaredNorm();
  if (nn > 1e-24 * u.squaredNorm() * v.squaredNorm())
    consider(std::clamp(w.cross(v).dot(n) / nn, 0.0, 1.0), std::clamp(w.cross(u).dot(n) / nn, 0.0, 1.0));
  consider(0, project_on_segment(a0, b0, v));
  consider(1, project_on_segment(a1, b0, v));
  consider(project_on_segment(b0, a0, u), 0);
  consider(project_on_segment(b1, a0, u), 1);
  return best;
}

double edge_edge_distance2(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                           const Eigen::Vector3d& b1) {
  const SegmentPoints q = closest_points_on_segments(a0, a1, b0, b1);
  return (q.on_a - q.on_b).squaredNorm();
}

namespace {

// Four points and their displacements over the step: (p, a, b, c) for
// point-triangle, (a0, a1, b0, b1) for edge-edge. The first `split` points
// are one primitive, the rest the other.
using Points = std::array<Eigen::Vector3d, 4>;

// Additive CCD's bound l_p on how fast the distance can change per unit t.
// A point of one primitive and a point of the other are convex combinations
// of their corners, so their relative displacement is at most the largest
// corner displacement of one plus that of the other; the distance, a minimum
// over such pairs, changes no faster. The mean displacement is removed first:
// a common translation changes no distance and would only loosen the bound.
double speed_bound(const Points& dx, std::size_t split) {
  const Eigen::Vector3d mean = (dx[0] + dx[1] + dx[2] + dx[3]) / 4;
  double first = 0, second = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    double& side = k < split ? first : second;
    side = std::max(side, (dx[k] - mean).norm());
  }
  return first + second;
}

// A second lower bound on the distance, for motion along the contact plane,
// where Additive CCD's steps shrink with the distance (a point sliding its
// own length at 1e-6 over a triangle would take ~1e6 of them).
//
// For a fixed unit direction n, the gaps g_ij(t) = (x_j(t) - x_i(t)) . n
// between each corner i of the first primitive and j of the second bound the
// distance from below by their minimum (every point is a convex combination
// of corners), and each is linear in t. With n the closest-point direction at
// time t they all start at >= the distance there. Returns the largest t' in
// [t, 1] with every gap still >= `floor` at t', and so on all of [t, t']; t
// when some gap is below it already (n no separating direction).
//
// The margin, 1e-12 of the sizes involved, is far above the rounding of these
// few products (~1e-15 of it), so the bound never rests on rounding.
double advance_along(const Points& x, const Points& dx, std::size_t split, const Eigen::Vector3d& n, double t,
                     double floor) {
  const double length = n.norm();
  if (!(length > 0 && std::isfinite(length))) return t;
  const Eigen::Vector3d unit = n / length;
  double reach = 1;
  for (std::size_t i = 0; i < split; ++i)
    for (std::size_t j = split; j < 4; ++j) {
      const Eigen::Vector3d e = x[j] - x[i], de = dx[j] - dx[i];
      const double lowest = floor + 1e-12 * (e.norm() + de.norm());
      const double gap = (e + t * de).dot(unit), slope = de.dot(unit);
      if (!(gap >= lowest)) return t;
      if (slope < 0) reach = std::min(reach, t + (gap - lowest) / -slope);
    }
  return std::max(t, reach);
}

double det(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const Eigen::Vector3d& z) { return x.dot(y.cross(z)); }

// True when the four points are certainly never coplanar for t in [0, 1].
// Touching (a point on a triangle, two segments meeting) needs the four
// points in one plane. This settles what no fixed direction can: a point
// sliding over a triangle that turns during the step.
//
// Coplanarity is the zero set of f(t) = det(e1(t), e2(t), e3(t)) with
// e_i = x_i - x_0, a cubic. Each e_i is linear in t, so f is trilinear in the
// end values e_i(0), e_i(1), and its Bernstein coefficients on [0, 1] are
// averages of determinants of those: b_k is the mean over the choices of k of
// the three vectors taken at t = 1. A Bernstein polynomial lies within the
// hull of its coefficients, so coefficients all of one sign exclude a root.
// The margin is 1e-12 of the product of the sizes, as above.
bool never_coplanar(const Points& x, const Points& dx) {
  std::array<Eigen::Vector3d, 3> e0, e1;
  double size = 1;
  for (std::size_t k = 0; k < 3; ++k) {
    e0[k] = x[k + 1] - x[0];
    const Eigen::Vector3d relative = dx[k + 1] - dx[0];
    e1[k] = e0[k] + relative;
    size *= e0[k].norm() + relative.norm();
  }
  const double b[4] = {
      det(e0[0], e0[1], e0[2]),
      (det(e1[0], e0[1], e0[2]) + det(e0[0], e1[1], e0[2]) + det(e0[0], e0[1], e1[2])) / 3,
      (det(e0[0], e1[1], e1[2]) + det(e1[0], e0[1], e1[2]) + det(e1[0], e1[1], e0[2])) / 3,
      det(e1[0], e1[1], e1[2]),
  };
  const double margin = 1e-12 * size;
  const double lo = std::min({b[0], b[1], b[2], b[3]}), hi = std::max({b[0], b[1], b[2], b[3]});
  return lo > margin || hi < -margin;  // false for NaN
}

// closest(points) is the vector from the first primitive's closest point to
// the second's: its norm is the distance, its direction separates them.
template <class Closest>
double additive_ccd(const Points& x, const Points& dx, std::size_t split, const Closest& closest, double ratio,
                    int max_iterations) {
  auto at = [&](double t) {
    Points y;
    for (std::size_t k = 0; k < 4; ++k) y[k] = x[k] + t * dx[k];
    return y;
  };
  Eigen::Vector3d g = closest(x);
  const double d0 = g.norm();
  if (!(d0 > 0 && std::isfinite(d0))) return 0;  // touching, crossed or NaN: no safe step
  const double speed = speed_bound(dx, split);
  if (speed == 0) return 1;  // a common translation: the distance is constant
  if (!std::isfinite(speed)) return 0;
  const double gap = ratio * d0;

  // When Additive CCD cannot reach t = 1 in one step, first try to prove the
  // whole step free of contact: the closest direction at t = 1 separating them
  // at both ends (so all along), or the points never coplanar.
  if (speed > (1 - ratio) * d0) {
    const Eigen::Vector3d g1 = closest(at(1));
    if (g1.norm() >= gap && (advance_along(x, dx, split, g1, 0, 0) >= 1 || never_coplanar(x, dx))) return 1;
  }

  // Algorithm 1 with thickness xi = 0: from a time t at distance d, the
  // distance cannot fall below ratio * d before t + (1 - ratio) d / speed, so
  // that step is free of contact. The step along the closest direction at t
  // (advance_along) is free of contact too and ends at distance >= the gap;
  // the longer of the two is taken. An Additive CCD step ending below the gap
  // stops the search at the previous t, where the distance was at least the
  // gap. Its first step from t = 0 ends at >= d0 - (1 - ratio) d0 = gap by the
  // bound itself, so, as in the paper, it is not tested: rounding must not
  // turn a head-on approach (where the bound is tight) into t = 0.
  double t = 0, d = d0;
  for (int i = 0; i < max_iterations; ++i) {
    const double additive = t + (1 - ratio) * d / speed, along = advance_along(x, dx, split, g, t, gap);
    const double next = std::min(1.0, std::max(additive, along));
    const bool proven = along >= next || t == 0;  // its distance is >= the gap by a bound, not only by evaluation
    g = closest(at(next));
    const double d_next = g.norm();
    if (!(d_next >= gap) && !(proven && d_next > 0)) return t;
    if (next >= 1) return 1;
    if (!(next > t)) return t;  // below the resolution of t
    t = next, d = d_next;
  }
  // Out of iterations (grazing motion the bounds could not settle): t is still
  // safe and separated, only short.
  return t;
}

void check_ratio(double min_separation_ratio) {
  if (!(min_separation_ratio > 0 && min_separation_ratio < 1))
    throw std::invalid_argument("CCD: min_separation_ratio must lie in (0, 1)");
}

}  // namespace

double point_triangle_ccd(const Eigen::Vector3d& p, const Eigen::Vector3d& dp, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& da, const Eigen::Vector3d& b, const Eigen::Vector3d& db,
                          const Eigen::Vector3d& c, const Eigen::Vector3d& dc, double min_separation_ratio,
                          int max_iterations) {
  check_ratio(min_separation_ratio);
  auto closest = [](const Points& y) -> Eigen::Vector3d {
    return closest_point_on_triangle(y[0], y[1], y[2], y[3]).point - y[0];
  };
  return additive_ccd(Points{p, a, b, c}, Points{dp, da, db, dc}, 1, closest, min_separation_ratio, max_iterations);
}

double edge_edge_ccd(const Eigen::Vector3d& a0, const Eigen::Vector3d& da0, const Eigen::Vector3d& a1,
                     const Eigen::Vector3d& da1, const Eigen::Vector3d& b0, const Eigen::Vector3d& db0,
                     const Eigen::Vector3d& b1, const Eigen::Vector3d& db1, double min_separation_ratio,
                     int max_iterations) {
  check_ratio(min_separation_ratio);
  auto closest = [](const Points& y) -> Eigen::Vector3d {
    const SegmentPoints q = closest_points_on_segments(y[0], y[1], y[2], y[3]);
    return q.on_b - q.on_a;
  };
  return additive_ccd(Points{a0, a1, b0, b1}, Points{da0, da1, db0, db1}, 2, closest, min_separation_ratio,
                      max_iterations);
}

}  // namespace drape::geometry
