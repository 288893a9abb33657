#pragma once
// A posed body as a scene or `drape body` takes it: refused, naming the bones
// and the joint angles, when the pose makes the body pass through itself (an
// arm into the trunk, thighs into each other). The test is independent of
// the posing: triangle-triangle intersection of non-adjacent faces of the
// posed mesh (geometry::self_intersections).
#include <drape/bodies/body.hpp>
#include <drape/training/rng.hpp>

#include <string>

namespace drape {

// "" when the posed mesh has no crossing face pairs beyond those of the
// unposed body; else "left_forearm into spine_upper (4 face pairs at heights
// 1.02-1.08 m; left_elbow_flexion=140, left_shoulder_abduction=10)".
std::string describe_pose_crossings(const BodyModel& model, const Eigen::VectorXd& shape, const Pose& pose,
                                    const Eigen::MatrixX3d& posed);
// The same for a body given by its unposed mesh (any mesh of the model's topology).
std::string describe_pose_crossings(const BodyModel& model, const Eigen::MatrixX3d& unposed, const Pose& pose,
                                    const Eigen::MatrixX3d& posed);

// `pose` with every angle of the model's pose space set: the angles it leaves
// alone at the rest angles of the body whose rest mesh is `unposed`
// (BodyModel::rest_pose_of, no second solve of the shape). What a posed
// dataset stores and a posed graph reads.
Pose full_pose(const BodyModel& model, const Pose& pose, const Eigen::MatrixX3d& unposed);

// Why `model` cannot be posed, when it says more than that it has no
// skeleton: its own refusal of a pose (BodyModel::posed), such as an SMPL
// file without its pose datasets naming the file. "" for a model that keeps
// the default refusal, or is poseable.
std::string unposeable_reason(const BodyModel& model);

// model.posed(shape, pose) after check_pose; ConfigError naming `model_name`
// when the model is not poseable or the posed body passes through itself.
Eigen::MatrixX3d pose_body(const BodyModel& model, const std::string& model_name, const Eigen::VectorXd& shape,
                           const Pose& pose);
// The same for a body given by its unposed mesh (a user's body of the
// model's topology): BodyModel::posed_vertices with the same checks.
Eigen::MatrixX3d pose_vertices(const BodyModel& model, const std::string& model_name, const Eigen::MatrixX3d& unposed,
                               const Pose& pose);

// A pose for the body of `shape` drawn from the model's pose space
// (draw_pose over pose_angles()), by rejection: a pose in which the body
// passes through itself (describe_pose_crossings) is drawn again. After
// `max_draws` rejections (a body no pose of the space leaves clear: a short
// woman near BMI 60, whose arms meet her trunk wherever the space puts them),
// each draw is pulled towards the body's own rest pose, halfway further every
// max_draws / 5 rejections, down to the rest pose itself; Error only when the
// body passes through itself at rest. What drape body --sample --poses (and
// any generator of posed bodies) draws; docs/poses.md gives the rate.
struct DrawnPose {
  Pose pose;
  Eigen::MatrixX3d vertices;  // the posed body
  int redraws = 0;            // poses drawn and rejected before this one
  double pull = 1.0;          // 1: drawn from the space; less: each angle's offset from the rest pose times this
};
// `space`, when given, replaces the model's pose_angles() (the same angles
// with other sampling ranges: with_sampling_ranges).
DrawnPose draw_free_pose(const BodyModel& model, const Eigen::VectorXd& shape, Rng& rng, int max_draws = 50,
                         const std::vector<PoseAngle>* space = nullptr);

}  // namespace drape
