// first_posed_sample, check_model_takes_dataset_poses (dataset_poses.hpp).
#include <drape/services/dataset_poses.hpp>

#include <drape/bodies/body.hpp>
#include <drape/errors.hpp>
#include <drape/services/model_body.hpp>
#include <drape/training/model_domain.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace drape {

std::optional<std::string> first_posed_sample(const DatasetReader& data, const std::vector<std::size_t>& indices,
                                              const BodyModel& body_model) {
  const std::vector<std::string>& names = data.layout().pose_angles;
  if (names.empty() || indices.empty()) return std::nullopt;
  const Tensor angles = data.poses(indices);
  const Tensor shapes = data.body_params(indices);
  for (int k = 0; k < angles.batch(); ++k) {
    const Pose rest = body_model.rest_pose(shapes.mat(k).row(0).transpose().cast<double>());
    for (std::size_t a = 0; a < names.size(); ++a) {
      const double angle = static_cast<double>(angles(k, 0, static_cast<int>(a)));
      const double at_rest = rest.get(names[a], angle);
      if (!(std::abs(angle - at_rest) <= kPosedAngle)) {
        char what[256];
        std::snprintf(what, sizeof what, "sample %zu's body is posed (%s %.1f degrees, its rest %.1f)",
                      indices[static_cast<std::size_t>(k)], names[a].c_str(), angle, at_rest);
        return std::string(what);
      }
    }
  }
  return std::nullopt;
}

bool drapes_a_pose_only(const Model& model) {
  if (model_takes_pose(model)) return false;
  if (model.file().empty() || !std::filesystem::exists(model.file())) return true;
  const std::optional<ModelDomain> domain = read_domain(model.file());
  return !domain || domain->pose.empty();
}

void check_model_takes_dataset_poses(const Model& model, const DatasetReader& data, const std::vector<std::size_t>& indices) {
  if (data.layout().pose_angles.empty() || !drapes_a_pose_only(model)) return;
  const std::optional<std::string> posed = first_posed_sample(data, indices, model.body_model());
  if (!posed) return;
  throw ConfigError(data.name() + ": " + *posed + ", and " + model.file().filename().string() +
                    " drapes the A-pose only (trained on A-pose bodies; its graph takes no pose), so its drapes of "
                    "these bodies would be wrong: give a model of posed drapes (--model "
                    "models/tshirt-coarse-posed-human.h5 on the human rig; docs/poses.md)");
}

}  // namespace drape
