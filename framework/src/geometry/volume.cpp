#include <drape/geometry/volume.hpp>

#include <Eigen/Geometry>

namespace drape::geometry {

double mesh_volume(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  double six_volume = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)), c = vertices.row(faces(f, 2));
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

double mesh_area(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  double twice_area = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)), c = vertices.row(faces(f, 2));
    twice_area += (b - a).cross(c - a).norm();
  }
  return twice_area / 2.0;
}

}  // namespace drape::geometry
