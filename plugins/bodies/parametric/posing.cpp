// Joint angles to bone rotations (posing.hpp); the framework composes and
// blends them (drape/bodies/skinning.hpp).
//
// Axes: x to the body's left, y up, z forward. Each joint's rotation is
// written in the rest frame and applied about the joint's rest centre, after
// its parent's transform: G_child = G_parent * T(J) * R * T(-J).
#include "posing.hpp"

#include <drape/bodies/skinning.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace drape::parametric {
namespace {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

double rad(double degrees) { return degrees * M_PI / 180.0; }
M3 turn(double degrees, const V3& axis) {
  if (degrees == 0) return M3::Identity();
  return Eigen::AngleAxisd(rad(degrees), axis.normalized()).toRotationMatrix();
}

V3 row(const Eigen::MatrixX3d& m, int i) { return m.row(i).transpose(); }

double shoulder_abduction_at_rest(const Eigen::MatrixX3d& joints, int upper_arm) {
  const V3 d = row(joints, upper_arm + 1) - row(joints, upper_arm);
  return std::atan2(std::abs(d.x()), -d.y()) * 180.0 / M_PI;
}

// Bend, flexion and twist of the trunk or neck: flexion forward about x
// (positive takes +y towards +z), bend to the left about z (positive takes +y
// towards +x), twist to the left about y (positive takes +z towards +x).
M3 trunk_rotation(double flexion, double bend, double twist) {
  return turn(-bend, V3::UnitZ()) * turn(flexion, V3::UnitX()) * turn(twist, V3::UnitY());
}

}  // namespace

Pose rest_angles(const Eigen::MatrixX3d& joints) {
  Pose rest;
  for (const PoseAngle& a : human_pose_angles()) rest.angles[a.name] = 0;
  rest.angles["left_shoulder_abduction"] = shoulder_abduction_at_rest(joints, kLeftUpperArm);
  rest.angles["right_shoulder_abduction"] = shoulder_abduction_at_rest(joints, kRightUpperArm);
  return rest;
}

namespace {

// How much of the inner-elbow corrective a flexion gets: none up to 70
// degrees, the top of the sampled range (so every drawn pose, and every
// posed dataset, is plain LBS), all of it from 90 (the first body whose
// crease crosses under LBS, BMI 65, does at 73), smoothly between, so the
// body is a continuous function of the angle.
double elbow_press(double flexion) {
  const double x = std::clamp((flexion - 70.0) / 20.0, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

// The inner side of a bent elbow, pressed flat as flesh pressed on flesh is:
// LBS averages the crease's vertices into the opposite limb (the forearm
// through the upper arm from 73-101 degrees, docs/poses.md). Each arm vertex
// on the crease's side is kept on its own limb's side of the plane that
// bisects the two limbs at the elbow, `kGap` from it: upper-arm vertices
// (more upper arm than forearm in their weights) behind it, forearm ones in
// front. A geometric corrective in the spirit of implicit skinning (Vaillant
// et al. 2013, which stops the skin where two limbs' surfaces meet), not a
// learned pose blend shape; the joints' transforms (and so a garment's
// skinning) are untouched.
void press_inner_elbows(Eigen::MatrixX3d& posed, const Skeleton& skeleton, const Eigen::MatrixX3d& joints,
                        const std::vector<skinning::Rigid>& transforms, double left_flexion, double right_flexion) {
  constexpr double kGap = 0.002;  // m each side of the plane: the two sides never touch
  for (int side : {1, -1}) {
    const double s = elbow_press(side > 0 ? left_flexion : right_flexion);
    if (s == 0) continue;
    const int upper = side > 0 ? kLeftUpperArm : kRightUpperArm, fore = upper + 1;
    const V3 rest_arm = (row(joints, fore) - row(joints, upper)).normalized();
    const skinning::Rigid& tu = transforms[static_cast<std::size_t>(upper)];
    const skinning::Rigid& tf = transforms[static_cast<std::size_t>(fore)];
    const V3 elbow = tu.r * row(joints, fore) + tu.t;
    const V3 u = tu.r * rest_arm, f = tf.r * rest_arm;  // along the upper arm and the forearm, away from the shoulder
    const V3 normal = (u + f).normalized();              // the bisecting plane's, towards the hand
    const V3 inner = (f - u).normalized();               // towards the crease
    for (Eigen::Index i = 0; i < posed.rows(); ++i) {
      const double wu = skeleton.weights(i, upper), wf = skeleton.weights(i, fore);
      if (wu + wf < 0.5) continue;  // the trunk's, not the arm's
      const V3 x = posed.row(i).transpose();
      if (inner.dot(x - elbow) <= 0) continue;  // the outer side: the point of the elbow stays
      const double h = normal.dot(x - elbow);
      const double push = wu >= wf ? -std::max(0.0, h + kGap) : std::max(0.0, kGap - h);
      if (push != 0) posed.row(i) += (s * push * normal).transpose();
    }
  }
}

}  // namespace

Eigen::MatrixX3d skin(const Skeleton& skeleton, const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d& joints,
                      const Pose& pose, double fraction) {
  // Blended by the framework's skinning: a bone at rest adds exactly zero, so
  // the rest pose gives `vertices` back.
  const std::vector<skinning::Rigid> transforms = bone_transforms(skeleton, joints, pose, fraction);
  Eigen::MatrixX3d posed = skinning::blend(vertices, skeleton.weights, transforms);
  // The elbows' rest angle is 0 (straight), so `fraction` of the way is fraction * angle.
  press_inner_elbows(posed, skeleton, joints, transforms, fraction * pose.get("left_elbow_flexion", 0.0),
                     fraction * pose.get("right_elbow_flexion", 0.0));
  return posed;
}

std::vector<skinning::Rigid> bone_transforms(const Skeleton& skeleton, const Eigen::MatrixX3d& joints, const Pose& pose,
                                             double fraction) {
  const Pose rest = rest_angles(joints);
  // The angle `fraction` of the way from this body's rest (its A-pose arms) to the pose's.
  auto angle = [&](const std::string& name) {
    const double at_rest = rest.angles.at(name), target = pose.get(name, at_rest);
    return fraction == 1 ? target : at_rest + fraction * (target - at_rest);
  };
  // Each joint's rotation in the rest frame.
  std::vector<M3> local(kNumBones, M3::Identity());
  // The trunk bends at two joints, half at each, so that it curves.
  const M3 half_trunk = trunk_rotation(0.5 * angle("spine_flexion"), 0.5 * angle("spine_bend"), 0.5 * angle("spine_twist"));
  local[kSpineLower] = local[kSpineUpper] = half_trunk;
  local[kNeck] = trunk_rotation(angle("neck_flexion"), angle("neck_bend"), angle("neck_twist"));
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "left_" : "right_";
    const double s = side;
    const int u = side > 0 ? kLeftUpperArm : kRightUpperArm;
    const V3 arm = (row(joints, u + 1) - row(joints, u)).normalized();
    // Rotation about the arm's own axis (inwards positive), then abduction in
    // the frontal plane (away from the body), then flexion (forward).
    local[static_cast<std::size_t>(u)] =
        turn(-angle(p + "shoulder_flexion"), V3::UnitX()) *
        turn(s * (angle(p + "shoulder_abduction") - rest.angles.at(p + "shoulder_abduction")), V3::UnitZ()) *
        turn(s * angle(p + "shoulder_rotation"), arm);
    // The elbow's hinge lies across the arm in the frontal plane: flexion
    // takes the forearm forward (palms face the thighs in the A-pose).
    local[static_cast<std::size_t>(u + 1)] = turn(angle(p + "elbow_flexion"), arm.cross(V3::UnitZ()));
    const int h = side > 0 ? kLeftThigh : kRightThigh;
    const V3 leg = (row(joints, h + 1) - row(joints, h)).normalized();
    local[static_cast<std::size_t>(h)] = turn(-angle(p + "hip_flexion"), V3::UnitX()) *
                                         turn(s * angle(p + "hip_abduction"), V3::UnitZ()) *
                                         turn(s * angle(p + "hip_rotation"), leg);
    local[static_cast<std::size_t>(h + 1)] = turn(angle(p + "knee_flexion"), V3::UnitX());
  }

  // Composed down the skeleton.
  std::vector<int> parents;
  for (const BodyModel::Joint& j : skeleton.joints) parents.push_back(j.parent);
  return skinning::joint_transforms(parents, local, joints);
}

}  // namespace drape::parametric
