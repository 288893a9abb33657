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

double body_height(const Eigen::MatrixX3d& vertices) { return vertices.col(1).maxCoeff() - vertices.col(1).minCoeff(); }

double body_bmi(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  constexpr double kBodyDensity = 985.0;  // kg/m^3
  const double h = body_height(vertices);
  return mesh_volume(vertices, faces) * kBodyDensity / (h * h);
}

}  // namespace drape::geometry
