#pragma once
// SMPL's pose parameters θ as SMPL's users hold them -- one axis-angle
// vector per joint in radians, the root (global orientation) first, 72
// numbers for SMPL's 24 joints -- turned into a drape Pose of a body model
// whose joints take axis-angle angles (<joint>_x, _y, _z in degrees, the
// SMPL plugin's; docs/smpl.md). The root's rotation is not a pose angle:
// drape's bodies stand upright under gravity -Y, so a θ that turns the root
// is refused.
#include <drape/bodies/body.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace drape {

// The numbers of a θ file: text (numbers separated by whitespace or commas;
// '#' starts a comment) or a NumPy .npy array of float64 or float32 in C
// order, of any shape. ConfigError naming the file for anything else, or a
// number that is NaN or infinite.
std::vector<double> read_theta_file(const std::filesystem::path& file);

// θ (radians) to a Pose of `model`: 3K numbers (every joint, the root first)
// or 3(K - 1) (without the root), K = model.joints().size(). An axis-angle
// vector longer than pi is wrapped to the same rotation's vector of length at
// most pi, so every rotation fits the angles' +-180 degrees. ConfigError,
// prefixed by `what`, for another count, a non-finite number, a root that
// turns, or a model whose joints do not take axis-angle vectors.
Pose pose_from_theta(const std::vector<double>& theta, const BodyModel& model, const std::string& what);

}  // namespace drape
