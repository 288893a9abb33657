// Joint angles to bone transforms and linear blend skinning (posing.hpp).
//
// Axes: x to the body's left, y up, z forward. Each joint's rotation is
// written in the rest frame and applied about the joint's rest centre, after
// its parent's transform: G_child = G_parent * T(J) * R * T(-J).
#include "posing.hpp"

#include <Eigen/Geometry>

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

struct Rigid {
  M3 r = M3::Identity();
  V3 t = V3::Zero();
  bool identity() const { return r == M3::Identity() && t == V3::Zero(); }
};

Rigid about(const M3& r, const V3& centre) { return {r, centre - r * centre}; }
Rigid compose(const Rigid& a, const Rigid& b) { return {a.r * b.r, a.r * b.t + a.t}; }

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

Eigen::MatrixX3d skin(const Skeleton& skeleton, const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d& joints,
                      const Pose& pose) {
  const Pose rest = rest_angles(joints);
  auto angle = [&](const std::string& name) { return pose.get(name, rest.angles.at(name)); };
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

  std::vector<Rigid> global(kNumBones);
  for (int b = 0; b < kNumBones; ++b) {
    const Rigid own = about(local[static_cast<std::size_t>(b)], row(joints, b));
    const int parent = skeleton.joints[static_cast<std::size_t>(b)].parent;
    global[static_cast<std::size_t>(b)] = parent < 0 ? own : compose(global[static_cast<std::size_t>(parent)], own);
  }

  // v' = v + sum_b w_b ((R_b - I) v + t_b): bones at rest add exactly zero.
  Eigen::MatrixX3d out = vertices;
  for (int b = 0; b < kNumBones; ++b) {
    const Rigid& g = global[static_cast<std::size_t>(b)];
    if (g.identity()) continue;
    const M3 d = g.r - M3::Identity();
    for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
      const double w = skeleton.weights(v, b);
      if (w == 0) continue;
      out.row(v) += w * (d * vertices.row(v).transpose() + g.t).transpose();
    }
  }
  return out;
}

}  // namespace drape::parametric
