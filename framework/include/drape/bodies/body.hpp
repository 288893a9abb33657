#pragma once
// Body models: a fixed-topology, watertight mesh in A-pose (meters, Y up) driven
// by a few shape parameters. Plugins of kind "body" provide them.
#include <drape/energy.hpp>
#include <drape/mesh.hpp>

#include <Eigen/Core>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace drape {

// What a user asks of a body; the model solves its parameters to match.
struct BodyRequest {
  double bmi = 24.0;      // computed from the mesh: volume * 985 kg/m^3 / height^2
  double height = 1.75;   // m
  double sex = 1.0;       // 0 female ... 1 male
  // Proportions held while the model reaches BMI and height, by name (the
  // parametric body's girths: chest, waist, belly, hips, arms, thighs); a
  // model refuses a name not in its proportion_names().
  std::map<std::string, double> proportions;
};

class BodyModel {
 public:
  virtual ~BodyModel() = default;
  virtual int num_vertices() const = 0;
  virtual const Eigen::MatrixX3i& faces() const = 0;
  virtual std::vector<std::string> shape_names() const = 0;
  virtual Eigen::VectorXd mean_shape() const = 0;
  virtual Eigen::MatrixX3d vertices(const Eigen::VectorXd& shape) const = 0;
  // Shape parameters that reach the request; throws ConfigError (naming the
  // reachable range) when the model cannot reach it.
  virtual Eigen::VectorXd solve(const BodyRequest& request) const = 0;
  // The BMI range this model reaches without breaking its mesh.
  virtual std::pair<double, double> bmi_range() const = 0;
  // Shape parameters a BodyRequest may hold (proportions) and the range over
  // which the model stays a plausible, watertight body at every BMI; none by
  // default.
  struct Proportion {
    std::string name;
    double min = 0, max = 0;
  };
  virtual std::vector<Proportion> proportions() const { return {}; }
  // The request whose solve() gives (about) the mean shape: its BMI, height
  // and sex. A garment cut for a larger body is dressed on this request with
  // another BMI (fit_body, drape/bodies/fit_body.hpp). By default the BMI and
  // height are measured on the mean body's mesh and the sex is 0.5.
  virtual BodyRequest mean_request() const;
};

// Garment templates (kind "garment"): the rest garment dressed on the mean body,
// its material space (UV in meters) and per-face materials.
class GarmentSource {
 public:
  virtual ~GarmentSource() = default;
  virtual Garment build() const = 0;
};

}  // namespace drape
