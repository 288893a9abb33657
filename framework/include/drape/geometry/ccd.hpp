#pragma once
// Distances between contact primitives and continuous collision detection
// (CCD) for an IPC-style barrier contact between a cloth and a body.
//
// The barrier needs every step of the solver to keep each point-triangle and
// edge-edge pair apart: a line search is cut at the first time the primitives
// could touch. The CCD here is Additive CCD (Li, Kaufman & Jiang, "Codimensional
// Incremental Potential Contact", 2021, Algorithm 1): it only evaluates
// distances, so parallel, coplanar and degenerate configurations need no
// special cases, and it is conservative by construction: it advances t by a
// step the primitives cannot close given a bound on their relative speed.
//
// Its weakness is grazing motion (sliding past at a tiny distance), where the
// steps shrink with the distance: ~1e6 of them for a point sliding its own
// length at 1e-6 over a triangle. Two additions keep that cheap, both as
// conservative as the steps themselves (see ccd.cpp): each step is the longer
// of Additive CCD's and one along the current closest direction (how far the
// corners' gaps along a fixed direction, linear in t, allow); and before
// iterating, a plane separating the primitives all step, or the four points
// never becoming coplanar, proves that they cannot touch, and t = 1 is taken.
#include <Eigen/Core>

namespace drape::geometry {

// Squared unsigned distance from p to the closed triangle (a, b, c); exact in
// double through closest_point_on_triangle. Degenerate triangles (collinear
// or coincident corners) give the distance to their segments, always finite.
double point_triangle_distance2(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c);

// The closest points of two closed segments, a(s) = a0 + s (a1 - a0) and
// b(t) = b0 + t (b1 - b0) with s, t in [0, 1]. For parallel or overlapping
// segments (many closest pairs) one of them; a zero-length segment is a point.
struct SegmentPoints {
  double s = 0, t = 0;
  Eigen::Vector3d on_a = Eigen::Vector3d::Zero(), on_b = Eigen::Vector3d::Zero();
};
SegmentPoints closest_points_on_segments(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                                         const Eigen::Vector3d& b1);

// Squared unsigned distance between the closed segments [a0, a1] and [b0, b1].
double edge_edge_distance2(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                           const Eigen::Vector3d& b1);

// Enough for approaching primitives (each step closes 90% of the remaining
// distance if they approach head-on); grazing motion that the certificates
// cannot settle may hit it, and then gets a safe but early t.
inline constexpr int default_ccd_max_iterations = 1000;

// Continuous collision detection over linear trajectories: each point moves
// from its start x to x + dx as t goes from 0 to 1. Returns t_max in [0, 1]
// such that
//   - the distance stays > 0 for all t in [0, t_max] (conservative: contact
//     is never missed, up to rounding in evaluating a distance), and
//   - the distance at t_max is at least min_separation_ratio times the start
//     distance d0 (up to rounding), so the next step starts separated.
// It is 1 when the primitives never get that close within the step (1 also
// when they may get closer in between but contact is excluded and the
// distance at t = 1 is at least the fraction), and 0 when the start distance
// is already <= 0 (touching or crossed) or not finite. Like any conservative
// CCD it may return less than the time the fraction is actually reached (its
// steps assume the worst speed). After max_iterations steps the current t is
// returned: safe and separated, only shorter than needed.
// min_separation_ratio must lie in (0, 1); throws std::invalid_argument otherwise.
double point_triangle_ccd(const Eigen::Vector3d& p, const Eigen::Vector3d& dp, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& da, const Eigen::Vector3d& b, const Eigen::Vector3d& db,
                          const Eigen::Vector3d& c, const Eigen::Vector3d& dc, double min_separation_ratio = 0.1,
                          int max_iterations = default_ccd_max_iterations);

// The same for the segments [a0, a1] and [b0, b1].
double edge_edge_ccd(const Eigen::Vector3d& a0, const Eigen::Vector3d& da0, const Eigen::Vector3d& a1,
                     const Eigen::Vector3d& da1, const Eigen::Vector3d& b0, const Eigen::Vector3d& db0,
                     const Eigen::Vector3d& b1, const Eigen::Vector3d& db1, double min_separation_ratio = 0.1,
                     int max_iterations = default_ccd_max_iterations);

}  // namespace drape::geometry
