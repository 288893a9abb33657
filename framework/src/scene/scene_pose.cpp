// A scene's pose and the path into it (scene_pose.hpp).
#include <drape/bodies/posed_body.hpp>
#include <drape/errors.hpp>
#include <drape/scene/scene_pose.hpp>

#include <algorithm>

namespace drape {

Pose scene_pose(const Scene& scene, const BodyModel& model) {
  Pose pose;
  if (scene.pose.empty()) return pose;
  if (!model.poseable()) {
    const std::string reason = unposeable_reason(model);  // an SMPL file without its pose datasets says so
    // Both places named: the pose may come from a base scene and the model
    // from the user's (it pointed at the installed base's pose alone).
    const std::string model_set_at =
        scene.body_model_where.line > 0 ? " (set at " + scene.body_model_where.str() + ")" : "";
    throw ConfigError(scene.pose.begin()->second.where,
                      "body `pose`: body model '" + scene.body_model + "'" + model_set_at + " " +
                          (reason.empty() ? "has no skeleton, so it cannot be posed (docs/poses.md says which models can)"
                                          : "cannot be posed: " + reason));
  }
  const std::vector<PoseAngle> space = model.pose_angles();
  std::map<std::string, std::string> setters;
  for (const auto& [name, value] : scene.pose)
    add_pose_entry(pose, name, value.node, space, value.where.str() + ": body `pose`", &setters);
  return pose;
}

PosePath pose_path_named(const std::string& name) {
  if (name == "together") return PosePath::together;
  if (name == "pose_first") return PosePath::pose_first;
  if (name == "shape_first") return PosePath::shape_first;
  throw ConfigError("solver pose_path: '" + name + "' is not one of together, pose_first, shape_first");
}

MorphFractions morph_fractions(PosePath path, double t) {
  const double first = std::clamp(2 * t, 0.0, 1.0), second = std::clamp(2 * t - 1, 0.0, 1.0);
  switch (path) {
    case PosePath::pose_first: return {second, first};
    case PosePath::shape_first: return {first, second};
    case PosePath::together: break;
  }
  return {t, t};
}

}  // namespace drape
