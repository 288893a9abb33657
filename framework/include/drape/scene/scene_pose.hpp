#pragma once
// A scene's target pose (`body: {pose: {shoulder_abduction: 20}}`, degrees,
// docs/poses.md) read against the body model's pose space, and the path the
// body takes into it while its shape morphs (the solver's `pose_path`).
#include <drape/bodies/body.hpp>
#include <drape/scene/scene.hpp>

#include <string>

namespace drape {

// The scene's pose; empty for an A-pose scene. ConfigError at the entry's
// file and line for a body model without a skeleton, an unknown angle (with
// the close names), a value that is not a number of degrees or lies outside
// the angle's range of motion, and an angle set twice (`elbow_flexion` sets
// both sides, so with `left_elbow_flexion` beside it one side is set twice).
Pose scene_pose(const Scene& scene, const BodyModel& model);

// How far the shape morph and the joint angles have gone at morph time t in
// [0, 1]. together: both by t (every step moves the body a little of each);
// pose_first: the joints turn on the start shape in the first half, then the
// shape morphs; shape_first: the other way round. docs/poses.md compares them.
enum class PosePath { together, pose_first, shape_first };
PosePath pose_path_named(const std::string& name);
struct MorphFractions {
  double shape = 0, pose = 0;
};
MorphFractions morph_fractions(PosePath path, double t);

}  // namespace drape
