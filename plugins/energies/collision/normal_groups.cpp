#include "normal_groups.hpp"

#include <cmath>

namespace drape::collision {
namespace {

// The 26 unit directions (i, j, k) / |(i, j, k)|, i, j, k in {-1, 0, 1}, not all 0.
const std::vector<Eigen::Vector3d>& directions() {
  static const std::vector<Eigen::Vector3d> all = [] {
    std::vector<Eigen::Vector3d> d;
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int k = -1; k <= 1; ++k)
          if (i || j || k) d.push_back(Eigen::Vector3d(i, j, k).normalized());
    return d;
  }();
  return all;
}

int nearest_direction(const Eigen::Vector3d& normal) {
  int best = 0;
  double best_dot = -INFINITY;
  for (std::size_t i = 0; i < directions().size(); ++i)
    if (const double d = normal.dot(directions()[i]); d > best_dot) best_dot = d, best = static_cast<int>(i);
  return best;
}

}  // namespace

std::vector<int> normal_groups(const geometry::BodySurface& body) {
  const Eigen::MatrixX3d& normals = body.face_normals();
  std::vector<int> group(static_cast<std::size_t>(normals.rows()));
  for (Eigen::Index f = 0; f < normals.rows(); ++f)
    group[static_cast<std::size_t>(f)] = nearest_direction(normals.row(f).transpose());
  return group;
}

}  // namespace drape::collision
