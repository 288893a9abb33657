#pragma once
// Exact signs of the 2D and 3D orientation determinants, and the 2D segment
// test built on them (internal to the geometry layer; used by
// surface_crossings.cpp and height_field_nodes.cpp).
//
// A sign computed in plain double can be wrong when the points are nearly
// coplanar, and two triangles sharing an edge can then disagree about which
// side of it a segment passes: a crossing falls through the crack or is seen
// by neither. Here the double value is used only when a forward error bound
// proves its sign (Shewchuk's filter); otherwise the determinant is evaluated
// exactly in floating-point expansion arithmetic, so orient3d(p, q, a, b) is
// always exactly -orient3d(p, q, b, a). Assumes no overflow or underflow
// (coordinates of metre-sized meshes are far from both).
#include <Eigen/Core>

namespace drape::geometry::exact {

// Sign (-1, 0, +1) of det[b - a, c - a, d - a]: +1 when d lies on the side of
// the plane through a, b, c that (b - a) x (c - a) points to, 0 when coplanar.
int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d);

// Sign of det[b - a, c - a]: +1 when a, b, c turn counter-clockwise, 0 when collinear.
int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

// Closed 2D segments (p, q) and (a, b) share a point (a proper crossing, or
// an endpoint of one on the other; collinear overlaps are endpoints on the other).
bool segments_meet_2d(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

}  // namespace drape::geometry::exact
