// Linear blend skinning (skinning.hpp).
#include <drape/bodies/skinning.hpp>
#include <drape/errors.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace drape::skinning {
namespace {

Rigid turn_about(const Eigen::Matrix3d& r, const Eigen::Vector3d& centre) { return {r, centre - r * centre}; }
Rigid then(const Rigid& parent, const Rigid& own) { return {parent.r * own.r, parent.r * own.t + parent.t}; }

}  // namespace

std::vector<Rigid> joint_transforms(const std::vector<int>& parents, const std::vector<Eigen::Matrix3d>& local,
                                    const Eigen::MatrixX3d& joints) {
  const std::size_t n = parents.size();
  if (local.size() != n || static_cast<std::size_t>(joints.rows()) != n)
    throw Error("skinning: " + std::to_string(n) + " joints' parents, " + std::to_string(local.size()) +
                " rotations and " + std::to_string(joints.rows()) + " joint centres");
  std::vector<Rigid> global(n);
  for (std::size_t b = 0; b < n; ++b) {
    const Rigid own = turn_about(local[b], joints.row(static_cast<Eigen::Index>(b)).transpose());
    const int parent = parents[b];
    if (parent >= static_cast<int>(b)) throw Error("skinning: joint " + std::to_string(b) + " comes before its parent");
    global[b] = parent < 0 ? own : then(global[static_cast<std::size_t>(parent)], own);
  }
  return global;
}

Eigen::MatrixX3d blend(const Eigen::MatrixX3d& vertices, const Eigen::MatrixXd& weights,
                       const std::vector<Rigid>& transforms) {
  if (weights.rows() != vertices.rows() || static_cast<std::size_t>(weights.cols()) != transforms.size())
    throw Error("skinning: weights of " + std::to_string(weights.rows()) + " vertices and " +
                std::to_string(weights.cols()) + " joints for " + std::to_string(vertices.rows()) + " vertices and " +
                std::to_string(transforms.size()) + " joints");
  Eigen::MatrixX3d out = vertices;
  for (std::size_t b = 0; b < transforms.size(); ++b) {
    const Rigid& g = transforms[b];
    if (g.identity()) continue;
    const Eigen::Matrix3d d = g.r - Eigen::Matrix3d::Identity();
    const auto col = static_cast<Eigen::Index>(b);
    for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
      const double w = weights(v, col);
      if (w == 0) continue;
      out.row(v) += w * (d * vertices.row(v).transpose() + g.t).transpose();
    }
  }
  return out;
}

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& axis_angle) {
  const double angle = axis_angle.norm();
  if (angle == 0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, axis_angle / angle).toRotationMatrix();
}

}  // namespace drape::skinning
