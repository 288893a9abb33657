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
  Eigen::MatrixX3d vertices(const Eigen::VectorXd& shape) const override;
  Eigen::VectorXd solve(const BodyRequest& request) const override;
  std::pair<double, double> bmi_range() const override;
  // The default sliders' BMI and height, and their gender (1: the mean body is a man's).
  BodyRequest mean_request() const override;
  // The range for one sex and height (what solve() can reach for that request).
  std::pair<double, double> bmi_range(double sex, double height) const;

 private:
  Sliders along_path(Sliders s, double t) const;  // t in [0, 1]: thinnest .. heaviest
  Sliders fit_height(Sliders s, double height) const;
  std::shared_ptr<const Model> model_;
  double muscle_;
};

}  // namespace drape::makehuman
