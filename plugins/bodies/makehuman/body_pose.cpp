// Posing the MakeHuman body by MakeHuman's own rig (body_model.hpp; the
// angles' meaning on its bones in rig_pose.cpp).
#include "body_model.hpp"
#include "rig_pose.hpp"

#include <drape/bodies/skinning.hpp>
#include <drape/errors.hpp>

namespace drape::makehuman {

std::vector<PoseAngle> MakeHumanBody::pose_angles() const {
  if (!poseable()) return {};
  return human_pose_angles();
}

Eigen::MatrixX3d MakeHumanBody::joints_of(const Eigen::MatrixX3d& unposed) const {
  const Rig& rig = model_->rig();  // refuses first when the rig is missing
  if (unposed.rows() != num_vertices())
    throw ConfigError("body makehuman: a body to pose has " + std::to_string(unposed.rows()) + " vertices, the model " +
                      std::to_string(num_vertices()));
  return regress_joints(rig, unposed);
}

Eigen::MatrixX3d MakeHumanBody::joint_positions(const Eigen::VectorXd& shape) const { return joints_of(vertices(shape)); }

// Without the rig, what BodyModel does for a model without a skeleton: no
// angles, and the empty pose is the unposed body; any other pose is refused
// by joints_of, naming the missing files.
Pose MakeHumanBody::rest_pose(const Eigen::VectorXd& shape) const {
  return poseable() ? rest_angles(model_->rig(), joint_positions(shape)) : Pose{};
}

Pose MakeHumanBody::rest_pose_of(const Eigen::MatrixX3d& unposed) const {
  return poseable() ? rest_angles(model_->rig(), joints_of(unposed)) : Pose{};
}

Eigen::MatrixX3d MakeHumanBody::posed_vertices(const Eigen::MatrixX3d& unposed, const Pose& pose, double fraction) const {
  if (!poseable() && pose.empty()) return unposed;
  const Eigen::MatrixX3d joints = joints_of(unposed);
  check_pose(pose, pose_angles(), "body makehuman pose");
  if (!(fraction >= 0 && fraction <= 1)) throw ConfigError("body makehuman: a pose fraction must lie in [0, 1]");
  if (pose.empty() || fraction == 0) return unposed;
  // Plain linear blend skinning with MakeHuman's weights (docs/poses.md says where it holds).
  return skinning::blend(unposed, model_->rig().weights, rig_transforms(model_->rig(), joints, pose, fraction));
}

std::vector<skinning::Rigid> MakeHumanBody::joint_transforms(const Eigen::MatrixX3d& unposed, const Pose& pose) const {
  const Eigen::MatrixX3d joints = joints_of(unposed);
  check_pose(pose, pose_angles(), "body makehuman pose");
  return rig_transforms(model_->rig(), joints, pose, 1.0);
}

}  // namespace drape::makehuman
