// drape's joint angles on MakeHuman's bones (rig_pose.hpp). Axes as
// everywhere in drape: x to the body's left, y up, z forward. Each bone's
// rotation is written in the rest frame and turns about its head, after its
// parent's (drape/bodies/skinning.hpp).
#include "rig_pose.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace drape::makehuman {
namespace {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

// The trunk bends over three spine bones and the neck over three neck
// bones, a third of each angle at each, so that both curve.
const char* const kSpine[] = {"spine03", "spine02", "spine01"};
const char* const kNeck[] = {"neck01", "neck02", "neck03"};

double degrees(double radians) { return radians * 180.0 / M_PI; }
M3 turn(double deg, const V3& axis) {
  if (deg == 0) return M3::Identity();
  return Eigen::AngleAxisd(deg * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

// Flexion forward about x, bend to the left about z, twist to the left about
// y: the parametric body's convention (plugins/bodies/parametric/posing.cpp).
M3 trunk_rotation(double flexion, double bend, double twist) {
  return turn(-bend, V3::UnitZ()) * turn(flexion, V3::UnitX()) * turn(twist, V3::UnitY());
}

// A limb's direction from hanging straight down as abduction (in the frontal
// plane, away from the body; `side` +1 left, -1 right) then flexion
// (forward, about x): F(-flexion) A(side abduction) takes -y to it.
M3 limb_frame(double side, double abduction, double flexion) {
  return turn(-flexion, V3::UnitX()) * turn(side * abduction, V3::UnitZ());
}
struct Direction {
  double abduction, flexion;
};
// The inverse of limb_frame for a direction `d` (from the upper joint to the lower one).
Direction direction_angles(double side, const V3& d) {
  const V3 u = d.normalized();
  return {degrees(std::asin(std::clamp(side * u.x(), -1.0, 1.0))), degrees(std::atan2(u.z(), -u.y()))};
}
// From the rest direction to the pose's, exactly the identity when they agree.
M3 swing(double side, Direction rest, Direction to) {
  if (rest.abduction == to.abduction && rest.flexion == to.flexion) return M3::Identity();
  return limb_frame(side, to.abduction, to.flexion) * limb_frame(side, rest.abduction, rest.flexion).transpose();
}

V3 at(const Rig& rig, const Eigen::MatrixX3d& joints, const std::string& bone) {
  return joints.row(rig.index(bone)).transpose();
}

// MakeHuman's bone name suffix, drape's angle prefix, and the side's sign (+1 left, x > 0).
struct Side {
  const char* suffix;
  const char* prefix;
  double sign;
};
constexpr Side kSides[] = {{".L", "left_", 1.0}, {".R", "right_", -1.0}};

struct Limb {
  std::string upper, lower, end;  // bones: the ball joint's, the hinge's, the one after it
};
Limb arm(const std::string& s) { return {"upperarm01" + s, "lowerarm01" + s, "wrist" + s}; }
Limb leg(const std::string& s) { return {"upperleg01" + s, "lowerleg01" + s, "foot" + s}; }

// The elbow's hinge: across the plane of the rest upper arm and forearm
// (MakeHuman's elbows rest bent by 39-47 degrees), so that flexion
// moves the forearm in the plane it is bent in; across the arm in the
// frontal plane, as the parametric body's, if the arm were straight.
V3 elbow_hinge(const V3& upper, const V3& fore) {
  const V3 n = upper.normalized().cross(fore.normalized());
  return n.norm() > 0.03 ? V3(n.normalized()) : V3(upper.normalized().cross(V3::UnitZ()).normalized());
}
double angle_between(const V3& a, const V3& b) { return degrees(std::atan2(a.cross(b).norm(), a.dot(b))); }
// The knee's flexion in the sagittal plane: the shin's backward turn from the thigh's line.
double knee_flexion(const V3& thigh, const V3& shin) {
  return degrees(std::atan2(thigh.z(), -thigh.y()) - std::atan2(shin.z(), -shin.y()));
}

}  // namespace

std::vector<std::string> angles_of_bone(const std::string& bone) {
  for (const char* b : kSpine)
    if (bone == b) return {"spine_flexion", "spine_bend", "spine_twist"};
  for (const char* b : kNeck)
    if (bone == b) return {"neck_flexion", "neck_bend", "neck_twist"};
  for (const Side& sd : kSides) {
    const std::string side = sd.prefix;
    const Limb a = arm(sd.suffix), l = leg(sd.suffix);
    if (bone == a.upper) return {side + "shoulder_abduction", side + "shoulder_flexion", side + "shoulder_rotation"};
    if (bone == a.lower) return {side + "elbow_flexion"};
    if (bone == l.upper) return {side + "hip_flexion", side + "hip_abduction", side + "hip_rotation"};
    if (bone == l.lower) return {side + "knee_flexion"};
  }
  return {};
}

Pose rest_angles(const Rig& rig, const Eigen::MatrixX3d& joints) {
  Pose rest;
  for (const PoseAngle& a : human_pose_angles()) rest.angles[a.name] = 0;
  for (const Side& sd : kSides) {
    const std::string side = sd.prefix;
    const double s = sd.sign;
    const Limb a = arm(sd.suffix), l = leg(sd.suffix);
    const V3 shoulder = at(rig, joints, a.upper), elbow = at(rig, joints, a.lower), wrist = at(rig, joints, a.end);
    const Direction upper = direction_angles(s, elbow - shoulder);
    rest.angles[side + "shoulder_abduction"] = upper.abduction;
    rest.angles[side + "shoulder_flexion"] = upper.flexion;
    rest.angles[side + "elbow_flexion"] = angle_between(elbow - shoulder, wrist - elbow);
    const V3 hip = at(rig, joints, l.upper), knee = at(rig, joints, l.lower), ankle = at(rig, joints, l.end);
    const Direction thigh = direction_angles(s, knee - hip);
    rest.angles[side + "hip_abduction"] = thigh.abduction;
    rest.angles[side + "hip_flexion"] = thigh.flexion;
    rest.angles[side + "knee_flexion"] = knee_flexion(knee - hip, ankle - knee);
  }
  return rest;
}

std::vector<skinning::Rigid> rig_transforms(const Rig& rig, const Eigen::MatrixX3d& joints, const Pose& pose,
                                            double fraction) {
  const Pose rest = rest_angles(rig, joints);
  auto angle = [&](const std::string& name) {
    const double at_rest = rest.angles.at(name), target = pose.get(name, at_rest);
    return fraction == 1 ? target : at_rest + fraction * (target - at_rest);
  };
  std::vector<M3> local(rig.joints.size(), M3::Identity());
  auto set = [&](const std::string& bone, const M3& r) { local[static_cast<std::size_t>(rig.index(bone))] = r; };

  const M3 trunk = trunk_rotation(angle("spine_flexion") / 3, angle("spine_bend") / 3, angle("spine_twist") / 3);
  for (const char* b : kSpine) set(b, trunk);
  const M3 neck = trunk_rotation(angle("neck_flexion") / 3, angle("neck_bend") / 3, angle("neck_twist") / 3);
  for (const char* b : kNeck) set(b, neck);

  for (const Side& sd : kSides) {
    const std::string side = sd.prefix;
    const double s = sd.sign;
    // A ball joint (shoulder, hip): the limb turned about its own axis (the
    // line from the joint to the next one), then swung from its rest
    // direction to the pose's. All at the ball joint's bone, as the
    // parametric body does: MakeHuman's twist bone half way down the limb
    // (upperarm02, upperleg02) stays at rest against it, since a twist
    // split over two axes that are not quite one line would also bend the
    // elbow or knee a little.
    const auto ball = [&](const Limb& limb, const std::string& abduction, const std::string& flexion,
                          const std::string& rotation) {
      const V3 top = at(rig, joints, limb.upper), low = at(rig, joints, limb.lower);
      const Direction from = direction_angles(s, low - top);
      const Direction to{angle(side + abduction), angle(side + flexion)};
      set(limb.upper, swing(s, from, to) * turn(s * angle(side + rotation), low - top));
    };
    const Limb a = arm(sd.suffix), l = leg(sd.suffix);
    ball(a, "shoulder_abduction", "shoulder_flexion", "shoulder_rotation");
    ball(l, "hip_abduction", "hip_flexion", "hip_rotation");
    const V3 shoulder = at(rig, joints, a.upper), elbow = at(rig, joints, a.lower), wrist = at(rig, joints, a.end);
    const std::string e = side + "elbow_flexion", k = side + "knee_flexion";
    set(a.lower, turn(angle(e) - rest.angles.at(e), elbow_hinge(elbow - shoulder, wrist - elbow)));
    set(l.lower, turn(angle(k) - rest.angles.at(k), V3::UnitX()));
  }

  std::vector<int> parents;
  for (const BodyModel::Joint& j : rig.joints) parents.push_back(j.parent);
  return skinning::joint_transforms(parents, local, joints);
}

}  // namespace drape::makehuman
