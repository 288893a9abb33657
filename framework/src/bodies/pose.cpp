// Poses by name (pose.hpp) and the default, unposeable BodyModel.
#include <drape/bodies/body.hpp>
#include <drape/bodies/pose.hpp>
#include <drape/errors.hpp>

#include "../yaml_util.hpp"
#include "no_skeleton.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>
#include <map>
#include <cstdlib>
#include <set>
#include <sstream>
#include <utility>

namespace drape {
namespace {

constexpr const char* kSides[] = {"left_", "right_"};

std::string range_text(const PoseAngle& a) {
  std::ostringstream s;
  s << "[" << a.min << ", " << a.max << "] degrees";
  return s.str();
}

// The sided names an entry sets: itself, or both sides of an unsided name.
std::vector<const PoseAngle*> targets(const std::string& name, const std::vector<PoseAngle>& space) {
  std::vector<const PoseAngle*> out;
  for (const PoseAngle& a : space)
    if (a.name == name) return {&a};
  for (const char* side : kSides)
    for (const PoseAngle& a : space)
      if (a.name == side + name) out.push_back(&a);
  return out;
}

std::vector<std::string> accepted_names(const std::vector<PoseAngle>& space) {
  std::set<std::string> names;
  for (const PoseAngle& a : space) {
    names.insert(a.name);
    for (const char* side : kSides)
      if (a.name.rfind(side, 0) == 0) names.insert(a.name.substr(std::string(side).size()));
  }
  return {names.begin(), names.end()};
}

void check_value(const PoseAngle& a, double degrees, const std::string& what) {
  if (degrees >= a.min && degrees <= a.max) return;  // (before any stream: a pose is checked per angle per body)
  std::ostringstream m;
  m.precision(10);  // a value just past a bound is not printed as the bound ("= 180 is outside [0, 180]")
  if (std::isnan(degrees))
    m << what << ": " << a.name << " is NaN; expected a number in " << range_text(a);
  else
    m << what << ": " << a.name << " = " << degrees << " is outside its range of motion " << range_text(a) << " ("
      << a.meaning << ")";
  throw ConfigError(m.str());
}

// targets(), or a ConfigError naming the close matches (or every angle)
// when `name` is no angle of the space.
std::vector<const PoseAngle*> known_targets(const std::string& name, const std::vector<PoseAngle>& space,
                                            const std::string& what) {
  auto set = targets(name, space);
  if (!set.empty()) return set;
  std::string msg = what + ": no joint angle '" + name + "'" + did_you_mean(name, accepted_names(space));
  if (msg.find("did you mean") == std::string::npos) {
    msg += "; the angles are";
    for (const std::string& n : accepted_names(space)) msg += " " + n;
    msg += " (left_/right_ prefix for one side)";
  }
  throw ConfigError(msg);
}

// Sets `name` (sided or both sides) to `degrees`, checking all of it.
// `setters` (optional): the name that set each angle so far, to say which
// two names set one angle twice (elbow_flexion and left_elbow_flexion).
void set_angle(Pose& pose, const std::string& name, double degrees, const std::vector<PoseAngle>& space,
               const std::string& what, std::map<std::string, std::string>* setters = nullptr) {
  for (const PoseAngle* a : known_targets(name, space, what)) {
    check_value(*a, degrees, what);
    if (!pose.angles.emplace(a->name, degrees).second) {
      const auto before = setters ? setters->find(a->name) : std::map<std::string, std::string>::iterator{};
      if (setters && before != setters->end())
        throw ConfigError(what + ": " + a->name + " is set twice (by '" + before->second + "' and by '" + name + "')");
      throw ConfigError(what + ": " + a->name + " is set twice (by '" + name + "' and before)");
    }
    if (setters) (*setters)[a->name] = name;
  }
}

double parse_degrees(const std::string& name, const std::string& text, const std::string& what,
                     const std::vector<PoseAngle>& space) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  // (strtod also reads C's hexadecimal numbers: 0x10 would be 16 degrees.)
  if (text.empty() || end == begin || *end != '\0' || text.find_first_of("xX") != std::string::npos)
    throw ConfigError(what + ": " + name + " = '" + text + "' is not a number of degrees");
  // (strtod reads 1e400 as infinity: said as written, not as "inf".)
  if (std::isinf(v) && text.find_first_of("iI") == std::string::npos) {
    // The range the angle takes, as a value just outside it is told (an unknown name: its own refusal first).
    throw ConfigError(what + ": " + name + " = " + text + " is beyond any angle; expected a number in " +
                      range_text(*known_targets(name, space, what).front()));
  }
  return v;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

}  // namespace

double Pose::get(const std::string& name, double rest) const {
  const auto it = angles.find(name);
  return it == angles.end() ? rest : it->second;
}

Pose mirrored_pose(const Pose& pose, const std::vector<PoseAngle>& space) {
  const auto find = [&](const std::string& name) -> const PoseAngle* {
    for (const PoseAngle& a : space)
      if (a.name == name) return &a;
    return nullptr;
  };
  const auto other_side = [](const std::string& name) -> std::string {
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"left_", "right_"}, {"right_", "left_"}})
      if (name.rfind(from, 0) == 0) return to + name.substr(from.size());
    return name;
  };
  Pose out;
  for (const auto& [name, degrees] : pose.angles) {
    const PoseAngle* angle = find(name);
    if (!angle) throw ConfigError("mirroring a pose: '" + name + "' is not an angle of the body model's pose space");
    if (angle->mirror == PoseAngle::Mirror::unknown)
      throw ConfigError("mirroring a pose: the body model's pose space does not say how '" + name +
                        "' mirrors left for right (only drape's human pose space does)");
    const std::string to = other_side(name);
    if (!find(to)) throw ConfigError("mirroring a pose: '" + name + "' has no other side '" + to + "' in the pose space");
    out.angles[to] = angle->mirror == PoseAngle::Mirror::negated ? -degrees : degrees;
  }
  return out;
}

Pose parse_pose(const std::string& text, const std::vector<PoseAngle>& space, const std::string& what) {
  Pose pose;
  std::map<std::string, std::string> setters;
  // Empty text is the rest pose (Python's pose=""; the command line refuses
  // it first). An empty item among others is refused: `--pose "$A,$B"` with
  // neither set was the rest pose without a word. One comma after the last
  // item is allowed (a list joined in a loop writes one).
  if (trim(text).empty()) return pose;
  std::string items = trim(text);
  if (items.size() > 1 && items.back() == ',') items.pop_back();
  for (std::size_t start = 0;;) {
    const std::size_t comma = items.find(',', start);
    std::string item = trim(items.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.empty())
      throw ConfigError(what + ": an empty item between commas in '" + text +
                        "' (a shell variable never set?): expected name=degrees,... (docs/poses.md)");
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw ConfigError(what + ": expected name=degrees, got '" + item + "'");
    const std::string name = trim(item.substr(0, eq));
    set_angle(pose, name, parse_degrees(name, trim(item.substr(eq + 1)), what, space), space, what, &setters);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return pose;
}

Pose read_pose_file(const std::string& path, const std::vector<PoseAngle>& space) {
  // The project's loader: malformed YAML at its line, and an angle written
  // twice refused (yaml-cpp alone keeps one of them silently).
  const YAML::Node root = yaml::load_file(path);
  if (!root.IsMap()) throw ConfigError("pose file " + path + ": expected a map of joint angle names to degrees");
  Pose pose;
  std::map<std::string, std::string> setters;
  for (const auto& kv : root) {
    const std::string name = kv.first.as<std::string>();
    add_pose_entry(pose, name, kv.second, space, "pose file " + yaml::at(path, kv.first).str(), &setters);
  }
  return pose;
}

void add_pose_entry(Pose& pose, const std::string& name, const YAML::Node& value, const std::vector<PoseAngle>& space,
                    const std::string& what, std::map<std::string, std::string>* setters) {
  if (!value.IsScalar()) {
    // A key that is no angle (a map nested under `pose:`) is named as such first.
    known_targets(name, space, what);
    throw ConfigError(what + ": " + name + " wants one number of degrees");
  }
  // YAML's own spellings of NaN and infinity, read as YAML means them (`.inf`
  // was "not a number of degrees" where `.nan` was "is NaN").
  std::string text = value.Scalar();
  for (const auto& [yaml_word, c_word] : {std::pair<const char*, const char*>{".nan", "nan"}, {".NaN", "nan"}, {".NAN", "nan"},
                                          {".inf", "inf"}, {".Inf", "inf"}, {".INF", "inf"}, {"+.inf", "inf"},
                                          {"-.inf", "-inf"}, {"-.Inf", "-inf"}, {"-.INF", "-inf"}})
    if (text == yaml_word) text = c_word;
  set_angle(pose, name, parse_degrees(name, text, what, space), space, what, setters);
}

void check_pose(const Pose& pose, const std::vector<PoseAngle>& space, const std::string& what) {
  for (const auto& [name, degrees] : pose.angles) {
    const PoseAngle* found = nullptr;
    for (const PoseAngle& a : space)
      if (a.name == name) found = &a;
    if (!found) throw ConfigError(what + ": no joint angle '" + name + "'" + did_you_mean(name, accepted_names(space)));
    check_value(*found, degrees, what);
  }
}

std::string format_pose(const Pose& pose) {
  std::ostringstream s;
  s.precision(10);
  for (const auto& [name, degrees] : pose.angles) s << (s.tellp() > 0 ? "," : "") << name << "=" << degrees + 0.0;  // (+ 0: no "-0")
  return s.str();
}

void check_drawable(const std::vector<PoseAngle>& space, const std::string& model) {
  for (const PoseAngle& a : space)
    if (a.sample_hi > a.sample_lo) return;
  throw ConfigError("body model '" + model +
                    "' has no pose distribution to draw from (no angle has a sampling range): drape generate takes "
                    "one as --pose-range name=lo:hi,... (degrees); drape body poses one body at a time with --pose");
}

Pose draw_pose(const std::vector<PoseAngle>& space, Rng& rng) {
  Pose pose;
  for (const PoseAngle& a : space) pose.angles[a.name] = a.sample_lo + (a.sample_hi - a.sample_lo) * rng.uniform();
  return pose;
}

std::vector<PoseAngle> human_pose_angles() {
  // Limits: the American Academy of Orthopaedic Surgeons' average ranges of
  // motion (AAOS, "Joint Motion: Method of Measuring and Recording", 1965), as
  // tabulated by Norkin & White, "Measurement of Joint Motion: A Guide to
  // Goniometry" (5th ed., 2016), appendix. Sampling ranges: a person standing
  // in a T-shirt, not the extremes, and within what the parametric body's
  // linear blend skinning keeps free of self-intersection over the whole body
  // space (scripts/pose_limits.py: elbows to 73, knees to 68, hips to 52
  // degrees of flexion, arms down to 18 degrees of abduction at worst), so
  // that few draws are rejected and poses stay about independent of shape
  // (docs/poses.md). The hips' are narrower still: a thigh both raised and
  // turned out presses into a heavy belly (BMI 55: flexion 30 with abduction
  // 15), and a T-shirt ends above the thighs.
  struct Row {
    const char* name;
    bool sided;    // left_ and right_; a mirror swaps them
    bool lateral;  // bends or turns towards one side: a mirror negates it
    double min, max, lo, hi;
    const char* meaning;
  };
  static const Row rows[] = {
      {"spine_flexion", false, false, -25, 80, -10, 20, "bends the trunk forward (negative: backward); AAOS thoracolumbar flexion 80, extension 25"},
      {"spine_bend", false, true, -35, 35, -15, 15, "bends the trunk towards the body's left (negative: right); AAOS lateral flexion 35"},
      {"spine_twist", false, true, -45, 45, -30, 30, "turns the shoulders to the body's left (negative: right); AAOS rotation 45"},
      {"neck_flexion", false, false, -45, 45, -20, 30, "bends the head forward (negative: backward); AAOS cervical flexion 45, extension 45"},
      {"neck_bend", false, true, -45, 45, -20, 20, "tilts the head towards the body's left; AAOS cervical lateral flexion 45"},
      {"neck_twist", false, true, -60, 60, -45, 45, "turns the head to the body's left; AAOS cervical rotation 60"},
      {"shoulder_abduction", true, false, 0, 180, 25, 100, "raises the arm sideways from hanging (0) to overhead (180); AAOS abduction 180"},
      {"shoulder_flexion", true, false, -60, 180, -20, 60, "raises the arm forward (negative: backward); AAOS flexion 180, extension 60"},
      {"shoulder_rotation", true, false, -90, 70, -30, 30, "turns the arm about its axis inwards (negative: outwards); AAOS medial 70, lateral 90"},
      {"elbow_flexion", true, false, 0, 150, 0, 70, "bends the forearm forward from straight (0); AAOS flexion 150"},
      {"hip_flexion", true, false, -30, 120, -5, 25, "raises the thigh forward (negative: backward); AAOS flexion 120, extension 30"},
      {"hip_abduction", true, false, -30, 45, 0, 10, "moves the thigh sideways out (negative: across); AAOS abduction 45, adduction 30"},
      {"hip_rotation", true, false, -45, 45, -10, 10, "turns the thigh inwards (negative: outwards); AAOS medial 45, lateral 45"},
      {"knee_flexion", true, false, 0, 135, 0, 60, "bends the shin backward from straight (0); AAOS flexion 135"},
  };
  std::vector<PoseAngle> out;
  for (const Row& r : rows) {
    if (!r.sided) {
      out.push_back({r.name, r.min, r.max, r.lo, r.hi, r.meaning,
                     r.lateral ? PoseAngle::Mirror::negated : PoseAngle::Mirror::same});
      continue;
    }
    for (const char* side : kSides)
      out.push_back({std::string(side) + r.name, r.min, r.max, r.lo, r.hi, r.meaning, PoseAngle::Mirror::same});
  }
  return out;
}

Eigen::MatrixX3d BodyModel::joint_positions(const Eigen::VectorXd&) const {
  throw ConfigError("this body model has no skeleton (it makes unposed bodies only; docs/poses.md)");
}
Eigen::MatrixXd BodyModel::skinning_weights() const {
  throw ConfigError("this body model has no skeleton (it makes unposed bodies only; docs/poses.md)");
}
Pose BodyModel::rest_pose(const Eigen::VectorXd&) const { return {}; }
std::vector<std::pair<double, double>> BodyModel::shape_ranges() const {
  const double inf = std::numeric_limits<double>::infinity();
  return std::vector<std::pair<double, double>>(shape_names().size(), {-inf, inf});
}
Pose BodyModel::rest_pose_of(const Eigen::MatrixX3d&) const { return rest_pose(mean_shape()); }
// The shape's body posed all the way: one definition for every model whose
// pose does not depend on the shape beyond its mesh (posed_vertices refuses
// for a model without a skeleton).
Eigen::MatrixX3d BodyModel::posed(const Eigen::VectorXd& shape, const Pose& pose) const {
  if (pose.empty()) return vertices(shape);
  return posed_vertices(vertices(shape), pose, 1.0);
}
Eigen::MatrixX3d BodyModel::posed_vertices(const Eigen::MatrixX3d& unposed, const Pose& pose, double) const {
  if (pose.empty()) return unposed;
  throw ConfigError(kNoSkeletonRefusal);
}
std::vector<skinning::Rigid> BodyModel::joint_transforms(const Eigen::MatrixX3d&, const Pose&) const {
  throw ConfigError(kNoSkeletonRefusal);
}

std::vector<PoseAngle> with_sampling_ranges(std::vector<PoseAngle> space, const std::string& text, const std::string& what) {
  std::stringstream items(text);
  std::string item;
  std::set<std::string> seen;
  while (std::getline(items, item, ',')) {
    item = trim(item);
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw ConfigError(what + ": expected name=lo:hi, got '" + item + "'");
    const std::string name = trim(item.substr(0, eq));
    const std::string range = trim(item.substr(eq + 1));
    const auto colon = range.find(':');
    const double lo = parse_degrees(name, trim(range.substr(0, colon)), what, space);
    const double hi = colon == std::string::npos ? lo : parse_degrees(name, trim(range.substr(colon + 1)), what, space);
    std::vector<PoseAngle*> set;
    for (const PoseAngle* a : known_targets(name, space, what))
      for (PoseAngle& b : space)
        if (&b == a) set.push_back(&b);
    for (PoseAngle* a : set) {
      check_value(*a, lo, what);  // first: a NaN bound is named as NaN, not as lo > hi
      check_value(*a, hi, what);
      if (!(lo <= hi)) throw ConfigError(what + ": " + a->name + " range " + range + ": expected lo <= hi");
      if (!seen.insert(a->name).second) throw ConfigError(what + ": " + a->name + " is given twice");
      a->sample_lo = lo;
      a->sample_hi = hi;
    }
  }
  return space;
}

std::string sampling_ranges_text(const std::vector<PoseAngle>& space, const std::vector<PoseAngle>& reference) {
  std::ostringstream s;
  s.precision(6);
  for (const PoseAngle& a : space) {
    bool same = false;
    for (const PoseAngle& r : reference)
      if (r.name == a.name) same = r.sample_lo == a.sample_lo && r.sample_hi == a.sample_hi;
    if (same) continue;
    s << (s.tellp() > 0 ? ", " : "") << a.name << " " << a.sample_lo << ":" << a.sample_hi;
  }
  return s.str();
}

}  // namespace drape
