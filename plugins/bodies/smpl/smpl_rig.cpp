// SMPL's pose datasets and a body posed by θ (smpl_rig.hpp).
#include "smpl_rig.hpp"

#include <drape/bodies/skinning.hpp>
#include <drape/errors.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>

namespace drape::smpl {
namespace {

// SMPL writes the root's parent as 2^32 - 1 (an unsigned -1); -1 is accepted too.
constexpr std::int64_t kSmplNoParent = 4294967295LL;
constexpr const char* kAxes[] = {"_x", "_y", "_z"};

std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
}

std::string dims_text(const h5::Dims& d) { return h5::to_string(d); }

}  // namespace

std::optional<SmplRig> read_smpl_rig(const h5::File& f, Eigen::Index n) {
  const std::string file = f.path().string();
  std::vector<std::string> present, missing;
  for (const char* name : {"/J_regressor", "/weights", "/kintree_table", "/posedirs"})
    (f.exists(name) ? present : missing).push_back(name);
  if (present.empty()) return std::nullopt;
  if (!missing.empty())
    throw ConfigError(file + " has " + listed(present) + " but not " + listed(missing) +
                      ": SMPL's pose needs all four (docs/smpl.md shows how to convert them)");
  const auto nv = static_cast<std::size_t>(n);
  h5::Dims jd, wd, kd, pd;
  const std::vector<double> jr = f.read<double>("/J_regressor", &jd);
  if (jd.size() != 2 || jd[1] != nv || jd[0] < 2)
    throw ConfigError(file + ": /J_regressor is " + dims_text(jd) + ", expected [K, " + std::to_string(n) +
                      "] (K >= 2 joints, one column per vertex of /v_template)");
  const std::size_t k = jd[0];
  const std::vector<double> w = f.read<double>("/weights", &wd);
  if (wd.size() != 2 || wd[0] != nv || wd[1] != k)
    throw ConfigError(file + ": /weights is " + dims_text(wd) + " but /J_regressor is " + dims_text(jd) + ": expected [" +
                      std::to_string(n) + ", " + std::to_string(k) + "] (one row per vertex, one column per joint)");
  const std::vector<std::int64_t> tree = f.read<std::int64_t>("/kintree_table", &kd);
  if (kd.size() != 2 || kd[0] != 2 || kd[1] != k)
    throw ConfigError(file + ": /kintree_table is " + dims_text(kd) + " but /J_regressor is " + dims_text(jd) +
                      ": expected [2, " + std::to_string(k) + "] (parents, then the joints' own indices)");
  const std::vector<double> pdirs = f.read<double>("/posedirs", &pd);
  const std::size_t features = 9 * (k - 1);
  if (pd.size() != 3 || pd[0] != nv || pd[1] != 3 || pd[2] != features)
    throw ConfigError(file + ": /posedirs is " + dims_text(pd) + " but /J_regressor is " + dims_text(jd) + ": expected [" +
                      std::to_string(n) + ", 3, " + std::to_string(features) + "] (9 per joint but the root)");

  SmplRig rig;
  rig.names = smpl_joint_names(static_cast<int>(k));
  for (std::size_t j = 0; j < k; ++j) {
    const std::int64_t parent = tree[j], self = tree[k + j];
    const bool root = parent == kSmplNoParent || parent == -1;
    if (self != static_cast<std::int64_t>(j))
      throw ConfigError(file + ": /kintree_table's second row names joint " + std::to_string(self) + " at column " +
                        std::to_string(j) + "; expected the joints in order 0, 1, ...");
    if (j == 0 ? !root : (root || parent < 0 || parent >= static_cast<std::int64_t>(j)))
      throw ConfigError(file + ": /kintree_table gives joint " + std::to_string(j) + " the parent " + std::to_string(parent) +
                        (j == 0 ? "; the root (joint 0) has none (" + std::to_string(kSmplNoParent) + " or -1)"
                                : "; expected an earlier joint (parents before children, one root)"));
    rig.parents.push_back(j == 0 ? -1 : static_cast<int>(parent));
  }
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const auto kk = static_cast<Eigen::Index>(k);
  rig.j_regressor = Eigen::Map<const RowMajor>(jr.data(), kk, n);
  rig.weights = Eigen::Map<const RowMajor>(w.data(), n, kk);
  rig.posedirs = Eigen::Map<const RowMajor>(pdirs.data(), 3 * n, static_cast<Eigen::Index>(features));
  for (const auto& [name, m] : {std::pair{"/J_regressor", &rig.j_regressor}, std::pair{"/weights", &rig.weights},
                                std::pair{"/posedirs", &rig.posedirs}})
    if (!m->allFinite()) throw ConfigError(file + ": " + name + " holds NaN or infinite values");
  // Each joint is a weighted average of vertices, so that it follows the body
  // as drape scales it and stands it on y = 0: a row summing to 2 puts its
  // joint twice as far from the origin, and every vertex skinned to it turns
  // about the wrong centre. SMPL's rows sum to 1 within float rounding.
  for (Eigen::Index j = 0; j < rig.j_regressor.rows(); ++j)
    if (const double sum = rig.j_regressor.row(j).sum(); !(std::abs(sum - 1.0) <= 1e-3)) {
      char text[64];
      std::snprintf(text, sizeof text, "%.6g", sum);
      throw ConfigError(file + ": /J_regressor row " + std::to_string(j) + " (joint " + rig.names[static_cast<std::size_t>(j)] +
                        ") sums to " + text + "; each joint is a weighted average of vertices, its row summing to 1 (docs/smpl.md)");
    }
  // Linear blend skinning moves a vertex by the weighted sum of its joints'
  // transforms: weights that do not sum to 1 scale the vertex with the
  // rotation (doubled weights moved an outside check's arm 9.8 cm further at
  // a 20 degree elbow, without a word). SMPL's own rows sum to 1 within
  // float rounding; 1e-3 leaves room for any converter's.
  for (Eigen::Index v = 0; v < rig.weights.rows(); ++v) {
    // (A negative weight pulls the vertex away from its joint's move: no SMPL file has one.)
    if (const double least = rig.weights.row(v).minCoeff(); least < -1e-6)
      throw ConfigError(file + ": /weights row " + std::to_string(v) + " holds a negative weight (" + std::to_string(least) +
                        "); skinning weights are 0 or more and sum to 1 (docs/smpl.md)");
    if (const double sum = rig.weights.row(v).sum(); !(std::abs(sum - 1.0) <= 1e-3)) {
      char text[64];  // %g: a weight of 1e300 printed by std::to_string was a 300-digit sum
      std::snprintf(text, sizeof text, "%.6g", sum);
      throw ConfigError(file + ": /weights row " + std::to_string(v) + " sums to " + text +
                        "; each vertex's skinning weights must sum to 1 (docs/smpl.md)");
    }
  }
  return rig;
}

std::vector<std::string> smpl_joint_names(int num_joints) {
  static const std::vector<std::string> smpl = {
      "pelvis",      "left_hip",     "right_hip",      "spine1",        "left_knee",  "right_knee",
      "spine2",      "left_ankle",   "right_ankle",    "spine3",        "left_foot",  "right_foot",
      "neck",        "left_collar",  "right_collar",   "head",          "left_shoulder", "right_shoulder",
      "left_elbow",  "right_elbow",  "left_wrist",     "right_wrist",   "left_hand",  "right_hand"};
  if (num_joints == static_cast<int>(smpl.size())) return smpl;
  std::vector<std::string> out{"root"};
  for (int j = 1; j < num_joints; ++j) out.push_back("joint" + std::to_string(j));
  return out;
}

std::vector<PoseAngle> smpl_pose_angles(const SmplRig& rig) {
  std::vector<PoseAngle> out;
  for (int j = 1; j < rig.num_joints(); ++j)
    for (int c = 0; c < 3; ++c)
      // SMPL sets no range of motion; every rotation has an axis-angle vector
      // of norm at most 180 degrees, so each component stays within +-180.
      // Nothing is drawn (sample range 0): SMPL ships no pose distribution.
      out.push_back({rig.names[static_cast<std::size_t>(j)] + kAxes[c], -180, 180, 0, 0,
                     std::string("component ") + "xyz"[c] + " of SMPL's axis-angle vector of joint " +
                         rig.names[static_cast<std::size_t>(j)] + ", degrees; SMPL sets no limit"});
  return out;
}

std::vector<BodyModel::Joint> smpl_joints(const SmplRig& rig) {
  std::vector<BodyModel::Joint> out;
  for (int j = 0; j < rig.num_joints(); ++j) {
    BodyModel::Joint joint{rig.names[static_cast<std::size_t>(j)], rig.parents[static_cast<std::size_t>(j)], {}};
    if (j > 0)
      for (const char* axis : kAxes) joint.angles.push_back(joint.name + axis);
    out.push_back(std::move(joint));
  }
  return out;
}

std::vector<Eigen::Vector3d> axis_angles(const SmplRig& rig, const Pose& pose, double fraction) {
  std::vector<Eigen::Vector3d> theta(static_cast<std::size_t>(rig.num_joints()), Eigen::Vector3d::Zero());
  for (int j = 1; j < rig.num_joints(); ++j)
    for (int c = 0; c < 3; ++c)
      theta[static_cast<std::size_t>(j)][c] =
          fraction * pose.get(rig.names[static_cast<std::size_t>(j)] + kAxes[c], 0.0) * M_PI / 180.0;
  return theta;
}

Eigen::MatrixX3d pose_shaped(const SmplRig& rig, const Eigen::MatrixX3d& shaped, double scale,
                             const std::vector<Eigen::Vector3d>& theta) {
  const int k = rig.num_joints();
  std::vector<Eigen::Matrix3d> rotation(static_cast<std::size_t>(k), Eigen::Matrix3d::Identity());
  // SMPL's pose feature: R_j - I of every joint but the root, each matrix row by row.
  Eigen::VectorXd feature(9 * (k - 1));
  for (int j = 1; j < k; ++j) {
    rotation[static_cast<std::size_t>(j)] = skinning::rodrigues(theta[static_cast<std::size_t>(j)]);
    const Eigen::Matrix3d d = rotation[static_cast<std::size_t>(j)] - Eigen::Matrix3d::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) feature[9 * (j - 1) + 3 * r + c] = d(r, c);
  }
  Eigen::MatrixX3d with_blend_shapes = shaped;
  if (!(feature.array() == 0).all()) {  // at rest they add nothing, not even a rounding
    const Eigen::VectorXd offsets = rig.posedirs * feature;
    for (Eigen::Index v = 0; v < shaped.rows(); ++v) with_blend_shapes.row(v) += scale * offsets.segment<3>(3 * v).transpose();
  }
  // SMPL regresses the joints from the shaped body, before the pose blend shapes.
  const Eigen::MatrixX3d joints = rig.j_regressor * shaped;
  return skinning::blend(with_blend_shapes, rig.weights, skinning::joint_transforms(rig.parents, rotation, joints));
}

std::vector<skinning::Rigid> pose_transforms(const SmplRig& rig, const Eigen::MatrixX3d& shaped,
                                             const std::vector<Eigen::Vector3d>& theta) {
  std::vector<Eigen::Matrix3d> rotation(static_cast<std::size_t>(rig.num_joints()), Eigen::Matrix3d::Identity());
  for (int j = 1; j < rig.num_joints(); ++j) rotation[static_cast<std::size_t>(j)] = skinning::rodrigues(theta[static_cast<std::size_t>(j)]);
  return skinning::joint_transforms(rig.parents, rotation, rig.j_regressor * shaped);
}

}  // namespace drape::smpl
