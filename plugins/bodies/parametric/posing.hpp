#pragma once
// Posing the parametric body: its joint angles -> one rotation per bone in
// the rest frame; the framework's linear blend skinning
// (drape/bodies/skinning.hpp) composes them down the skeleton, each joint
// turning about its own centre, and moves every vertex by its bones'
// transforms blended by its skinning weights.
#include "skeleton.hpp"

#include <drape/bodies/pose.hpp>
#include <drape/bodies/skinning.hpp>

namespace drape::parametric {

// The angles of the unposed body whose joints are `joints`: 0 except the
// shoulders' abduction, the A-pose arm's angle from hanging straight down,
// measured in the frontal plane from shoulder to elbow.
Pose rest_angles(const Eigen::MatrixX3d& joints);

// The body `vertices` (unposed, joints `joints`) in `pose`. A bone whose
// transform is the identity adds exactly nothing, so the empty pose gives
// `vertices` back bit for bit.
// With `fraction` < 1, each angle the pose sets goes that fraction of the
// way from the body's own rest angle (BodyModel::posed_vertices).
Eigen::MatrixX3d skin(const Skeleton& skeleton, const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d& joints,
                      const Pose& pose, double fraction = 1.0);
// The bones' transforms skin() blends (BodyModel::joint_transforms).
std::vector<skinning::Rigid> bone_transforms(const Skeleton& skeleton, const Eigen::MatrixX3d& joints, const Pose& pose,
                                             double fraction = 1.0);

}  // namespace drape::parametric
