#include "body_model.hpp"

#include <drape/bodies/body_space.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/volume.hpp>

#include <cmath>
#include <sstream>

namespace drape::makehuman {

const std::vector<std::string>& slider_names() {
  static const std::vector<std::string> names = {"gender", "muscle", "weight", "height", "proportions",
                                                 "african", "asian", "caucasian"};
  return names;
}

Sliders to_sliders(const Eigen::VectorXd& v) {
  if (v.size() != 8) throw ConfigError("a MakeHuman shape has 8 sliders (" + std::to_string(v.size()) + " given)");
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!(v[i] >= 0.0 && v[i] <= 1.0))
      throw ConfigError("MakeHuman slider '" + slider_names()[static_cast<std::size_t>(i)] + "' must be in [0, 1], got " +
                        std::to_string(v[i]));
  return {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]};
}

Eigen::VectorXd to_shape(const Sliders& s) {
  Eigen::VectorXd v(8);
  v << s.gender, s.muscle, s.weight, s.height, s.proportions, s.african, s.asian, s.caucasian;
  return v;
}

BodyMeasure measure(const Mesh& body) {
  BodyMeasure m;
  m.volume = geometry::mesh_volume(body.vertices, body.faces);
  m.height = body.vertices.col(1).maxCoeff() - body.vertices.col(1).minCoeff();
  m.bmi = m.volume * 985.0 / (m.height * m.height);
  return m;
}

MakeHumanBody::MakeHumanBody(std::shared_ptr<const Model> model, double muscle) : model_(std::move(model)), muscle_(muscle) {}

Eigen::VectorXd MakeHumanBody::mean_shape() const { return to_shape(Sliders{}); }

BodyRequest MakeHumanBody::mean_request() const {
  const BodyMeasure m = measure(model_->body(Sliders{}));
  BodyRequest r;
  r.bmi = m.bmi;
  r.height = m.height;
  r.sex = Sliders{}.gender;
  return r;
}

Eigen::MatrixX3d MakeHumanBody::vertices(const Eigen::VectorXd& shape) const { return model_->body(to_sliders(shape)).vertices; }

// The path through (muscle, weight) used by the BMI search. With free muscle it
// runs minmuscle-minweight -> average -> minmuscle-maxweight, which MakeHuman's
// own figures show spans the widest BMI range (~13-37); BMI grows along it.
Sliders MakeHumanBody::along_path(Sliders s, double t) const {
  s.weight = t;
  s.muscle = muscle_ >= 0.0 ? muscle_ : 0.5 * (1.0 - std::abs(2.0 * t - 1.0));
  return s;
}

Sliders MakeHumanBody::fit_height(Sliders s, double height) const {
  // Height is monotone in its slider; bisection to 1 mm.
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 30 && hi - lo > 1e-5; ++i) {
    s.height = 0.5 * (lo + hi);
    const double h = measure(model_->body(s)).height;
    if (std::abs(h - height) < 5e-4) return s;
    (h < height ? lo : hi) = s.height;
  }
  s.height = 0.5 * (lo + hi);
  return s;
}

std::pair<double, double> MakeHumanBody::bmi_range(double sex, double height) const {
  Sliders s;
  s.gender = sex;
  const Sliders thin = fit_height(along_path(s, 0.0), height);
  const Sliders heavy = fit_height(along_path(s, 1.0), height);
  return {measure(model_->body(thin)).bmi, measure(model_->body(heavy)).bmi};
}

std::pair<double, double> MakeHumanBody::bmi_range() const {
  // Over both sexes at their default heights: the union of what solve() reaches.
  Sliders female, male;
  female.gender = 0.0;
  male.gender = 1.0;
  const double lo = std::min(measure(model_->body(along_path(female, 0.0))).bmi, measure(model_->body(along_path(male, 0.0))).bmi);
  const double hi = std::max(measure(model_->body(along_path(female, 1.0))).bmi, measure(model_->body(along_path(male, 1.0))).bmi);
  return {lo, hi};
}

Eigen::VectorXd MakeHumanBody::solve(const BodyRequest& r) const {
  check_proportions(*this, "makehuman", r);  // it offers none: a request with girths is refused
  if (!(r.sex >= 0.0 && r.sex <= 1.0)) throw ConfigError("sex must be in [0, 1] (0 female, 1 male)");
  Sliders s;
  s.gender = r.sex;
  // Height first at average weight, then alternate: BMI moves height a little.
  s = fit_height(along_path(s, 0.5), r.height);
  const double h_slider_check = measure(model_->body(s)).height;
  if (std::abs(h_slider_check - r.height) > 0.01)
    throw ConfigError("MakeHuman cannot reach height " + std::to_string(r.height) + " m for this sex");
  for (int round = 0; round < 3; ++round) {
    const double lo_bmi = measure(model_->body(fit_height(along_path(s, 0.0), r.height))).bmi;
    const double hi_bmi = measure(model_->body(fit_height(along_path(s, 1.0), r.height))).bmi;
    if (r.bmi < lo_bmi - 0.25 || r.bmi > hi_bmi + 0.25) {
      std::ostringstream o;
      o.precision(3);
      o << "MakeHuman reaches BMI " << lo_bmi << " to " << hi_bmi << " for sex " << r.sex << " and height " << r.height
        << " m; BMI " << r.bmi << " is outside (it would extrapolate the targets into broken meshes). "
        << "Use the parametric body for BMI 10-65.";
      throw ConfigError(o.str());
    }
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 40 && hi - lo > 1e-6; ++i) {
      const double t = 0.5 * (lo + hi);
      const Sliders trial = along_path(s, t);
      const double bmi = measure(model_->body(trial)).bmi;
      (bmi < r.bmi ? lo : hi) = t;
    }
    s = fit_height(along_path(s, 0.5 * (lo + hi)), r.height);
    const BodyMeasure m = measure(model_->body(s));
    if (std::abs(m.bmi - r.bmi) < 0.1 && std::abs(m.height - r.height) < 0.005) break;
  }
  return to_shape(s);
}

}  // namespace drape::makehuman
