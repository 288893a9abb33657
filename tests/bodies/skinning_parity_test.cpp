// The parametric body's posing as it was written before linear blend
// skinning moved into the framework (drape/bodies/skinning.hpp): its joint
// angles turned into per-bone rotations, composed down the skeleton about the
// rest joint centres and blended by the weights, here in one piece on the
// BodyModel interface alone. The plugin's posed bodies must stay within
// 1e-12 m of it over shapes and poses (issue 55: the refactor changes no body).
#include <catch2/catch.hpp>

#include <drape/bodies/body.hpp>
#include <drape/bodies/pose.hpp>
#include <test_support.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>

namespace {

using namespace drape;
using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

M3 turn_by(double degrees, const V3& axis) {
  if (degrees == 0) return M3::Identity();
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

M3 trunk_turn(double flexion, double bend, double twist) {
  return turn_by(-bend, V3::UnitZ()) * turn_by(flexion, V3::UnitX()) * turn_by(twist, V3::UnitY());
}

int bone(const std::vector<BodyModel::Joint>& joints, const std::string& name) {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  FAIL("no bone " << name);
  return -1;
}

// The pre-refactor posing of the parametric body (plugins/bodies/parametric/posing.cpp at b7bad3c).
Eigen::MatrixX3d posed_before(const BodyModel& model, const Eigen::VectorXd& shape, const Pose& pose) {
  const auto joints = model.joints();
  const Eigen::MatrixX3d v = model.vertices(shape), j = model.joint_positions(shape);
  const Eigen::MatrixXd w = model.skinning_weights();
  const Pose rest = model.rest_pose(shape);
  auto angle = [&](const std::string& name) { return pose.get(name, rest.angles.at(name)); };
  auto at = [&](int b) -> V3 { return j.row(b).transpose(); };
  const auto n = joints.size();
  std::vector<M3> local(n, M3::Identity());
  const M3 half = trunk_turn(0.5 * angle("spine_flexion"), 0.5 * angle("spine_bend"), 0.5 * angle("spine_twist"));
  local[static_cast<std::size_t>(bone(joints, "spine_lower"))] = half;
  local[static_cast<std::size_t>(bone(joints, "spine_upper"))] = half;
  local[static_cast<std::size_t>(bone(joints, "neck"))] =
      trunk_turn(angle("neck_flexion"), angle("neck_bend"), angle("neck_twist"));
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "left_" : "right_";
    const double s = side;
    const int u = bone(joints, p + "upper_arm"), fa = bone(joints, p + "forearm");
    const V3 arm = (at(fa) - at(u)).normalized();
    local[static_cast<std::size_t>(u)] =
        turn_by(-angle(p + "shoulder_flexion"), V3::UnitX()) *
        turn_by(s * (angle(p + "shoulder_abduction") - rest.angles.at(p + "shoulder_abduction")), V3::UnitZ()) *
        turn_by(s * angle(p + "shoulder_rotation"), arm);
    local[static_cast<std::size_t>(fa)] = turn_by(angle(p + "elbow_flexion"), arm.cross(V3::UnitZ()));
    const int h = bone(joints, p + "thigh"), k = bone(joints, p + "shin");
    const V3 leg = (at(k) - at(h)).normalized();
    local[static_cast<std::size_t>(h)] = turn_by(-angle(p + "hip_flexion"), V3::UnitX()) *
                                         turn_by(s * angle(p + "hip_abduction"), V3::UnitZ()) *
                                         turn_by(s * angle(p + "hip_rotation"), leg);
    local[static_cast<std::size_t>(k)] = turn_by(angle(p + "knee_flexion"), V3::UnitX());
  }
  // G_b = G_parent * T(J_b) R_b T(-J_b), as 4x4 matrices.
  std::vector<Eigen::Matrix4d> global(n);
  for (std::size_t b = 0; b < n; ++b) {
    Eigen::Matrix4d own = Eigen::Matrix4d::Identity();
    own.topLeftCorner<3, 3>() = local[b];
    own.topRightCorner<3, 1>() = at(static_cast<int>(b)) - local[b] * at(static_cast<int>(b));
    const int parent = joints[b].parent;
    global[b] = parent < 0 ? own : Eigen::Matrix4d(global[static_cast<std::size_t>(parent)] * own);
  }
  Eigen::MatrixX3d out = v;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    V3 moved = V3::Zero();
    for (std::size_t b = 0; b < n; ++b)
      moved += w(i, static_cast<Eigen::Index>(b)) *
               (global[b].topLeftCorner<3, 3>() * v.row(i).transpose() + global[b].topRightCorner<3, 1>() -
                v.row(i).transpose());
    out.row(i) += moved.transpose();
  }
  return out;
}

}  // namespace

TEST_CASE("parametric posing equals its pre-framework skinning", "[bodies][pose]") {
  const std::unique_ptr<BodyModel> model = test::parametric_body();
  const auto space = model->pose_angles();
  const std::vector<std::string> poses = {
      "shoulder_abduction=90,left_elbow_flexion=60",
      "spine_flexion=20,spine_bend=-10,spine_twist=25,neck_twist=30,neck_flexion=-15",
      "left_shoulder_flexion=40,right_shoulder_rotation=-30,left_hip_flexion=20,right_knee_flexion=45,hip_rotation=8",
      "left_shoulder_abduction=60,right_shoulder_abduction=30,elbow_flexion=30,hip_abduction=5,knee_flexion=20"};
  const std::vector<BodyRequest> bodies = {{24, 1.75, 1, {}}, {12, 1.55, 0, {}}, {55, 1.95, 1, {}}, {33, 1.70, 0.5, {}}};
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const Eigen::VectorXd shape = model->solve(bodies[k]);
    for (std::size_t p = k % 2; p < poses.size(); p += 2) {
      const Pose pose = parse_pose(poses[p], space, "test");
      const Eigen::MatrixX3d posed = model->posed(shape, pose);
      INFO("body " << k << ", pose " << poses[p]);
      CHECK((posed - model->vertices(shape)).cwiseAbs().maxCoeff() > 0.05);  // the pose moves the body
      CHECK((posed - posed_before(*model, shape, pose)).cwiseAbs().maxCoeff() < 1e-12);
    }
  }
}
