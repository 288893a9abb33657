#include <drape/geometry/nearest_triangles.hpp>

#include "triangle_bvh.hpp"

#include <drape/errors.hpp>

#include <string>

namespace drape::geometry {

NearestTriangles::NearestTriangles(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces)
    : faces_(faces), num_vertices_(vertices.rows()) {
  if (faces.rows() == 0) throw Error("nearest triangles: the mesh has no faces");
  for (int f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= vertices.rows())
        throw Error("nearest triangles: face " + std::to_string(f) + " uses vertex " + std::to_string(faces(f, k)) +
                    ", outside [0, " + std::to_string(vertices.rows()) + ")");
  bvh_ = std::make_unique<TriangleBvh>(vertices, faces_);
}

NearestTriangles::~NearestTriangles() = default;
NearestTriangles::NearestTriangles(NearestTriangles&&) noexcept = default;
NearestTriangles& NearestTriangles::operator=(NearestTriangles&&) noexcept = default;

void NearestTriangles::update(const Eigen::MatrixX3d& vertices) {
  if (vertices.rows() != num_vertices_)
    throw Error("nearest triangles update: " + std::to_string(vertices.rows()) + " vertices given, the mesh has " +
                std::to_string(num_vertices_));
  bvh_->refit(vertices);
}

SurfacePoint NearestTriangles::nearest(const Eigen::Vector3d& p, int hint) const {
  TrianglePoint hit;
  const int face = bvh_->nearest(p, std::numeric_limits<double>::infinity(), hit, nullptr, 0, hint);
  SurfacePoint r;
  if (face < 0) return r;  // only for a non-finite p
  r.face = face;
  r.barycentric = hit.barycentric;
  r.point = hit.point;
  r.feature = hit.feature;
  r.signed_distance = (p - hit.point).norm();
  return r;
}

std::vector<SurfacePoint> NearestTriangles::nearest_all(const Eigen::MatrixX3d& points, const std::vector<int>& hints) const {
  if (!hints.empty() && static_cast<Eigen::Index>(hints.size()) != points.rows())
    throw Error("nearest triangles: " + std::to_string(hints.size()) + " hints for " + std::to_string(points.rows()) +
                " points");
  std::vector<SurfacePoint> out(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    out[i] = nearest(points.row(i).transpose(), hints.empty() ? -1 : hints[static_cast<std::size_t>(i)]);
  return out;
}

}  // namespace drape::geometry
