#pragma once
// Body models: a fixed-topology, watertight mesh in A-pose (meters, Y up) driven
// by a few shape parameters. Plugins of kind "body" provide them.
#include <drape/bodies/pose.hpp>
#include <drape/bodies/skinning.hpp>
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
  std::map<std::string, double> proportions = {};
};

class BodyModel {
 public:
  virtual ~BodyModel() = default;
  virtual int num_vertices() const = 0;
  virtual const Eigen::MatrixX3i& faces() const = 0;
  virtual std::vector<std::string> shape_names() const = 0;
  virtual Eigen::VectorXd mean_shape() const = 0;
  // Each shape parameter's accepted range, in shape_names() order, for a
  // caller that searches the shape space (fit_pose, drape/bodies/pose_fit.hpp);
  // unbounded by default (SMPL's betas).
  virtual std::vector<std::pair<double, double>> shape_ranges() const;
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

  // Posing (docs/poses.md). A poseable model has a skeleton: bones, each
  // turning about its joint, the first the root (parent -1), parents before
  // children.
  struct Joint {
    std::string name;  // the bone that turns about it: "left_forearm" turns at the elbow
    int parent = -1;
    std::vector<std::string> angles;  // the pose angles that turn it there ("left_elbow_flexion")
  };
  virtual bool poseable() const { return false; }
  // The angles posed() takes, with their limits; none by default.
  virtual std::vector<PoseAngle> pose_angles() const { return {}; }
  virtual std::vector<Joint> joints() const { return {}; }
  // Joint centres of the unposed body of `shape`, one row per joints() entry.
  virtual Eigen::MatrixX3d joint_positions(const Eigen::VectorXd& shape) const;
  // Skinning weights: one row per vertex, one column per joint, rows summing to 1.
  virtual Eigen::MatrixXd skinning_weights() const;
  // The angles of the unposed body of `shape` (the A-pose), every angle of
  // pose_angles() set.
  virtual Pose rest_pose(const Eigen::VectorXd& shape) const;
  // The same for a body given by its unposed mesh (any mesh of this model's
  // topology, e.g. a user's body without shape parameters). By default
  // rest_pose of the mean shape (right for a model whose rest angles do not
  // depend on the shape, as SMPL's zeros).
  virtual Pose rest_pose_of(const Eigen::MatrixX3d& unposed) const;
  // The body of `shape` in `pose` (angles it does not set stay at rest).
  // The empty pose gives vertices(shape) bit for bit. Not poseable: ConfigError.
  virtual Eigen::MatrixX3d posed(const Eigen::VectorXd& shape, const Pose& pose) const;
  // The body whose unposed mesh is `unposed` (this model's topology: any
  // shape, or a body on its way from one shape to another) a `fraction` of
  // the way from its own rest angles to `pose`: each angle the pose sets at
  // rest + fraction (angle - rest). Fraction 0 gives `unposed` bit for bit,
  // fraction 1 gives posed(shape, pose) when `unposed` is vertices(shape).
  // The path a simulation's body takes into a pose (Simulation::run).
  virtual Eigen::MatrixX3d posed_vertices(const Eigen::MatrixX3d& unposed, const Pose& pose, double fraction) const;
  // Each joint's rigid transform (one per joints() entry, in its order) that
  // takes the body whose unposed mesh is `unposed` into `pose`: what
  // posed_vertices blends by skinning_weights() (for SMPL, after its pose
  // blend shapes, which these leave out). What poses a garment with the body
  // (drape/bodies/garment_skinning.hpp). Not poseable: ConfigError.
  virtual std::vector<skinning::Rigid> joint_transforms(const Eigen::MatrixX3d& unposed, const Pose& pose) const;
};

// Garment templates (kind "garment"): the rest garment dressed on the mean body,
// its material space (UV in meters) and per-face materials.
class GarmentSource {
 public:
  virtual ~GarmentSource() = default;
  virtual Garment build() const = 0;
};

}  // namespace drape
