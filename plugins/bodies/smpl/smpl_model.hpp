#pragma once
// SMPL bodies for users who hold a licence, from an HDF5 conversion of the
// official model (layout and converter in docs/smpl.md):
//   /v_template [N, 3] f64 or f32   mean-shape vertices, meters, A- or T-pose
//   /shapedirs  [N, 3, B]           shape blend shapes (B = 10 or 300)
//   /f          [F, 3] i32 or i64   triangles
// and, optionally, SMPL's pose (smpl_rig.hpp): /J_regressor [K, N], /weights
// [N, K], /kintree_table [2, K], /posedirs [N, 3, 9(K-1)]. With them the body
// is poseable by θ (pose angles <joint>_x/_y/_z, degrees); without, it makes
// unposed bodies only.
#include "smpl_rig.hpp"

#include <drape/bodies/body.hpp>

#include <Eigen/QR>

#include <filesystem>
#include <mutex>
#include <optional>

namespace drape::smpl {

struct SmplData {
  Eigen::MatrixX3d v_template;
  Eigen::MatrixXd shapedirs;  // [3N, B], row 3*v + axis
  Eigen::MatrixX3i faces;
  std::optional<SmplRig> rig;  // SMPL's pose, when the file has it
  std::filesystem::path file;  // where it was read from, for messages
};

SmplData read_smpl_h5(const std::filesystem::path& file);

class SmplBody final : public BodyModel {
 public:
  SmplBody(SmplData data, int num_betas);
  int num_vertices() const override { return static_cast<int>(data_.v_template.rows()); }
  const Eigen::MatrixX3i& faces() const override { return data_.faces; }
  std::vector<std::string> shape_names() const override;  // "beta0".. then "scale"
  Eigen::VectorXd mean_shape() const override;
  Eigen::MatrixX3d vertices(const Eigen::VectorXd& shape) const override;
  // BMI along the betas direction that changes the volume most (measured at the
  // mean), then a uniform scale for the height, as SMPL has no height parameter.
  Eigen::VectorXd solve(const BodyRequest& request) const override;
  std::pair<double, double> bmi_range() const override;

  // Posing by SMPL's θ (smpl_rig.hpp), when the file has the pose datasets.
  bool poseable() const override { return data_.rig.has_value(); }
  std::vector<PoseAngle> pose_angles() const override;
  std::vector<Joint> joints() const override;
  Eigen::MatrixX3d joint_positions(const Eigen::VectorXd& shape) const override;
  Eigen::MatrixXd skinning_weights() const override;
  Pose rest_pose(const Eigen::VectorXd& shape) const override;  // every angle 0: the file's own rest (a T-pose for SMPL)
  Eigen::MatrixX3d posed(const Eigen::VectorXd& shape, const Pose& pose) const override;
  // θ times `fraction` (the rest is θ = 0).
  Eigen::MatrixX3d posed_vertices(const Eigen::MatrixX3d& unposed, const Pose& pose, double fraction) const override;
  std::vector<skinning::Rigid> joint_transforms(const Eigen::MatrixX3d& unposed, const Pose& pose) const override;

 private:
  const SmplRig& rig() const;  // ConfigError naming the file when it has no pose datasets
  // The scale of a body of this model (shape's last entry) recovered from its
  // mesh alone: the least-squares fit of unposed = s v_template + shapedirs c + t.
  double scale_of(const Eigen::MatrixX3d& unposed) const;
  double bmi_at(double t, double height) const;
  Eigen::VectorXd shape_at(double t, double height) const;
  SmplData data_;
  int betas_;
  Eigen::VectorXd direction_;  // unit, in betas space
  double t_max_ = 3.0;         // |betas| stay within +-3 standard deviations along the direction
  // [v_template | shapedirs (the betas used) | unit translations], 3N rows,
  // factored once when the model is poseable (scale_of).
  std::optional<Eigen::ColPivHouseholderQR<Eigen::MatrixXd>> scale_fit_;
  mutable std::once_flag sex_warned_;  // a requested sex is not used: said once per model
};

}  // namespace drape::smpl
