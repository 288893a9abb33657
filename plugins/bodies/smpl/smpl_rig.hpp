#pragma once
// SMPL's pose: its kinematic tree, joint regressor, skinning weights and pose
// blend shapes, read from the optional datasets of the HDF5 conversion
// (docs/smpl.md), and a body posed by θ exactly as the SMPL paper defines it
// (Loper et al. 2015, "SMPL: A Skinned Multi-Person Linear Model", eqs. 1-10):
//   J = J_regressor · (shaped vertices)
//   v_P = shaped + posedirs · (R(θ_j) - I) over the non-root joints j
//   v' = sum_k w_k G'_k(θ, J) v_P (linear blend skinning, drape/bodies/skinning.hpp)
// θ_j is joint j's axis-angle vector, R by Rodrigues' formula. The root's
// rotation (SMPL's global orientation) is not used: drape's bodies stand
// upright under gravity -Y.
#include <drape/bodies/body.hpp>
#include <drape/io/h5.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace drape::smpl {

struct SmplRig {
  std::vector<std::string> names;  // one per joint, the root first
  std::vector<int> parents;        // -1 for the root, each before its children
  Eigen::MatrixXd j_regressor;     // [K, N]
  Eigen::MatrixXd weights;         // [N, K]
  Eigen::MatrixXd posedirs;        // [3N, 9(K-1)], row 3 v + axis, column 9 (j-1) + 3 row + col of R_j - I
  int num_joints() const { return static_cast<int>(parents.size()); }
};

// The four pose datasets (/J_regressor, /weights, /kintree_table, /posedirs)
// of `file` for a mesh of `num_vertices` vertices; none when the file has none
// of them. ConfigError naming the file when only some are there, or their
// sizes disagree (with both sizes).
std::optional<SmplRig> read_smpl_rig(const h5::File& file, Eigen::Index num_vertices);

// SMPL's 24 joint names (pelvis, left_hip, ..., right_hand) for K = 24;
// joint1, joint2, ... for any other K (SMPL-H, SMPL-X, a custom rig).
std::vector<std::string> smpl_joint_names(int num_joints);

// The pose angles of a rig: <joint>_x, _y, _z for every joint but the root,
// the components of its axis-angle vector in degrees.
std::vector<PoseAngle> smpl_pose_angles(const SmplRig& rig);
std::vector<BodyModel::Joint> smpl_joints(const SmplRig& rig);

// Each joint's axis-angle vector in radians from a pose, times `fraction`
// (angles the pose does not set are 0); the root's is zero.
std::vector<Eigen::Vector3d> axis_angles(const SmplRig& rig, const Pose& pose, double fraction);

// The shaped body `shaped` (N x 3, the model's vertices of some shape, times
// `scale` and moved, as SmplBody::vertices makes them) posed by `theta`:
// pose blend shapes times `scale` (they are in the file's units), joints
// regressed from `shaped`, then linear blend skinning. All-zero θ gives
// `shaped` bit for bit.
Eigen::MatrixX3d pose_shaped(const SmplRig& rig, const Eigen::MatrixX3d& shaped, double scale,
                             const std::vector<Eigen::Vector3d>& theta);
// The joints' transforms pose_shaped blends (without the pose blend shapes).
std::vector<skinning::Rigid> pose_transforms(const SmplRig& rig, const Eigen::MatrixX3d& shaped,
                                             const std::vector<Eigen::Vector3d>& theta);

}  // namespace drape::smpl
