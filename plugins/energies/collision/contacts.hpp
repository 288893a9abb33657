#pragma once
// Where each garment vertex stands relative to the body: signed distance, its
// gradient (the outward unit normal at the closest point) and, when the body can
// say which feature the closest point lies on, the Hessian of the signed distance.
#include "crease_penalty.hpp"

#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::collision {

struct Contact {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // d(distance)/dx, unit, outward
  double distance = 0;                               // signed, < 0 inside the body
  // d^2(distance)/dx^2: zero when the closest point is inside a face (the
  // surface is flat there), (I - n n^T) / distance at a body vertex (distance to
  // a point), (I - n n^T - t t^T) / distance on an edge of direction t (distance
  // to a line). Left zero when not asked for or not known (see body_contacts).
  Eigen::Matrix3d distance_hessian = Eigen::Matrix3d::Zero();
  // From a BodySurface only: the closest point and its face (-1 otherwise).
  ClosestPoint closest;
  int face = -1;
  // The far side of a crease (crease_penalty.hpp), filled in by the collision energy.
  CreaseTerm crease;
};

// The closest point of a surface query with dq/dp: I - n n^T inside a face (n
// its normal), t t^T on an edge of direction t, zero at a vertex.
ClosestPoint closest_point_of(const geometry::BodySurface& surface, const geometry::SurfacePoint& s);

// The closest point to p on one given face of the surface (not necessarily
// the surface's closest), signed by that face's normal.
ClosestPoint closest_point_on_face(const geometry::BodySurface& surface, const Eigen::Vector3d& p, int face);

// The contact of one point (with the distance Hessian only from a BodySurface).
Contact body_contact(const BodyQuery& body, const Eigen::Vector3d& p, bool with_hessian);

// One contact per row of x. A BodySurface is queried in parallel and reports the
// feature (face, edge, vertex) of each closest point, which the distance Hessian
// needs; any other BodyQuery is asked closest() one point at a time (its thread
// safety is unknown) and its contacts carry no distance Hessian.
std::vector<Contact> body_contacts(const BodyQuery& body, const Eigen::MatrixX3d& x, bool with_hessian);

}  // namespace drape::collision
