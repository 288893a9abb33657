#pragma once
// Poses: joint angles by name, in degrees, over a body model's pose space
// (BodyModel::pose_angles). Angles are anatomical: each is 0 in the neutral
// stance (arms hanging, legs straight, trunk upright) except where the body
// model's rest pose differs (the A-pose's shoulder abduction: rest_pose()).
// An angle a Pose does not hold stays at the rest pose, so the empty Pose is
// the unposed body itself. docs/poses.md lists the angles, their limits and
// where the limits come from.
#include <drape/training/rng.hpp>

#include <map>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace drape {

// One degree of freedom of a pose space. Sided angles are named
// "left_shoulder_abduction", "right_shoulder_abduction"; a pose may name
// both at once without the prefix.
struct PoseAngle {
  std::string name;
  double min = 0, max = 0;            // the range of motion accepted, degrees
  double sample_lo = 0, sample_hi = 0;  // what draw_pose draws from, uniform
  std::string meaning;                // "raises the arm sideways; AAOS 0-180"
  // What a left-right mirror (x -> -x, the body's plane of symmetry) makes
  // of the angle: a sided angle becomes the other side's, an angle that
  // bends or turns towards one side its negative, and one in the sagittal
  // plane (a flexion) stays. unknown: the space does not say (SMPL's raw
  // axes), and nothing mirrors a pose of it.
  enum class Mirror { unknown, same, negated };
  Mirror mirror = Mirror::unknown;
};

struct Pose {
  std::map<std::string, double> angles;  // full (sided) names, degrees
  bool empty() const { return angles.empty(); }
  // The angle, or `rest` when the pose does not set it.
  double get(const std::string& name, double rest) const;
};

// The human pose space of drape's body models: spine (flexion, bend, twist),
// neck (the same), shoulders (abduction, flexion, rotation), elbows (flexion),
// hips (flexion, abduction, rotation) and knees (flexion), left and right;
// limits from the published ranges of motion (docs/poses.md).
std::vector<PoseAngle> human_pose_angles();

// The pose mirrored left for right: each sided angle takes the value of its
// other side's, each lateral one (PoseAngle::Mirror::negated: the trunk's and
// the neck's bend and twist) is negated. A body posed so is the reflection
// of the body in `pose` (for a body symmetric at rest). ConfigError naming
// the angle when the space does not say how one mirrors or lacks its other side.
Pose mirrored_pose(const Pose& pose, const std::vector<PoseAngle>& space);

// "shoulder_abduction=40,left_elbow_flexion=30": comma-separated name=value
// in degrees; a name without left_/right_ sets both sides. ConfigError (one
// line, prefixed by `what`) for an unknown name (with the closest names), a
// value that is not a number, NaN, out of its range (with the range), or an
// angle set twice.
Pose parse_pose(const std::string& text, const std::vector<PoseAngle>& space, const std::string& what);
// A YAML map of the same names to degrees ({shoulder_abduction: 40, ...}).
Pose read_pose_file(const std::string& path, const std::vector<PoseAngle>& space);
// One `name: degrees` entry of a YAML map (a pose file, a scene's `body:
// {pose: ...}`) added to `pose` with the checks of parse_pose, and an angle
// the pose already holds refused; `what` begins the message ("scene.yaml:12").
// `setters` (optional, one map for all the entries of one pose): the name
// that set each angle, so that an angle set twice names both names
// ("by 'elbow_flexion' and by 'left_elbow_flexion'").
void add_pose_entry(Pose& pose, const std::string& name, const YAML::Node& value, const std::vector<PoseAngle>& space,
                    const std::string& what, std::map<std::string, std::string>* setters = nullptr);
// The checks of parse_pose on a pose built in code.
void check_pose(const Pose& pose, const std::vector<PoseAngle>& space, const std::string& what);
// "left_elbow_flexion=30,..." in the order of the map; parse_pose reads it back.
std::string format_pose(const Pose& pose);

// Every angle of the space drawn independently, uniform over its sampling
// range (a fixed number of draws, one per angle in the space's order).
Pose draw_pose(const std::vector<PoseAngle>& space, Rng& rng);

// `space` with the sampling ranges of some angles replaced, from
// "shoulder_abduction=60:90,spine_twist=-45:-30" (degrees; a name without
// left_/right_ sets both sides; one value draws that value). What drape
// generate --pose-range draws from: a narrower training set, or a held-out
// set outside it. ConfigError (prefixed by `what`) for an unknown name (with
// the close names), lo > hi, a bound that is not a number, or a range beyond
// the angle's range of motion.
// ConfigError unless some angle of `space` has a sampling range to draw from:
// a model that ships no pose distribution (SMPL) would otherwise draw its
// rest pose for every body, silently. `model` names it in the message.
void check_drawable(const std::vector<PoseAngle>& space, const std::string& model);
std::vector<PoseAngle> with_sampling_ranges(std::vector<PoseAngle> space, const std::string& text, const std::string& what);
// "shoulder_abduction 25:100, ..." of the angles whose sampling range differs
// from `reference`'s (all of them when reference is empty): for messages and
// a dataset's generator attribute.
std::string sampling_ranges_text(const std::vector<PoseAngle>& space, const std::vector<PoseAngle>& reference = {});

}  // namespace drape
