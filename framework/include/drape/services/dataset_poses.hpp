#pragma once
// A model of A-pose drapes kept off a dataset's posed bodies: render --data,
// eval and the benches fed a posed held-out set to the shipped A-pose model
// without a word, and drew a shredded shirt (ME 16 cm, 599 % strain) as
// that model's prediction. A model that reads no pose but was trained on
// posed drapes (the world-space ablation of docs/poses.md) is measured on
// them as asked: that is the ablation's row.
#include <drape/io/dataset.hpp>
#include <drape/training/model.hpp>

#include <optional>
#include <string>
#include <vector>

namespace drape {

// An angle this far from its body's rest angle makes a posed body (degrees):
// well above a float's rounding of the stored angles, well below any pose a
// pose space draws.
inline constexpr double kPosedAngle = 0.5;

// "sample 3's body is posed (shoulder_abduction_left 62.0 degrees, its rest
// 45.0)" for the first of `indices` whose body is posed, by the stored
// angles against `body_model`'s rest angles of the sample's shape; nullopt
// when every one stands at rest or the dataset stores no pose.
std::optional<std::string> first_posed_sample(const DatasetReader& data, const std::vector<std::size_t>& indices,
                                              const BodyModel& body_model);

// A model that drapes the A-pose only: its graph takes no pose and its
// domain records no training poses.
bool drapes_a_pose_only(const Model& model);

// ConfigError, naming the sample, the model and what to give instead, when
// the model drapes the A-pose only and one of `indices` is posed.
void check_model_takes_dataset_poses(const Model& model, const DatasetReader& data, const std::vector<std::size_t>& indices);

}  // namespace drape
