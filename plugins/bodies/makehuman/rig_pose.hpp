#pragma once
// drape's pose space (human_pose_angles, the parametric body's angles and
// meanings) on MakeHuman's bones. Which bone turns for which angle, about
// which axis, and the rest angles of MakeHuman's own stance are in
// docs/poses.md ("MakeHuman's rig").
#include "rig.hpp"

#include <drape/bodies/pose.hpp>
#include <drape/bodies/skinning.hpp>

namespace drape::makehuman {

// The pose angles that turn `bone` (the Joint::angles of the rig).
std::vector<std::string> angles_of_bone(const std::string& bone);

// The angles of the unposed body whose bone heads are `joints`: measured
// from the joints where MakeHuman's rest stance is not the neutral one
// (shoulder abduction and flexion, elbow flexion, hip abduction and flexion,
// knee flexion), 0 for the rest.
Pose rest_angles(const Rig& rig, const Eigen::MatrixX3d& joints);

// Each bone's transform taking the body whose bone heads are `joints` a
// `fraction` of the way from its rest angles to `pose` (angles the pose
// does not set stay at rest). A pose of the rest angles gives identities.
std::vector<skinning::Rigid> rig_transforms(const Rig& rig, const Eigen::MatrixX3d& joints, const Pose& pose,
                                            double fraction);

}  // namespace drape::makehuman
