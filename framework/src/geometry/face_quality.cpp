#include <drape/geometry/face_quality.hpp>

#include <drape/errors.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace drape::geometry {

Eigen::MatrixX3d face_normals(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  Eigen::MatrixX3d n(faces.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)), c = vertices.row(faces(f, 2));
    n.row(f) = (b - a).cross(c - a);
  }
  return n;
}

std::vector<int> degenerate_faces(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, double min_area,
                                  double min_angle) {
  std::vector<int> bad;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d p[3] = {vertices.row(faces(f, 0)), vertices.row(faces(f, 1)), vertices.row(faces(f, 2))};
    const double twice_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
    double smallest = M_PI;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
      // atan2 of |cross| and dot stays accurate for tiny angles, unlike acos.
      smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)));
    }
    if (!(twice_area / 2 >= min_area) || !(smallest >= min_angle)) bad.push_back(static_cast<int>(f));
  }
  return bad;
}

std::vector<int> inverted_faces(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                const Eigen::MatrixX3d& reference) {
  if (reference.rows() != faces.rows())
    throw Error("inverted_faces: " + std::to_string(reference.rows()) + " reference directions for " +
                std::to_string(faces.rows()) + " faces");
  const Eigen::MatrixX3d n = face_normals(vertices, faces);
  std::vector<int> bad;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    if (!(n.row(f).dot(reference.row(f)) > 0)) bad.push_back(static_cast<int>(f));
  return bad;
}

std::vector<std::array<int, 2>> folded_edges(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                             double max_angle) {
  const Eigen::MatrixX3d n = face_normals(vertices, faces);
  // (lo, hi, face) for every face corner edge; equal keys are the two faces of an edge.
  std::vector<std::array<int, 3>> half;
  half.reserve(static_cast<std::size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = faces(f, k), v = faces(f, (k + 1) % 3);
      half.push_back({std::min(u, v), std::max(u, v), static_cast<int>(f)});
    }
  std::sort(half.begin(), half.end());
  const double min_cos = std::cos(max_angle);
  std::vector<std::array<int, 2>> bad;
  for (std::size_t i = 0; i + 1 < half.size(); ++i) {
    if (half[i][0] != half[i + 1][0] || half[i][1] != half[i + 1][1]) continue;
    const Eigen::Vector3d a = n.row(half[i][2]), b = n.row(half[i + 1][2]);
    const double denom = a.norm() * b.norm();
    if (!(denom > 0) || a.dot(b) < min_cos * denom) bad.push_back({half[i][0], half[i][1]});
  }
  return bad;
}

}  // namespace drape::geometry
