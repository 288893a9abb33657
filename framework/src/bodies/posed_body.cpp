// Refusing a pose in which the body passes through itself (posed_body.hpp).
#include <drape/bodies/posed_body.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/self_intersection.hpp>

#include "no_skeleton.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace drape {
namespace {

// The bone each face follows most (its three vertices' skinning weights summed).
std::vector<int> face_bones(const Eigen::MatrixXd& weights, const Eigen::MatrixX3i& faces) {
  std::vector<int> out(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::RowVectorXd w = weights.row(faces(f, 0)) + weights.row(faces(f, 1)) + weights.row(faces(f, 2));
    Eigen::Index best = 0;
    w.maxCoeff(&best);
    out[static_cast<std::size_t>(f)] = static_cast<int>(best);
  }
  return out;
}

std::vector<int> chain(const std::vector<BodyModel::Joint>& joints, int bone) {
  std::vector<int> out;
  for (; bone >= 0; bone = joints[static_cast<std::size_t>(bone)].parent) out.push_back(bone);
  return out;
}

}  // namespace

std::string describe_pose_crossings(const BodyModel& model, const Eigen::VectorXd& shape, const Pose& pose,
                                    const Eigen::MatrixX3d& posed) {
  return describe_pose_crossings(model, model.vertices(shape), pose, posed);
}

std::string describe_pose_crossings(const BodyModel& model, const Eigen::MatrixX3d& unposed, const Pose& pose,
                                    const Eigen::MatrixX3d& posed) {
  constexpr std::size_t kMaxPairs = 2000;
  const Eigen::MatrixX3i& faces = model.faces();
  auto pairs = geometry::self_intersections(posed, faces, kMaxPairs);
  if (pairs.empty()) return "";
  // Crossings the unposed body already has are the shape's, not the pose's.
  const auto rest = geometry::self_intersections(unposed, faces, kMaxPairs);
  const std::set<std::pair<int, int>> at_rest(rest.begin(), rest.end());
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [&](const auto& p) { return at_rest.count(p) > 0; }), pairs.end());
  if (pairs.empty()) return "";

  const auto joints = model.joints();
  const auto bone_of = face_bones(model.skinning_weights(), faces);
  struct Region {
    int count = 0;
    double y_lo = 1e300, y_hi = -1e300;
  };
  std::map<std::pair<int, int>, Region> regions;
  for (const auto& [fa, fb] : pairs) {
    int a = bone_of[static_cast<std::size_t>(fa)], b = bone_of[static_cast<std::size_t>(fb)];
    if (a > b) std::swap(a, b);
    Region& r = regions[{a, b}];
    ++r.count;
    for (int f : {fa, fb})
      for (int c = 0; c < 3; ++c) {
        r.y_lo = std::min(r.y_lo, posed(faces(f, c), 1));
        r.y_hi = std::max(r.y_hi, posed(faces(f, c), 1));
      }
  }
  std::ostringstream s;
  s.precision(3);
  bool first = true;
  for (const auto& [bones, r] : regions) {
    // The angles that moved either bone relative to the other: those of the
    // joints on both chains below their common ancestor.
    auto ca = chain(joints, bones.first), cb = chain(joints, bones.second);
    std::set<int> common(ca.begin(), ca.end());
    std::set<int> moved;
    for (int j : cb)
      if (!common.count(j)) moved.insert(j);
    const std::set<int> in_b(cb.begin(), cb.end());
    for (int j : ca)
      if (!in_b.count(j)) moved.insert(j);
    if (bones.first == bones.second) {
      // Folded at its own joint, or at a joint below it: a bone's faces near
      // its child's joint blend with the child (the elbow's crease is the
      // upper arm's faces), so the child joints' angles are named too (an
      // elbow at 150 degrees on the human rig was refused as "left_upper_arm
      // into itself" naming no joint, an outside check).
      moved.insert(bones.first);
      for (std::size_t j = 0; j < joints.size(); ++j)
        if (joints[j].parent == bones.first) moved.insert(static_cast<int>(j));
    }
    std::vector<std::string> angles;
    std::set<std::string> named;  // an angle several joints share (the spine's bend) named once
    for (int j : moved)
      for (const std::string& a : joints[static_cast<std::size_t>(j)].angles)
        if (pose.angles.count(a) && named.insert(a).second) {
          std::ostringstream angle;
          angle << a << "=" << pose.angles.at(a);
          angles.push_back(angle.str());
        }
    // The bone further down the skeleton first: it is the one that moved in.
    s << (first ? "" : "; ") << joints[static_cast<std::size_t>(bones.second)].name;
    s << (bones.first == bones.second ? " into itself" : " into " + joints[static_cast<std::size_t>(bones.first)].name);
    s << " (" << r.count << (r.count >= static_cast<int>(kMaxPairs) ? "+" : "") << " face pairs at heights " << r.y_lo
      << "-" << r.y_hi << " m";
    if (!angles.empty()) {
      s << "; joints:";
      for (const auto& a : angles) s << " " << a;
    }
    s << ")";
    first = false;
  }
  return s.str();
}

std::string unposeable_reason(const BodyModel& model) {
  if (model.poseable()) return "";
  Pose probe;
  probe.angles["any"] = 0;
  try {
    model.posed(model.mean_shape(), probe);
  } catch (const ConfigError& e) {
    return e.what() == std::string(kNoSkeletonRefusal) ? "" : e.what();
  }
  return "";
}

Eigen::MatrixX3d pose_body(const BodyModel& model, const std::string& model_name, const Eigen::VectorXd& shape,
                           const Pose& pose) {
  if (!model.poseable() && pose.empty()) return model.vertices(shape);
  return pose_vertices(model, model_name, model.vertices(shape), pose);
}

Eigen::MatrixX3d pose_vertices(const BodyModel& model, const std::string& model_name, const Eigen::MatrixX3d& unposed,
                               const Pose& pose) {
  if (!model.poseable()) {
    if (pose.empty()) return unposed;
    const std::string reason = unposeable_reason(model);
    throw ConfigError("body " + model_name +
                      (reason.empty() ? " has no skeleton, so it cannot be posed (docs/poses.md says which models can)" : ": " + reason));
  }
  check_pose(pose, model.pose_angles(), "body " + model_name + " pose");
  if (pose.empty()) return unposed;
  Eigen::MatrixX3d posed = model.posed_vertices(unposed, pose, 1.0);
  const std::string where = describe_pose_crossings(model, unposed, pose, posed);
  if (!where.empty())
    throw ConfigError("body " + model_name + ": this pose makes the body pass through itself: " + where);
  return posed;
}

Pose full_pose(const BodyModel& model, const Pose& pose, const Eigen::MatrixX3d& unposed) {
  const Pose rest = model.rest_pose_of(unposed);
  Pose out;
  for (const PoseAngle& a : model.pose_angles()) out.angles[a.name] = pose.get(a.name, rest.get(a.name, 0.0));
  return out;
}

DrawnPose draw_free_pose(const BodyModel& model, const Eigen::VectorXd& shape, Rng& rng, int max_draws,
                         const std::vector<PoseAngle>* space) {
  const std::vector<PoseAngle> angles = space ? *space : model.pose_angles();
  DrawnPose out;
  auto clear = [&] {
    out.vertices = model.posed(shape, out.pose);
    return describe_pose_crossings(model, shape, out.pose, out.vertices).empty();
  };
  for (; out.redraws < max_draws; ++out.redraws) {
    out.pose = draw_pose(angles, rng);
    if (clear()) return out;
  }
  // Pulled towards the rest pose: 1/2, 1/4, ... 1/1024 of each drawn offset,
  // per_pull draws each, then the rest pose itself (pull 0), which the body,
  // checked at rest when drawn, keeps clear.
  const Pose rest = model.rest_pose(shape);
  const int per_pull = std::max(1, max_draws / 5);
  constexpr int kHalvings = 10;
  for (int halvings = 1; halvings <= kHalvings + 1; ++halvings) {
    out.pull = halvings <= kHalvings ? std::ldexp(1.0, -halvings) : 0.0;
    for (int k = 0; k < (out.pull > 0 ? per_pull : 1); ++k, ++out.redraws) {
      const Pose drawn = draw_pose(angles, rng);
      out.pose = Pose{};
      for (const PoseAngle& a : angles) {
        const double at_rest = rest.get(a.name, 0.0);
        out.pose.angles[a.name] = at_rest + out.pull * (drawn.get(a.name, at_rest) - at_rest);
      }
      if (clear()) return out;
    }
  }
  throw Error("the body passes through itself in its rest pose (and in " + std::to_string(out.redraws) +
              " poses drawn and pulled towards it)");
}

}  // namespace drape
