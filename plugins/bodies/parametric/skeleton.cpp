// Joint rings and skinning weights of the parametric body (skeleton.hpp).
#include "skeleton.hpp"

#include <drape/errors.hpp>

#include <cmath>
#include <limits>

namespace drape::parametric {
namespace {

using V3 = Eigen::Vector3d;

// The rig's parts by region (implicit_body.hpp), whatever their order: a
// limb is its region's parts on one side.
bool is_arm(const Primitive& p, int side) {
  return p.side == side && (p.region == Region::UpperArm || p.region == Region::Forearm || p.region == Region::Hand);
}
bool is_leg(const Primitive& p, int side) {
  return p.side == side &&
         (p.region == Region::Thigh || p.region == Region::Shin || p.region == Region::Calf || p.region == Region::Foot);
}

// The first part of a region (and side): the trunk's first is the hips, a
// limb's first its upper cone, whose axis the joint rings are laid across.
const Primitive& first_part(const ImplicitBody& body, Region region, int side = 0) {
  for (const Primitive& p : body.parts)
    if (p.region == region && p.side == side) return p;
  throw Error("body parametric: the rig has no part of the region the skeleton needs");
}

// A ring: the template vertices on the given parts whose position along the
// axis `dir` lies within `half` of `centre` and which are within `reach` of
// the axis. Its centroid is the axis point for a limb or trunk cross-section.
std::vector<int> ring(const BodyTemplate& t, const V3& centre, const V3& dir, double half, double reach,
                      bool (*on_part)(const Primitive& part, int side), int side) {
  std::vector<int> out;
  for (Eigen::Index v = 0; v < t.vertices.rows(); ++v) {
    if (!on_part(t.mean.parts[static_cast<std::size_t>(t.bind_part[static_cast<std::size_t>(v)][0])], side)) continue;
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

bool on_trunk(const Primitive& part, int) { return part.region == Region::Trunk; }
bool on_neck(const Primitive& part, int) { return part.region == Region::Neck; }

}  // namespace

Skeleton build_skeleton(const BodyTemplate& t) {
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
  const double hips_y = first_part(t.mean, Region::Trunk).a.y();  // the hips ellipsoid's centre
  s.regressor[kPelvis] = averaged(ring(t, {0, hips_y, 0}, up, kHalf, kFar, on_trunk, 0));
  s.regressor[kSpineLower] = averaged(ring(t, {0, 1.06, 0}, up, kHalf, kFar, on_trunk, 0));
  s.regressor[kSpineUpper] = averaged(ring(t, {0, 1.22, 0}, up, kHalf, kFar, on_trunk, 0));
  const Primitive& neck = first_part(t.mean, Region::Neck);
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
    limb(first_part(t.mean, Region::UpperArm, side), is_arm, side, side > 0 ? kLeftUpperArm : kRightUpperArm);
    limb(first_part(t.mean, Region::Thigh, side), is_leg, side, side > 0 ? kLeftThigh : kRightThigh);
  }

  // Hard labels: each vertex to the bone of the part it lies on, limbs split
  // at their joint's plane and the trunk at the spine joints' heights; then
  // diffused over the mesh so that the weights blend smoothly across joints.
  const Eigen::MatrixX3d joints = regress_joints(s, t.vertices);
  const auto nv = t.vertices.rows();
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(nv, kNumBones);
  for (Eigen::Index v = 0; v < nv; ++v) {
    const Primitive& part = t.mean.parts[static_cast<std::size_t>(t.bind_part[static_cast<std::size_t>(v)][0])];
    const V3 p = t.vertices.row(v).transpose();
    int bone = kNeck;
    if (part.region == Region::Trunk)
      bone = p.y() < joints(kSpineLower, 1) ? kPelvis : p.y() < joints(kSpineUpper, 1) ? kSpineLower : kSpineUpper;
    else if (part.region == Region::Neck)  // the neck below its joint stays with the shoulders
      bone = (p - joints.row(kNeck).transpose()).dot((neck.b - neck.a).normalized()) < 0 ? kSpineUpper : kNeck;
    else if (part.region == Region::Head)
      bone = kNeck;
    else
      for (int side : {1, -1}) {
        // A limb's vertex: its upper bone above the lower joint's plane, its lower bone below.
        const std::pair<int, bool (*)(const Primitive&, int)> limbs[] = {{side > 0 ? kLeftUpperArm : kRightUpperArm, is_arm},
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
