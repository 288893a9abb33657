// The pose options of drape body and drape simulate (pose_options.hpp).
#include "pose_options.hpp"

#include <drape/bodies/pose.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/bodies/smpl_theta.hpp>

#include <filesystem>
#include <system_error>

namespace drape::cli {

std::optional<Pose> pose_options(const po::variables_map& vm, const BodyModel& model, const std::string& model_name) {
  const std::size_t given = vm.count("pose") + vm.count("pose-file") + vm.count("smpl-theta");
  if (given > 1) throw UsageError("--pose, --pose-file and --smpl-theta: give one");
  if (given == 0) return std::nullopt;
  if (!model.poseable()) {
    const std::string reason = unposeable_reason(model);
    if (!reason.empty()) throw ConfigError("body " + model_name + ": " + reason);
    throw ConfigError("body " + model_name + " has no skeleton, so it cannot be posed (--pose, --pose-file, "
                      "--smpl-theta); docs/poses.md says which models can");
  }
  if (vm.count("pose")) {
    // parse_pose reads "" as the rest pose (Python's pose=""), but an empty
    // --pose on a command line is more likely a shell variable that was not
    // set than a request for the A-pose.
    const std::string text = vm["pose"].as<std::string>();
    if (text.find_first_not_of(" \t") == std::string::npos)
      throw UsageError("--pose is empty: give name=degrees,... (docs/poses.md), or leave it out for the rest pose");
    return parse_pose(text, model.pose_angles(), "--pose");
  }
  if (vm.count("pose-file")) {
    const std::string file = vm["pose-file"].as<std::string>();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
      throw ConfigError("--pose-file " + file + ": " + (std::filesystem::exists(file, ec) ? "not a file" : "no such file"));
    return read_pose_file(file, model.pose_angles());
  }
  const std::string file = vm["smpl-theta"].as<std::string>();
  return pose_from_theta(read_theta_file(file), model, "--smpl-theta " + file);
}

}  // namespace drape::cli
