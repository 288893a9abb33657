// Joint rings and skinning weights of the parametric body (skeleton.hpp).
#include "skeleton.hpp"

#include <drape/errors.hpp>

#include <cmath>
#include <limits>

namespace drape::parametric {
namespace {

using V3 = Eigen::Vector3d;

// The rig's parts in plan_body's order (body_plan.cpp): trunk 0-6, neck 7,
// head 8-9, then per side (right, x < 0, first) upper arm, forearm, hand, and
// thigh, shin, calf, foot.
constexpr int kNumParts = 24;
constexpr int kTrunkLast = 6, kNeckPart = 7, kHeadLast = 9;
int arm_part(int side, int k) { return 10 + (side > 0 ? 3 : 0) + k; }  // k: 0 upper, 1 fore, 2 hand
int leg_part(int side, int k) { return 16 + (side > 0 ? 4 : 0) + k; }  // k: 0 thigh, 1 shin, 2 calf, 3 foot

bool is_arm(int part, int side) { return part >= arm_part(side, 0) && part <= arm_part(side, 2); }
bool is_leg(int part, int side) { return part >= leg_part(side, 0) && part <= leg_part(side, 3); }

// A ring: the template vertices on the given parts whose position along the
// axis `dir` lies within `half` of `centre` and which are within `reach` of
// the axis. Its centroid is the axis point for a limb or trunk cross-section.
std::vector<int> ring(const BodyTemplate& t, const V3& centre, const V3& dir, double half, double reach,
                      bool (*on_part)(int part, int side), int side) {
  std::vector<int> out;
  for (Eigen::Index v = 0; v < t.vertices.rows(); ++v) {
    if (!on_part(t.bind_part[static_cast<std::size_t>(v)][0], side)) continue;
    const V3 d = t.vertices.row(v).transpose() - centre;
    const double along = d.dot(dir);
    if (std::abs(along) <= half && (d - along * dir).norm() <= reach) out.push_back(static_cast<int>(v));
  }
  if (out.size() < 6) throw Error("body parametric: a joint ring of the skeleton has " + std::to_string(out.size()) + " vertices");
  return out;
}

V3 centroid(const Eigen::MatrixX3d& v, const std::vector<int>& ids) {
  V3 c = V3::Zero();
  for (int i : ids) c += v.row(i).transpose();
  return c / static_cast<double>(ids.size());
}

// joint = (1 + t) * centroid(a) - t * centroid(b): the point on the line
// through both rings nearest `target` on the template. For a joint buried in
// the trunk (shoulder, hip) the rings lie out on the limb, where its cross-
// section is clean, and the joint is extrapolated along the limb's axis.
std::vector<std::pair<int, double>> extrapolated(const BodyTemplate& t, const std::vector<int>& a, const std::vector<int>& b,
                                                 const V3& target) {
  const V3 ca = centroid(t.vertices, a), cb = centroid(t.vertices, b);
  const double s = (target - ca).dot(ca - cb) / (ca - cb).squaredNorm();
  std::vector<std::pair<int, double>> out;
  for (int i : a) out.push_back({i, (1 + s) / static_cast<double>(a.size())});
  for (int i : b) out.push_back({i, -s / static_cast<double>(b.size())});
  return out;
}

std::vector<std::pair<int, double>> averaged(const std::vector<int>& ids) {
  std::vector<std::pair<int, double>> out;
  for (int i : ids) out.push_back({i, 1.0 / static_cast<double>(ids.size())});
  return out;
}

bool on_trunk(int part, int) { return part <= kTrunkLast; }
bool on_neck(int part, int) { return part == kNeckPart; }
bool on_arm(int part, int side) { return is_arm(part, side); }
bool on_leg(int part, int side) { return is_leg(part, side); }

}  // namespace

Skeleton build_skeleton(const BodyTemplate& t) {
  const auto& parts = t.mean.parts;
  if (parts.size() != kNumParts) throw Error("body parametric: the skeleton expects 24 rig parts, the rig has " + std::to_string(parts.size()));
  Skeleton s;
  auto joint = [&](const char* name, int parent, std::vector<std::string> angles) {
    s.joints.push_back({name, parent, std::move(angles)});
  };
  const std::vector<std::string> spine = {"spine_flexion", "spine_bend", "spine_twist"};
  joint("pelvis", -1, {});
  joint("spine_lower", kPelvis, spine);
  joint("spine_upper", kSpineLower, spine);
  joint("neck", kSpineUpper, {"neck_flexion", "neck_bend", "neck_twist"});
  for (const char* side : {"left", "right"}) {
    const std::string p = std::string(side) + "_";
    joint((p + "upper_arm").c_str(), kSpineUpper, {p + "shoulder_abduction", p + "shoulder_flexion", p + "shoulder_rotation"});
    joint((p + "forearm").c_str(), static_cast<int>(s.joints.size()) - 1, {p + "elbow_flexion"});
  }
  for (const char* side : {"left", "right"}) {
    const std::string p = std::string(side) + "_";
    joint((p + "thigh").c_str(), kPelvis, {p + "hip_flexion", p + "hip_abduction", p + "hip_rotation"});
    joint((p + "shin").c_str(), static_cast<int>(s.joints.size()) - 1, {p + "knee_flexion"});
  }

  // Joint rings on the mean body, at the rig's own joints (body_plan.cpp).
  constexpr double kHalf = 0.012, kFar = std::numeric_limits<double>::infinity();
  const V3 up = V3::UnitY();
  s.regressor.resize(kNumBones);
  const double hips_y = parts[0].a.y();  // ellipsoid centre
  s.regressor[kPelvis] = averaged(ring(t, {0, hips_y, 0}, up, kHalf, kFar, on_trunk, 0));
  s.regressor[kSpineLower] = averaged(ring(t, {0, 1.06, 0}, up, kHalf, kFar, on_trunk, 0));
  s.regressor[kSpineUpper] = averaged(ring(t, {0, 1.22, 0}, up, kHalf, kFar, on_trunk, 0));
  const Primitive& neck = parts[kNeckPart];
  s.regressor[kNeck] = averaged(ring(t, neck.a + 0.5 * (neck.b - neck.a), (neck.b - neck.a).normalized(), kHalf, 2 * neck.ra, on_neck, 0));
  // A limb's two bones: the upper one's joint extrapolated back from rings at
  // its middle and its far end (the joint itself sits where no clean ring
  // is), the lower one's at that far end's ring.
  const auto limb = [&](const Primitive& upper, const auto& on_limb, int side, int first_bone) {
    const V3 axis = (upper.b - upper.a).normalized();
    const auto end = ring(t, upper.b, axis, kHalf, 2 * upper.ra, on_limb, side);
    const auto mid = ring(t, upper.a + 0.45 * (upper.b - upper.a), axis, kHalf, 2 * upper.ra, on_limb, side);
    s.regressor[static_cast<std::size_t>(first_bone)] = extrapolated(t, mid, end, upper.a);
    s.regressor[static_cast<std::size_t>(first_bone + 1)] = averaged(end);
  };
  for (int side : {1, -1}) {
    limb(parts[static_cast<std::size_t>(arm_part(side, 0))], on_arm, side, side > 0 ? kLeftUpperArm : kRightUpperArm);
    limb(parts[static_cast<std::size_t>(leg_part(side, 0))], on_leg, side, side > 0 ? kLeftThigh : kRightThigh);
  }

  // Hard labels: each vertex to the bone of the part it lies on, limbs split
  // at their joint's plane and the trunk at the spine joints' heights; then
  // diffused over the mesh so that the weights blend smoothly across joints.
  const Eigen::MatrixX3d joints = regress_joints(s, t.vertices);
  const auto nv = t.vertices.rows();
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(nv, kNumBones);
  for (Eigen::Index v = 0; v < nv; ++v) {
    const int part = t.bind_part[static_cast<std::size_t>(v)][0];
    const V3 p = t.vertices.row(v).transpose();
    int bone = kNeck;
    if (part <= kTrunkLast)
      bone = p.y() < joints(kSpineLower, 1) ? kPelvis : p.y() < joints(kSpineUpper, 1) ? kSpineLower : kSpineUpper;
    else if (part == kNeckPart)  // the neck below its joint stays with the shoulders
      bone = (p - joints.row(kNeck).transpose()).dot((neck.b - neck.a).normalized()) < 0 ? kSpineUpper : kNeck;
    else if (part <= kHeadLast)
      bone = kNeck;
    else
      for (int side : {1, -1}) {
        // A limb's vertex: its upper bone above the lower joint's plane, its lower bone below.
        const std::pair<int, bool (*)(int, int)> limbs[] = {{side > 0 ? kLeftUpperArm : kRightUpperArm, is_arm},
                                                            {side > 0 ? kLeftThigh : kRightThigh, is_leg}};
        for (const auto& [upper, on_limb] : limbs)
          if (on_limb(part, side)) {
            const V3 axis = (joints.row(upper + 1) - joints.row(upper)).transpose().normalized();
            bone = (p - joints.row(upper + 1).transpose()).dot(axis) < 0 ? upper : upper + 1;
          }
      }
    w(v, bone) = 1;
  }
  Eigen::MatrixXd next(nv, kNumBones);
  for (int it = 0; it < kSkinningSmoothing; ++it) {
    for (Eigen::Index v = 0; v < nv; ++v) {
      const auto& nb = t.neighbours[static_cast<std::size_t>(v)];
      Eigen::Matrix<double, 1, kNumBones> mean = Eigen::Matrix<double, 1, kNumBones>::Zero();  // no allocation per vertex
      for (int u : nb) mean += w.row(u);
      next.row(v) = 0.5 * w.row(v) + (0.5 / static_cast<double>(nb.size())) * mean;
    }
    w.swap(next);
  }
  // Averaging keeps each row's sum at 1 up to rounding; make it exact.
  for (Eigen::Index v = 0; v < nv; ++v) w.row(v) /= w.row(v).sum();
  s.weights = std::move(w);
  return s;
}

Eigen::MatrixX3d regress_joints(const Skeleton& skeleton, const Eigen::MatrixX3d& vertices) {
  Eigen::MatrixX3d j = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(skeleton.regressor.size()), 3);
  for (std::size_t b = 0; b < skeleton.regressor.size(); ++b)
    for (const auto& [v, weight] : skeleton.regressor[b]) j.row(static_cast<Eigen::Index>(b)) += weight * vertices.row(v);
  return j;
}

}  // namespace drape::parametric
