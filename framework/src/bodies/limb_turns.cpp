// limb_turns (bodies/limb_turns.hpp).
#include <drape/bodies/limb_turns.hpp>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace drape {

namespace {

// The rotation R minimising sum |b_i - c_b - R (a_i - c_a)|^2 over the rows `rows`.
Eigen::Matrix3d fitted_rotation(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, const std::vector<int>& rows) {
  Eigen::RowVector3d ca = Eigen::RowVector3d::Zero(), cb = Eigen::RowVector3d::Zero();
  for (int r : rows) ca += a.row(r), cb += b.row(r);
  ca /= static_cast<double>(rows.size()), cb /= static_cast<double>(rows.size());
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (int r : rows) h += (a.row(r) - ca).transpose() * (b.row(r) - cb);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0) d(2, 2) = -1;
  return svd.matrixV() * d * svd.matrixU().transpose();
}

double angle_degrees(const Eigen::Matrix3d& r) {
  return std::acos(std::clamp(0.5 * (r.trace() - 1.0), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace

LimbFit::LimbFit(const BodyModel& model) {
  if (!model.poseable()) return;
  joints_ = model.joints();
  const Eigen::MatrixXd weights = model.skinning_weights();
  constexpr double kOwn = 0.95;  // a vertex this bone moves (nearly) alone
  own_.resize(joints_.size());
  for (Eigen::Index v = 0; v < weights.rows(); ++v)
    for (Eigen::Index j = 0; j < weights.cols() && j < static_cast<Eigen::Index>(joints_.size()); ++j)
      if (weights(v, j) >= kOwn) own_[static_cast<std::size_t>(j)].push_back(static_cast<int>(v));
}

std::vector<LimbTurn> LimbFit::turns(const Eigen::MatrixX3d& mean, const Eigen::MatrixX3d& body) const {
  std::vector<Eigen::Matrix3d> rotation(joints_.size(), Eigen::Matrix3d::Identity());
  std::vector<bool> fitted(joints_.size(), false);
  for (std::size_t j = 0; j < joints_.size(); ++j)
    if (own_[j].size() >= 3) rotation[j] = fitted_rotation(mean, body, own_[j]), fitted[j] = true;
  std::vector<LimbTurn> out;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const int parent = joints_[j].parent;
    if (joints_[j].angles.empty() || parent < 0 || !fitted[j] || !fitted[static_cast<std::size_t>(parent)]) continue;
    const Eigen::Matrix3d relative = rotation[static_cast<std::size_t>(parent)].transpose() * rotation[j];
    out.push_back({joints_[j].name, angle_degrees(relative)});
  }
  return out;
}

std::vector<LimbTurn> limb_turns(const BodyModel& model, const Eigen::MatrixX3d& mean, const Eigen::MatrixX3d& body) {
  return LimbFit(model).turns(mean, body);
}

}  // namespace drape
