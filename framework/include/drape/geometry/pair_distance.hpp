#pragma once
// Squared distances of contact pairs (of the energies barrier and
// self_contact), each as one smooth formula per "distance type" (IPC, Li et
// al. 2020, section 4.2): the distance of a point
// to a triangle is the distance to its plane, to the line of one of its
// edges, or to one of its corners, whichever feature the closest point lies
// on; that of two segments is the distance of their lines, or of an endpoint
// to the other segment's line, or of two endpoints. Inside each type the
// formula is smooth; across types it is C1 (the squared distance to a convex
// set), which Newton tolerates. The type is picked in plain doubles, then the
// formula is evaluated over any scalar (double, or Dual<N> for the exact
// gradient and Hessian).
#include <drape/dual.hpp>

#include <Eigen/Core>

#include <array>

namespace drape::geometry {

template <class S>
S point_point_distance2(const Vec3<S>& p, const Vec3<S>& q) {
  const Vec3<S> d = p - q;
  return dot(d, d);
}

template <class S>
S point_line_distance2(const Vec3<S>& p, const Vec3<S>& a, const Vec3<S>& b) {
  const Vec3<S> e = b - a;
  const Vec3<S> c = cross(p - a, e);
  return dot(c, c) * inverse(dot(e, e));
}

template <class S>
S point_plane_distance2(const Vec3<S>& p, const Vec3<S>& a, const Vec3<S>& b, const Vec3<S>& c) {
  const Vec3<S> n = cross(b - a, c - a);
  const S h = dot(p - a, n);
  return h * h * inverse(dot(n, n));
}

template <class S>
S line_line_distance2(const Vec3<S>& a0, const Vec3<S>& a1, const Vec3<S>& b0, const Vec3<S>& b1) {
  const Vec3<S> n = cross(a1 - a0, b1 - b0);
  const S h = dot(b0 - a0, n);
  return h * h * inverse(dot(n, n));
}

// Which formula gives the distance of a pair, and over which of its points.
// Points of a point-triangle pair: 0 = the point, 1..3 = the corners; of an
// edge-edge pair: 0, 1 = the first edge, 2, 3 = the second.
struct DistanceType {
  enum Kind : unsigned char { PointPoint, PointLine, PointPlane, LineLine } kind = PointPlane;
  std::array<unsigned char, 4> points{0, 1, 2, 3};  // the points the formula takes, in its argument order
};

// The type of a point-triangle pair from where the closest point lies.
DistanceType point_triangle_type(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c);
// The type of an edge-edge pair: their lines' distance when the closest points
// are inside both segments and the segments are not near parallel; else the
// nearest endpoint-to-segment pair's point-line or point-point distance.
DistanceType edge_edge_type(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                            const Eigen::Vector3d& b1);

// The squared distance of the points `p` (4 of them; a point-triangle pair
// uses all four, an edge-edge pair too) by `type`.
template <class S>
S typed_distance2(const DistanceType& type, const std::array<Vec3<S>, 4>& p) {
  const auto& i = type.points;
  switch (type.kind) {
    case DistanceType::PointPoint: return point_point_distance2(p[i[0]], p[i[1]]);
    case DistanceType::PointLine: return point_line_distance2(p[i[0]], p[i[1]], p[i[2]]);
    case DistanceType::PointPlane: return point_plane_distance2(p[i[0]], p[i[1]], p[i[2]], p[i[3]]);
    case DistanceType::LineLine: break;
  }
  return line_line_distance2(p[i[0]], p[i[1]], p[i[2]], p[i[3]]);
}

}  // namespace drape::geometry
