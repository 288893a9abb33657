// Picking the distance type of a contact pair (drape/geometry/pair_distance.hpp).
#include <drape/geometry/pair_distance.hpp>

#include <drape/geometry/ccd.hpp>
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>

namespace drape::geometry {

namespace {

using Kind = DistanceType::Kind;

DistanceType make(Kind kind, unsigned char p0, unsigned char p1, unsigned char p2 = 0, unsigned char p3 = 0) {
  DistanceType t;
  t.kind = kind;
  t.points = {p0, p1, p2, p3};
  return t;
}

// Point `point` against the segment (s0, s1): point-line when its projection
// falls inside, else point-point with the nearer end. Returns the squared distance.
double point_segment(const std::array<Eigen::Vector3d, 4>& x, unsigned char point, unsigned char s0, unsigned char s1,
                     DistanceType& type) {
  const Eigen::Vector3d e = x[s1] - x[s0];
  const double length2 = e.squaredNorm();
  const double u = length2 > 0 ? (x[point] - x[s0]).dot(e) / length2 : 0.0;
  if (u <= 0) {
    type = make(Kind::PointPoint, point, s0);
    return (x[point] - x[s0]).squaredNorm();
  }
  if (u >= 1) {
    type = make(Kind::PointPoint, point, s1);
    return (x[point] - x[s1]).squaredNorm();
  }
  type = make(Kind::PointLine, point, s0, s1);
  return (x[point] - (x[s0] + u * e)).squaredNorm();
}

}  // namespace

DistanceType point_triangle_type(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c) {
  const TrianglePoint hit = closest_point_on_triangle(p, a, b, c);
  switch (hit.feature) {
    case TriangleFeature::vertex_a: return make(Kind::PointPoint, 0, 1);
    case TriangleFeature::vertex_b: return make(Kind::PointPoint, 0, 2);
    case TriangleFeature::vertex_c: return make(Kind::PointPoint, 0, 3);
    case TriangleFeature::edge_ab: return make(Kind::PointLine, 0, 1, 2);
    case TriangleFeature::edge_bc: return make(Kind::PointLine, 0, 2, 3);
    case TriangleFeature::edge_ca: return make(Kind::PointLine, 0, 3, 1);
    case TriangleFeature::interior: break;
  }
  // The plane formula divides by the squared doubled area: a sliver whose
  // closest point is reported inside is measured from its nearest edge instead.
  const double area2 = (b - a).cross(c - a).squaredNorm();
  const double scale = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  if (area2 > 1e-16 * scale * scale) return make(Kind::PointPlane, 0, 1, 2, 3);
  const std::array<Eigen::Vector3d, 4> x{p, a, b, c};
  DistanceType best, candidate;
  double nearest = std::numeric_limits<double>::infinity();
  for (auto [s0, s1] : {std::pair<unsigned char, unsigned char>{1, 2}, {2, 3}, {3, 1}}) {
    const double d2 = point_segment(x, 0, s0, s1, candidate);
    if (d2 < nearest) nearest = d2, best = candidate;
  }
  return best;
}

DistanceType edge_edge_type(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                            const Eigen::Vector3d& b1) {
  // The lines' formula is used only off parallel (sin^2 of the angle above
  // 1e-6): near parallel it divides by a vanishing |d1 x d2|^2, and there the
  // endpoint types give the distance anyway (the closest points can be taken at
  // an endpoint). The edge-edge mollifier (physics/barrier_function.hpp) fades these pairs out
  // before the switch matters.
  const Eigen::Vector3d d1 = a1 - a0, d2 = b1 - b0;
  if (d1.cross(d2).squaredNorm() > 1e-6 * d1.squaredNorm() * d2.squaredNorm()) {
    const SegmentPoints q = closest_points_on_segments(a0, a1, b0, b1);
    if (q.s > 0 && q.s < 1 && q.t > 0 && q.t < 1) return make(Kind::LineLine, 0, 1, 2, 3);
  }
  const std::array<Eigen::Vector3d, 4> x{a0, a1, b0, b1};
  DistanceType best, candidate;
  double nearest = std::numeric_limits<double>::infinity();
  const std::array<std::array<unsigned char, 3>, 4> tries{{{0, 2, 3}, {1, 2, 3}, {2, 0, 1}, {3, 0, 1}}};
  for (const auto& t : tries) {
    const double distance2 = point_segment(x, t[0], t[1], t[2], candidate);
    if (distance2 < nearest) nearest = distance2, best = candidate;
  }
  return best;
}

}  // namespace drape::geometry
