#include "contacts.hpp"

#include <algorithm>
#include <utility>
#include <cmath>

namespace drape::collision {
namespace {

using geometry::BodySurface;
using geometry::SurfacePoint;
using geometry::TriangleFeature;

// Below a micrometre from a polygonal edge or vertex, the 1 / distance
// curvature is an artefact of the body's tessellation, not of its shape; the
// clamp keeps the Hessian finite when a point sits on the surface.
constexpr double kMinCurvatureRadius = 1e-6;  // m

// The edge (two slots of the face) a closest point lies on; a = b = -1 inside
// the face, a >= 0 and b = -1 at a corner.
std::pair<int, int> feature_slots(TriangleFeature feature) {
  switch (feature) {
    case TriangleFeature::interior: return {-1, -1};
    case TriangleFeature::edge_ab: return {0, 1};
    case TriangleFeature::edge_bc: return {1, 2};
    case TriangleFeature::edge_ca: return {2, 0};
    case TriangleFeature::vertex_a: return {0, -1};
    case TriangleFeature::vertex_b: return {1, -1};
    default: return {2, -1};
  }
}

// Zero inside a face (the surface is flat there); off it, the distance is to
// the feature the closest point slides on (a line or a point), whose Hessian is
// the projector onto the directions the point cannot follow, over the distance:
// (I - n n^T - slide) / d.
Eigen::Matrix3d distance_hessian(const SurfacePoint& s, const ClosestPoint& q) {
  if (s.feature == TriangleFeature::interior) return Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - s.normal * s.normal.transpose() - q.slide;
  const double radius = std::copysign(std::max(std::abs(s.signed_distance), kMinCurvatureRadius), s.signed_distance);
  return projector / radius;
}

Eigen::Vector3d corner_of(const BodySurface& surface, int face, int slot) {
  return surface.vertices().row(surface.faces()(face, slot));
}

Contact contact_of(const BodySurface& surface, const SurfacePoint& s, bool with_hessian) {
  Contact c;
  c.normal = s.normal;
  c.distance = s.signed_distance;
  c.closest = closest_point_of(surface, s);
  c.face = s.face;
  if (with_hessian) c.distance_hessian = distance_hessian(s, c.closest);
  return c;
}

}  // namespace

ClosestPoint closest_point_of(const BodySurface& surface, const SurfacePoint& s) {
  ClosestPoint q;
  q.point = s.point;
  q.sign = s.signed_distance < 0 ? -1 : 1;
  const auto corner = [&](int slot) { return corner_of(surface, s.face, slot); };
  const auto [a, b] = feature_slots(s.feature);
  if (a < 0) {
    const Eigen::Vector3d n = surface.face_normals().row(s.face);
    // A degenerate face has no plane (zero normal); its closest points lie on its edges (closest_point_on_triangle).
    if (n.squaredNorm() > 0) q.slide = Eigen::Matrix3d::Identity() - n * n.transpose();
  } else if (b >= 0) {
    // A degenerate (zero-length) edge is a point: it does not slide.
    const Eigen::Vector3d t = corner(b) - corner(a);
    if (t.norm() > 0) q.slide = t.normalized() * t.normalized().transpose();
  }
  return q;
}

ClosestPoint closest_point_on_face(const BodySurface& surface, const Eigen::Vector3d& p, int face) {
  const auto corner = [&](int slot) { return corner_of(surface, face, slot); };
  const geometry::TrianglePoint t = geometry::closest_point_on_triangle(p, corner(0), corner(1), corner(2));
  SurfacePoint s;
  s.face = face;
  s.point = t.point;
  s.feature = t.feature;
  const Eigen::Vector3d n = surface.face_normals().row(face);
  s.signed_distance = (p - t.point).dot(n) < 0 ? -(p - t.point).norm() : (p - t.point).norm();
  return closest_point_of(surface, s);
}

Contact body_contact(const BodyQuery& body, const Eigen::Vector3d& p, bool with_hessian) {
  if (const auto* surface = dynamic_cast<const BodySurface*>(&body))
    return contact_of(*surface, surface->locate(p), with_hessian);
  const BodyQuery::Hit hit = body.closest(p);
  Contact c;
  c.normal = hit.normal;
  c.distance = hit.signed_distance;
  return c;
}

std::vector<Contact> body_contacts(const BodyQuery& body, const Eigen::MatrixX3d& x, bool with_hessian) {
  std::vector<Contact> out(static_cast<std::size_t>(x.rows()));
  if (const auto* surface = dynamic_cast<const BodySurface*>(&body)) {
    const std::vector<SurfacePoint> located = surface->locate_all(x);
    for (std::size_t v = 0; v < out.size(); ++v) out[v] = contact_of(*surface, located[v], with_hessian);
    return out;
  }
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    out[static_cast<std::size_t>(v)] = body_contact(body, x.row(v).transpose(), with_hessian);
  return out;
}

}  // namespace drape::collision
