#pragma once
// drape::BodyModel over MakeHuman: shape parameters are the macro sliders, and a
// BMI/height request is met by searching the weight/muscle and height sliders.
#include "model.hpp"

#include <drape/bodies/body.hpp>

#include <memory>

namespace drape::makehuman {

// Slider names in shape-vector order.
const std::vector<std::string>& slider_names();
Sliders to_sliders(const Eigen::VectorXd& shape);
Eigen::VectorXd to_shape(const Sliders& s);

// BMI as the project defines it: enclosed volume * 985 kg/m^3 / height^2.
struct BodyMeasure {
  double bmi = 0, height = 0, volume = 0;
};
BodyMeasure measure(const Mesh& body);

class MakeHumanBody final : public BodyModel {
 public:
  // `muscle` < 0: the BMI search moves muscle with weight (widest BMI range);
  // otherwise muscle stays at that slider value and only weight moves.
  MakeHumanBody(std::shared_ptr<const Model> model, double muscle);

  int num_vertices() const override { return model_->body_vertex_count(); }
  const Eigen::MatrixX3i& faces() const override { return model_->body_faces(); }
  std::vector<std::string> shape_names() const override { return slider_names(); }
  Eigen::VectorXd mean_shape() const override;
  // Every slider in [0, 1] (to_sliders).
  std::vector<std::pair<double, double>> shape_ranges() const override { return {8, {0.0, 1.0}}; }
  Eigen::MatrixX3d vertices(const Eigen::VectorXd& shape) const override;
  Eigen::VectorXd solve(const BodyRequest& request) const override;
  std::pair<double, double> bmi_range() const override;
  // The default sliders' BMI and height, and their gender (1: the mean body is a man's).
  BodyRequest mean_request() const override;
  // The range for one sex and height (what solve() can reach for that request).
  std::pair<double, double> bmi_range(double sex, double height) const;

  // Posing by MakeHuman's own rig (rig.hpp, rig_pose.hpp) when the data
  // folder has it (rigs/default.mhskel, rigs/default_weights.mhw); without
  // it every pose is refused naming the missing files.
  bool poseable() const override { return model_->rig_missing().empty(); }
  std::vector<PoseAngle> pose_angles() const override;
  std::vector<Joint> joints() const override { return poseable() ? model_->rig().joints : BodyModel::joints(); }
  // Regressed from the skin (rig.hpp): MakeHuman's joint positions within a
  // few millimetres, and the same for any mesh of this topology.
  Eigen::MatrixX3d joint_positions(const Eigen::VectorXd& shape) const override;
  Eigen::MatrixXd skinning_weights() const override {
    return poseable() ? model_->rig().weights : BodyModel::skinning_weights();
  }
  // MakeHuman's own stance: arms abducted and the elbows bent (rig_pose.hpp).
  Pose rest_pose(const Eigen::VectorXd& shape) const override;
  Pose rest_pose_of(const Eigen::MatrixX3d& unposed) const override;
  Eigen::MatrixX3d posed_vertices(const Eigen::MatrixX3d& unposed, const Pose& pose, double fraction) const override;
  std::vector<skinning::Rigid> joint_transforms(const Eigen::MatrixX3d& unposed, const Pose& pose) const override;

 private:
  Sliders along_path(Sliders s, double t) const;  // t in [0, 1]: thinnest .. heaviest
  Sliders fit_height(Sliders s, double height) const;
  // The bone heads of a body of this topology, after checking its size.
  Eigen::MatrixX3d joints_of(const Eigen::MatrixX3d& unposed) const;
  std::shared_ptr<const Model> model_;
  double muscle_;
};

}  // namespace drape::makehuman
