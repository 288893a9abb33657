#pragma once
// The parametric body's skeleton: twelve bones (pelvis, two spine segments,
// neck with head, upper arms, forearms, thighs, shins), joint centres
// regressed from the body's own mesh, and skinning weights on its fixed
// topology. Both are computed once per topology, from the template (the mean
// body), and hold for every shape: a joint is a fixed linear combination of
// vertices (as SMPL's J_regressor), so it follows sex, height, BMI and girths
// wherever the template's vertices go (docs/poses.md).
#include "body_template.hpp"

#include <drape/bodies/body.hpp>

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace drape::parametric {

enum Bone {
  kPelvis = 0, kSpineLower, kSpineUpper, kNeck,
  kLeftUpperArm, kLeftForearm, kRightUpperArm, kRightForearm,
  kLeftThigh, kLeftShin, kRightThigh, kRightShin, kNumBones
};

struct Skeleton {
  std::vector<BodyModel::Joint> joints;  // one per Bone
  // Joint b = sum of weight * vertex over regressor[b] (weights sum to 1).
  std::vector<std::vector<std::pair<int, double>>> regressor;
  Eigen::MatrixXd weights;  // vertices x bones, rows sum to 1
};

// Diffusion steps that smooth the skinning weights (each: half the vertex's
// own weights, half its neighbours' mean): the width of the blend at a joint.
constexpr int kSkinningSmoothing = 16;

Skeleton build_skeleton(const BodyTemplate& tpl);

// Joint centres of a body with the template's topology.
Eigen::MatrixX3d regress_joints(const Skeleton& skeleton, const Eigen::MatrixX3d& vertices);

}  // namespace drape::parametric
