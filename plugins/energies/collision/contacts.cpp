#include "contacts.hpp"

#include <algorithm>
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

Eigen::Matrix3d distance_hessian(const BodySurface& body, const SurfacePoint& s) {
  int a = -1, b = -1;  // the edge's corners (slots in the face), or a = b = -1 for a vertex
  switch (s.feature) {
    case TriangleFeature::interior: return Eigen::Matrix3d::Zero();
    case TriangleFeature::edge_ab: a = 0, b = 1; break;
    case TriangleFeature::edge_bc: a = 1, b = 2; break;
    case TriangleFeature::edge_ca: a = 2, b = 0; break;
    default: break;  // one of the corners
  }
  Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - s.normal * s.normal.transpose();
  if (a >= 0) {
    const Eigen::Vector3d edge =
        body.vertices().row(body.faces()(s.face, b)) - body.vertices().row(body.faces()(s.face, a));
    // A degenerate (zero-length) edge is a point: keep the vertex form.
    if (edge.norm() > 0) {
      const Eigen::Vector3d t = edge.normalized();
      projector -= t * t.transpose();
    }
  }
  const double radius = std::copysign(std::max(std::abs(s.signed_distance), kMinCurvatureRadius), s.signed_distance);
  return projector / radius;
}

}  // namespace

std::vector<Contact> body_contacts(const BodyQuery& body, const Eigen::MatrixX3d& x, bool with_hessian) {
  std::vector<Contact> out(static_cast<std::size_t>(x.rows()));
  if (const auto* surface = dynamic_cast<const BodySurface*>(&body)) {
    const std::vector<SurfacePoint> located = surface->locate_all(x);
    for (std::size_t v = 0; v < out.size(); ++v) {
      out[v].normal = located[v].normal;
      out[v].distance = located[v].signed_distance;
      if (with_hessian) out[v].distance_hessian = distance_hessian(*surface, located[v]);
    }
    return out;
  }
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const BodyQuery::Hit hit = body.closest(x.row(v).transpose());
    out[static_cast<std::size_t>(v)].normal = hit.normal;
    out[static_cast<std::size_t>(v)].distance = hit.signed_distance;
  }
  return out;
}

}  // namespace drape::collision
