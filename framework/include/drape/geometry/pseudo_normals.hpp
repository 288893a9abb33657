#pragma once
// The sign of a closest point on a body mesh, from the pseudo-normal of the
// feature it lies on (Baerentzen & Aanaes 2005): the face's normal inside a
// face, the sum of the two faces' normals on an edge, the angle-weighted sum
// of the faces' normals at a vertex. BodySurface computes every one of them
// when its body moves; PseudoNormals computes only those of the features
// asked about, from the body's vertices as they are: a loss that signs a
// thousand garment vertices per training sample, each on another body, needs
// a few thousand normals, not the whole body's (whose angles alone cost a
// fifth of a training step). Both use the functions below, so their signs
// and normals are the same bits.
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::geometry {

// A face's unit normal (zero for a degenerate face) and its corner angles.
Eigen::Vector3d face_normal(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, int face);
double corner_angle(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, int face, int corner);

// p's signed closest point: the closest point found on `face` (hit) with the
// sign of (p - point) . pseudo and the normal (p - point) / signed distance,
// or `pseudo` itself within `on_surface_tolerance` of the surface.
SurfacePoint signed_surface_point(const Eigen::Vector3d& p, int face, const TrianglePoint& hit,
                                  const Eigen::Vector3d& pseudo, double on_surface_tolerance);

// BodySurface's tolerance below which a point counts as on the surface: 1e-10
// of the bounding box's diagonal.
double on_surface_tolerance(const Eigen::MatrixX3d& vertices);

class PseudoNormals {
 public:
  // The body's faces (its topology); the vertices come with each query.
  explicit PseudoNormals(const Eigen::MatrixX3i& faces);

  // The unit pseudo-normal of `feature` of `face` on the body `vertices`.
  Eigen::Vector3d at(const Eigen::MatrixX3d& vertices, int face, TriangleFeature feature) const;
  // `closest` (face, point, barycentric, feature of p's closest point, found
  // elsewhere) signed as BodySurface::locate signs it; tolerance from
  // on_surface_tolerance(vertices).
  SurfacePoint sign(const Eigen::MatrixX3d& vertices, const Eigen::Vector3d& p, const SurfacePoint& closest,
                    double tolerance) const;

 private:
  Eigen::MatrixX3i faces_;
  std::vector<std::array<int, 3>> neighbours_;  // the face across each edge (ab, bc, ca), -1 on a boundary
  std::vector<int> vertex_start_, vertex_faces_;  // the faces of vertex v, in increasing order
};

}  // namespace drape::geometry
