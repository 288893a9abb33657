#include <drape/geometry/body_correspondence.hpp>

#include <drape/errors.hpp>

#include <nanoflann.hpp>

#include <functional>
#include <string>

namespace drape::geometry {

SurfaceAttachment attach_to_surface(const BodySurface& body, const Eigen::MatrixX3d& points) {
  const std::vector<SurfacePoint> hits = body.locate_all(points);
  SurfaceAttachment a;
  a.face.resize(points.rows());
  a.barycentric.resize(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    a.face[i] = hits[i].face;
    a.barycentric.row(i) = hits[i].barycentric;
  }
  return a;
}

SurfaceAttachment attach_to_surface(const Mesh& body, const Eigen::MatrixX3d& points) {
  return attach_to_surface(BodySurface(body), points);
}

Eigen::MatrixX3d attached_points(const Eigen::MatrixX3d& body_vertices, const Eigen::MatrixX3i& body_faces,
                                 const SurfaceAttachment& attachment) {
  Eigen::MatrixX3d out(attachment.size(), 3);
  for (int i = 0; i < attachment.size(); ++i) {
    const int f = attachment.face[i];
    if (f < 0 || f >= body_faces.rows())
      throw Error("attached points: point " + std::to_string(i) + " is on face " + std::to_string(f) +
                  ", the body has " + std::to_string(body_faces.rows()) + " faces");
    out.row(i).setZero();
    for (int k = 0; k < 3; ++k) out.row(i) += attachment.barycentric(i, k) * body_vertices.row(body_faces(f, k));
  }
  return out;
}

std::vector<int> body_to_garment_correspondence(const Mesh& body, const Mesh& garment) {
  if (garment.vertices.rows() == 0) throw Error("body-to-garment correspondence: the garment has no vertices");
  const BodySurface surface(body);
  const std::vector<SurfacePoint> hits = surface.locate_all(garment.vertices);
  // Nearest vertices are point queries: nanoflann's kd-tree is the right tool.
  using KdTree = nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d, 3>;
  const KdTree tree(3, std::cref(body.vertices), 10);
  std::vector<int> out(hits.size());
  const Eigen::Index n = garment.vertices.rows();
#pragma omp parallel for schedule(static, 64)
  for (Eigen::Index i = 0; i < n; ++i) {
    KdTree::IndexType index = 0;
    double distance2 = 0;
    tree.query(hits[i].point.data(), 1, &index, &distance2);
    out[i] = static_cast<int>(index);
  }
  return out;
}

}  // namespace drape::geometry
