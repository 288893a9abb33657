#pragma once
// --pose name=degrees,..., --pose-file FILE and --smpl-theta FILE, read the
// same way by every command that poses a body (body, simulate).
#include "command.hpp"

#include <drape/bodies/body.hpp>

#include <optional>
#include <string>

namespace drape::cli {

// The pose the options give (at most one of them), checked against `model`'s
// pose space; nullopt when none is given. ConfigError naming the model, with
// its own reason when it has one (an SMPL file without pose datasets), when
// it cannot be posed.
std::optional<Pose> pose_options(const po::variables_map& vm, const BodyModel& model, const std::string& model_name);

}  // namespace drape::cli
