#pragma once
// SMPL bodies for users who hold a licence, from an HDF5 conversion of the
// official model (layout and converter in docs/smpl.md):
//   /v_template [N, 3] f64 or f32   mean-shape vertices, meters, A- or T-pose
//   /shapedirs  [N, 3, B]           shape blend shapes (B = 10 or 300)
//   /f          [F, 3] i32 or i64   triangles
// Only shape is applied (no pose): the project drapes A-pose bodies.
#include <drape/bodies/body.hpp>

#include <filesystem>

namespace drape::smpl {

struct SmplData {
  Eigen::MatrixX3d v_template;
  Eigen::MatrixXd shapedirs;  // [3N, B], row 3*v + axis
  Eigen::MatrixX3i faces;
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

 private:
  double bmi_at(double t, double height) const;
  Eigen::VectorXd shape_at(double t, double height) const;
  SmplData data_;
  int betas_;
  Eigen::VectorXd direction_;  // unit, in betas space
  double t_max_ = 3.0;         // |betas| stay within +-3 standard deviations along the direction
};

}  // namespace drape::smpl
