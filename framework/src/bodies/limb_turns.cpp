// limb_turns (bodies/limb_turns.hpp).
#include <drape/bodies/limb_turns.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace drape {

namespace {

// The least-squares rotation of `a`'s rows `rows` onto `b`'s, about their centroids (Eigen's Umeyama, no scaling).
Eigen::Matrix3d fitted_rotation(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, const std::vector<int>& rows) {
  const Eigen::Matrix3Xd from = a(rows, Eigen::all).transpose(), to = b(rows, Eigen::all).transpose();
  return Eigen::umeyama(from, to, false).topLeftCorner<3, 3>();
}

// Through the quaternion: acos of the trace loses half the digits near 0 (a
// rounding of 1e-16 reads as 1e-6 degrees).
double angle_degrees(const Eigen::Matrix3d& r) { return Eigen::AngleAxisd(r).angle() * 180.0 / std::numbers::pi; }

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

std::vector<LimbTurn> LimbFit::posed(const Eigen::MatrixX3d& mean, const Eigen::MatrixX3d& body) const {
  std::vector<LimbTurn> out = turns(mean, body);
  std::erase_if(out, [](const LimbTurn& t) { return !(t.degrees > kPosedLimbDegrees); });
  return out;
}

std::vector<LimbTurn> limb_turns(const BodyModel& model, const Eigen::MatrixX3d& mean, const Eigen::MatrixX3d& body) {
  return LimbFit(model).turns(mean, body);
}

}  // namespace drape
