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

// A hinge joint's corrective (press_inner_hinge): the bone before the joint
// (the one after is the next), the flexion angle, and where the corrective
// fades in. None up to the top of the sampled range (so every drawn pose,
// and every posed dataset, is plain LBS); all of it by `full`, smoothly
// between, so the body is a continuous function of the angle. Elbows: from
// 70 to 90 degrees (the first body whose crease crosses under LBS, BMI 65,
// does at 73); knees: from 60 to 68 (a BMI 65 woman's calf enters her thigh
// at 64-66 under LBS, so the fade is short).
struct Hinge {
  int bone;
  const char* flexion;
  double start, full;
};
constexpr Hinge kHinges[] = {
    {kLeftUpperArm, "left_elbow_flexion", 70, 90}, {kRightUpperArm, "right_elbow_flexion", 70, 90},
    {kLeftThigh, "left_knee_flexion", 60, 68},     {kRightThigh, "right_knee_flexion", 60, 68},
};

double press_share(const Hinge& hinge, double flexion) {
  const double x = std::clamp((flexion - hinge.start) / (hinge.full - hinge.start), 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

// The inner side of a bent elbow or knee, pressed flat as flesh pressed on
// flesh is: LBS averages the crease's vertices into the opposite limb (the
// forearm through the upper arm from 73-101 degrees, the calf through the
// thigh from 68-105, docs/poses.md). Each limb vertex on the crease's side
// is kept on its own limb's side of the plane that bisects the two limbs at
// the joint, more than `kGap` from it: vertices of the bone before the joint (more of
// its weight than the next bone's) behind it, the next bone's in front. A
// geometric corrective in the spirit of implicit skinning (Vaillant et al.
// 2013, which stops the skin where two limbs' surfaces meet), not a learned
// pose blend shape; the joints' transforms (and so a garment's skinning) are
// untouched.
void press_inner_hinge(Eigen::MatrixX3d& posed, const Skeleton& skeleton, const Eigen::MatrixX3d& joints,
                       const std::vector<skinning::Rigid>& transforms, int upper, double share) {
  constexpr double kGap = 0.002;   // m each side of the plane: the two sides never touch
  constexpr double kBand = 0.01;   // m: how far from the plane the skin begins to give
  const int fore = upper + 1;
  const V3 rest_limb = (row(joints, fore) - row(joints, upper)).normalized();
  const skinning::Rigid& tu = transforms[static_cast<std::size_t>(upper)];
  const skinning::Rigid& tf = transforms[static_cast<std::size_t>(fore)];
  const V3 hinge = tu.r * row(joints, fore) + tu.t;
  const V3 u = tu.r * rest_limb, f = tf.r * rest_limb;  // along the two bones, away from the trunk
  const V3 normal = (u + f).normalized();              // the bisecting plane's, towards the hand or foot
  const V3 inner = (f - u).normalized();               // towards the crease
  for (Eigen::Index i = 0; i < posed.rows(); ++i) {
    const double wu = skeleton.weights(i, upper), wf = skeleton.weights(i, fore);
    if (wu + wf < 0.5) continue;  // the trunk's, not the limb's
    const V3 x = posed.row(i).transpose();
    if (inner.dot(x - hinge) <= 0) continue;  // the outer side: the point of the elbow, the kneecap stay
    const double h = normal.dot(x - hinge);
    // Signed distance on the vertex's own side of the plane; below kBand it
    // is squeezed towards kGap by a monotone map (no two vertices swap order
    // along the normal, so the pressed skin cannot fold through itself, as a
    // projection onto the plane did from about 86 degrees at the knee).
    const double side = wu >= wf ? -1.0 : 1.0;  // the bone before the joint behind the plane, the next in front
    const double own = side * h;
    if (own >= kGap + kBand) continue;
    const double pressed = kGap + kBand * std::exp((own - kGap) / kBand - 1);
    const double push = pressed - own;  // >= 0: e^(t-1) >= t
    posed.row(i) += (share * side * push * normal).transpose();
  }
}

}  // namespace

Eigen::MatrixX3d skin(const Skeleton& skeleton, const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d& joints,
                      const Pose& pose, double fraction) {
  // Blended by the framework's skinning: a bone at rest adds exactly zero, so
  // the rest pose gives `vertices` back.
  const std::vector<skinning::Rigid> transforms = bone_transforms(skeleton, joints, pose, fraction);
  Eigen::MatrixX3d posed = skinning::blend(vertices, skeleton.weights, transforms);
  // Elbows and knees rest straight (0), so `fraction` of the way is fraction * angle.
  for (const Hinge& hinge : kHinges)
    if (const double share = press_share(hinge, fraction * pose.get(hinge.flexion, 0.0)); share > 0)
      press_inner_hinge(posed, skeleton, joints, transforms, hinge.bone, share);
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
