#pragma once
// Linear blend skinning of the parametric body: joint angles -> one rigid
// transform per bone (composed down the skeleton, each joint turning about
// its own centre in the rest frame) -> every vertex moved by its bones'
// transforms blended by its skinning weights.
#include "skeleton.hpp"

#include <drape/bodies/pose.hpp>

namespace drape::parametric {

// The angles of the unposed body whose joints are `joints`: 0 except the
// shoulders' abduction, the A-pose arm's angle from hanging straight down,
// measured in the frontal plane from shoulder to elbow.
Pose rest_angles(const Eigen::MatrixX3d& joints);

// The body `vertices` (unposed, joints `joints`) in `pose`. A bone whose
// transform is the identity adds exactly nothing, so the empty pose gives
// `vertices` back bit for bit.
Eigen::MatrixX3d skin(const Skeleton& skeleton, const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d& joints,
                      const Pose& pose);

}  // namespace drape::parametric
