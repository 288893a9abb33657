// The built-in parametric body: the default body model everywhere.
#include "body_memo.hpp"
#include "body_plan.hpp"
#include "body_template.hpp"
#include "posing.hpp"
#include "shape_fit.hpp"
#include "skeleton.hpp"
#include "template_cache.hpp"

#include <drape/bodies/body_space.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/bodies/body.hpp>
#include <drape/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

namespace drape::parametric {
namespace {

constexpr double kDensity = 985.0;  // kg/m^3, as the seed computes BMI from the mesh
constexpr double kBmiMin = 10.0, kBmiMax = 65.0;
constexpr double kBmiTolerance = 0.05;  // the solve stops this close to the request
// BMI ~ kBmiAtZeroWeight * exp(weight / kWeightPerLogBmi): the solver's first guess.
constexpr double kBmiAtZeroWeight = 20.0, kWeightPerLogBmi = 0.83;
// Girths a request may hold: +-0.15 in log factor, +-16 % of a girth.
constexpr double kGirthSpread = 0.15;

int index_of(const std::string& name) {
  for (int i = 0; i < kNumShape; ++i)
    if (shape_specs()[static_cast<std::size_t>(i)].name == name) return i;
  throw ConfigError("body parametric: no shape parameter '" + name + "'");
}

// Made once per process and rig and shared by every instance: read from the
// template cache, or meshed (about 0.15 s) and cached (template_cache.hpp).
const BodyTemplate& shared_template(Rig rig) {
  if (rig == Rig::Human) {
    static const BodyTemplate human = cached_template(6500, Rig::Human);
    return human;
  }
  static const BodyTemplate mannequin = cached_template(6500, Rig::Mannequin);
  return mannequin;
}

// Computed once per topology, from the template (skeleton.hpp).
const Skeleton& shared_skeleton(Rig rig) {
  if (rig == Rig::Human) {
    static const Skeleton human = build_skeleton(shared_template(Rig::Human));
    return human;
  }
  static const Skeleton mannequin = build_skeleton(shared_template(Rig::Mannequin));
  return mannequin;
}

// The last bodies made, shared by every instance of a rig as the template is:
// each scene, size of a size chart and assets build makes its own model
// instance, and they ask for the same bodies (the mean body, every size's fit
// body). Up to 128 bodies (20 MB at most); a size chart's fits make about 80.
BodyMemo& shared_memo(Rig rig) {
  if (rig == Rig::Human) {
    static BodyMemo human{128};
    return human;
  }
  static BodyMemo mannequin{128};
  return mannequin;
}

class ParametricBody final : public BodyModel {
 public:
  explicit ParametricBody(Rig rig) : rig_(rig), tpl_(shared_template(rig)) {}

  bool poseable() const override { return true; }
  std::vector<PoseAngle> pose_angles() const override { return human_pose_angles(); }
  std::vector<Joint> joints() const override { return skeleton().joints; }
  Eigen::MatrixX3d joint_positions(const Eigen::VectorXd& shape) const override {
    return regress_joints(skeleton(), vertices(shape));
  }
  Eigen::MatrixXd skinning_weights() const override { return skeleton().weights; }
  Pose rest_pose(const Eigen::VectorXd& shape) const override { return rest_angles(joint_positions(shape)); }
  Pose rest_pose_of(const Eigen::MatrixX3d& unposed) const override {
    if (unposed.rows() != num_vertices())
      throw ConfigError("body parametric: a body has " + std::to_string(unposed.rows()) + " vertices, the model " +
                        std::to_string(num_vertices()));
    return rest_angles(regress_joints(skeleton(), unposed));
  }
  Eigen::MatrixX3d posed_vertices(const Eigen::MatrixX3d& unposed, const Pose& pose, double fraction) const override {
    check_pose(pose, pose_angles(), "body parametric pose");
    if (unposed.rows() != num_vertices())
      throw ConfigError("body parametric: a body to pose has " + std::to_string(unposed.rows()) + " vertices, the model " +
                        std::to_string(num_vertices()));
    if (!(fraction >= 0 && fraction <= 1)) throw ConfigError("body parametric: a pose fraction must lie in [0, 1]");
    if (pose.empty() || fraction == 0) return unposed;
    return skin(skeleton(), unposed, regress_joints(skeleton(), unposed), pose, fraction);
  }
  std::vector<skinning::Rigid> joint_transforms(const Eigen::MatrixX3d& unposed, const Pose& pose) const override {
    check_pose(pose, pose_angles(), "body parametric pose");
    if (unposed.rows() != num_vertices())
      throw ConfigError("body parametric: a body to pose has " + std::to_string(unposed.rows()) + " vertices, the model " +
                        std::to_string(num_vertices()));
    return bone_transforms(skeleton(), regress_joints(skeleton(), unposed), pose, 1.0);
  }

  int num_vertices() const override { return static_cast<int>(tpl_.vertices.rows()); }
  const Eigen::MatrixX3i& faces() const override { return tpl_.faces; }
  std::vector<std::string> shape_names() const override {
    std::vector<std::string> names;
    for (const auto& s : shape_specs()) names.push_back(s.name);
    return names;
  }
  Eigen::VectorXd mean_shape() const override { return mean_shape_vector(); }
  std::vector<std::pair<double, double>> shape_ranges() const override {
    std::vector<std::pair<double, double>> out;
    for (const auto& s : shape_specs()) out.emplace_back(s.min, s.max);
    return out;
  }

  Eigen::MatrixX3d vertices(const Eigen::VectorXd& shape) const override {
    check_shape(shape);
    BodyMemo& memo = shared_memo(rig_);
    if (auto known = memo.find(shape)) return std::move(*known);
    Eigen::MatrixX3d v = fit_template(tpl_, plan_body(shape, rig_));
    normalise_height(v, shape[kHeight]);
    memo.add(shape, v);
    return v;
  }

  Eigen::VectorXd solve(const BodyRequest& req) const override {
    const ShapeSpec& h = shape_specs()[kHeight];
    std::ostringstream bad;
    bad.precision(10);  // a value just past a bound is not printed as the bound ("sex 1 is outside [0, 1]")
    if (!(req.bmi >= kBmiMin && req.bmi <= kBmiMax))
      bad << "BMI " << req.bmi << " is outside the reachable range [" << kBmiMin << ", " << kBmiMax << "]";
    else if (!(req.height >= h.min && req.height <= h.max))
      bad << "height " << req.height << " m is outside the reachable range [" << h.min << ", " << h.max << "] m";
    else if (!(req.sex >= 0 && req.sex <= 1))
      bad << "sex " << req.sex << " is outside [0, 1]";
    if (!bad.str().empty()) throw ConfigError("body parametric: " + bad.str());

    check_proportions(*this, "parametric", req);
    Eigen::VectorXd shape = mean_shape_vector();
    shape[kHeight] = req.height;
    shape[kSex] = req.sex;
    for (const auto& [name, value] : req.proportions) shape[index_of(name)] = value;
    const ShapeSpec& w = shape_specs()[kWeight];
    auto residual = [&](double weight) {
      shape[kWeight] = weight;
      return bmi(shape) - req.bmi;
    };
    // BMI grows monotonically and smoothly with weight: secant steps from a
    // calibrated guess, kept inside the bracket known so far (bisection otherwise).
    double lo = w.min, hi = w.max;
    double x0 = std::clamp(kWeightPerLogBmi * std::log(req.bmi / kBmiAtZeroWeight), lo, hi), f0 = residual(x0);
    double x1 = x0 + (f0 > 0 ? -0.1 : 0.1), f1 = residual(x1);
    for (double x : {x0, x1}) (x == x0 ? f0 : f1) < 0 ? lo = std::max(lo, x) : hi = std::min(hi, x);
    for (int it = 0; it < 40 && std::abs(f1) > kBmiTolerance && hi - lo > 1e-9; ++it) {
      double x2 = f1 != f0 ? x1 - f1 * (x1 - x0) / (f1 - f0) : 0.5 * (lo + hi);
      if (!(x2 > lo && x2 < hi)) x2 = 0.5 * (lo + hi);
      const double f2 = residual(x2);
      (f2 < 0 ? lo : hi) = x2;
      x0 = x1, f0 = f1, x1 = x2, f1 = f2;
    }
    if (std::abs(f1) > 0.25) {
      std::ostringstream m;
      m << "body parametric: BMI " << req.bmi << " is not reachable at height " << req.height << " m, sex " << req.sex
        << " (weight in [" << w.min << ", " << w.max << "] gives BMI " << residual(w.min) + req.bmi << " to "
        << residual(w.max) + req.bmi << ")";
      throw ConfigError(m.str());
    }
    shape[kWeight] = x1;
    return shape;  // holds the last weight evaluated
  }

  std::pair<double, double> bmi_range() const override { return {kBmiMin, kBmiMax}; }

  // The girths, over the range sampled bodies stay plausible in (docs/bodies.md).
  std::vector<Proportion> proportions() const override {
    std::vector<Proportion> out;
    for (int i = kChest; i < kNumShape; ++i) out.push_back({shape_specs()[static_cast<std::size_t>(i)].name, -kGirthSpread, kGirthSpread});
    return out;
  }

  double bmi(const Eigen::VectorXd& shape) const {
    const Eigen::MatrixX3d v = vertices(shape);
    return geometry::mesh_volume(v, tpl_.faces) * kDensity / (shape[kHeight] * shape[kHeight]);
  }

 private:
  // Built on first use: most bodies are never posed.
  const Skeleton& skeleton() const { return shared_skeleton(rig_); }

  Rig rig_;
  const BodyTemplate& tpl_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "body";
  d.name = "parametric";
  d.doc = "Built-in parametric body: smooth implicit primitives meshed once into a fixed watertight topology "
          "(~6k vertices, A-pose, Y up, feet at y=0, facing +Z); shape = height, sex, weight and six girths; "
          "solve() reaches BMI 10-65.";
  d.params = {{.name = "rig", .type = ParamType::String, .default_value = "mannequin",
               .doc = "mannequin: the rig of every shipped dataset and model; human: a face, sloping shoulders, hands with "
                      "a thumb, feet with heel and toes, buttocks (its own topology; docs/bodies.md)",
               .choices = {"mannequin", "human"}}};
  d.create_body = [](const Params& p) {
    return std::make_unique<ParametricBody>(p.get_string("rig") == "human" ? Rig::Human : Rig::Mannequin);
  };
  return {d};
}

}  // namespace
}  // namespace drape::parametric

DRAPE_PLUGIN_EXPORT(drape::parametric::plugins)
