#pragma once
// How far each limb of a body mesh is turned against its parent, compared
// with the body model's mean body: a body given posed where a body at rest is
// expected (drape predict --body, which poses the body it is given) is told
// by its limbs, whatever its build.
#include <drape/bodies/body.hpp>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace drape {

// A limb turned further than this against its parent, compared with the mean
// body, is posed: bodies at rest over the parametric space turn one by at most
// 10 degrees (the thin bodies' thighs; arms 4, the spine 7.5), a pose by its
// angles (an elbow bent 30 degrees: 30.2).
inline constexpr double kPosedLimbDegrees = 15.0;

struct LimbTurn {
  std::string bone;    // a joints() name: "left_forearm" turns at the elbow
  double degrees = 0;  // its rotation against its parent's, relative to the mean body's
};

// One entry per joint of a poseable model that has pose angles and moves
// vertices of its own (skinning weight at least 0.95), in joints() order;
// none for a model without a skeleton. Each bone's rotation is the
// least-squares rotation of the mean body's vertices it moves onto the
// body's (Kabsch), taken against its parent's.
std::vector<LimbTurn> limb_turns(const BodyModel& model, const Eigen::MatrixX3d& mean, const Eigen::MatrixX3d& body);

// The same with what depends only on the model (each bone's own vertices,
// read off the skinning weights) made once: for body after body.
class LimbFit {
 public:
  explicit LimbFit(const BodyModel& model);
  std::vector<LimbTurn> turns(const Eigen::MatrixX3d& mean, const Eigen::MatrixX3d& body) const;
  // Those turned past kPosedLimbDegrees: none for a body at rest.
  std::vector<LimbTurn> posed(const Eigen::MatrixX3d& mean, const Eigen::MatrixX3d& body) const;

 private:
  std::vector<BodyModel::Joint> joints_;
  std::vector<std::vector<int>> own_;  // per joint: the vertices it moves (nearly) alone
};

}  // namespace drape
