#include <drape/geometry/pseudo_normals.hpp>

#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace drape::geometry {

Eigen::Vector3d face_normal(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, int face) {
  const Eigen::Vector3d a = vertices.row(faces(face, 0)), b = vertices.row(faces(face, 1)), c = vertices.row(faces(face, 2));
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double length = n.norm();
  // A degenerate face has no direction: it adds nothing to its neighbours' pseudo-normals.
  return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

double corner_angle(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, int face, int corner) {
  const Eigen::Vector3d p = vertices.row(faces(face, corner)), q = vertices.row(faces(face, (corner + 1) % 3)),
                        r = vertices.row(faces(face, (corner + 2) % 3));
  const Eigen::Vector3d e1 = q - p, e2 = r - p;
  return std::atan2(e1.cross(e2).norm(), e1.dot(e2));
}

SurfacePoint signed_surface_point(const Eigen::Vector3d& p, int face, const TrianglePoint& hit,
                                  const Eigen::Vector3d& pseudo, double on_surface_tolerance) {
  SurfacePoint r;
  r.face = face;
  r.barycentric = hit.barycentric;
  r.point = hit.point;
  r.feature = hit.feature;
  const Eigen::Vector3d offset = p - hit.point;
  const double distance = offset.norm();
  r.signed_distance = offset.dot(pseudo) < 0 ? -distance : distance;
  r.normal = distance > on_surface_tolerance ? Eigen::Vector3d(offset / r.signed_distance) : pseudo;
  return r;
}

double on_surface_tolerance(const Eigen::MatrixX3d& vertices) {
  const double diagonal = (vertices.colwise().maxCoeff() - vertices.colwise().minCoeff()).norm();
  return 1e-10 * std::max(diagonal, 1e-300);
}

PseudoNormals::PseudoNormals(const Eigen::MatrixX3i& faces) : faces_(faces), neighbours_(face_neighbours(faces)) {
  const int nv = faces.size() > 0 ? faces.maxCoeff() + 1 : 0;
  vertex_start_.assign(static_cast<std::size_t>(nv) + 1, 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++vertex_start_[static_cast<std::size_t>(faces(f, k)) + 1];
  for (std::size_t v = 0; v < static_cast<std::size_t>(nv); ++v) vertex_start_[v + 1] += vertex_start_[v];
  vertex_faces_.resize(static_cast<std::size_t>(vertex_start_.back()));
  std::vector<int> fill(vertex_start_.begin(), vertex_start_.end() - 1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)  // faces in increasing order within each vertex's list
    for (int k = 0; k < 3; ++k) vertex_faces_[static_cast<std::size_t>(fill[static_cast<std::size_t>(faces(f, k))]++)] = static_cast<int>(f);
}

Eigen::Vector3d PseudoNormals::at(const Eigen::MatrixX3d& vertices, int face, TriangleFeature feature) const {
  using F = TriangleFeature;
  auto vertex_normal = [&](int corner) {
    // Summed over the vertex's faces in increasing order, as BodySurface accumulates them.
    const int v = faces_(face, corner);
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int i = vertex_start_[static_cast<std::size_t>(v)]; i < vertex_start_[static_cast<std::size_t>(v) + 1]; ++i) {
      const int f = vertex_faces_[static_cast<std::size_t>(i)];
      const int k = faces_(f, 0) == v ? 0 : faces_(f, 1) == v ? 1 : 2;
      n += corner_angle(vertices, faces_, f, k) * face_normal(vertices, faces_, f);
    }
    return Eigen::Vector3d(n.normalized());
  };
  auto edge_normal = [&](int edge) {
    // Non-manifold edges have no single mate: their pseudo-normal is the face's own.
    const int g = neighbours_[static_cast<std::size_t>(face)][static_cast<std::size_t>(edge)];
    Eigen::Vector3d n = face_normal(vertices, faces_, face);
    if (g >= 0) n += face_normal(vertices, faces_, g);
    return Eigen::Vector3d(n.normalized());
  };
  switch (feature) {
    case F::vertex_a: return vertex_normal(0);
    case F::vertex_b: return vertex_normal(1);
    case F::vertex_c: return vertex_normal(2);
    case F::edge_ab: return edge_normal(0);
    case F::edge_bc: return edge_normal(1);
    case F::edge_ca: return edge_normal(2);
    default: return face_normal(vertices, faces_, face);
  }
}

SurfacePoint PseudoNormals::sign(const Eigen::MatrixX3d& vertices, const Eigen::Vector3d& p, const SurfacePoint& closest,
                                 double tolerance) const {
  if (closest.face < 0 || closest.face >= faces_.rows())
    throw Error("pseudo-normals: closest point on face " + std::to_string(closest.face) + " of " +
                std::to_string(faces_.rows()));
  return signed_surface_point(p, closest.face, TrianglePoint{closest.point, closest.barycentric, closest.feature},
                              at(vertices, closest.face, closest.feature), tolerance);
}

}  // namespace drape::geometry
