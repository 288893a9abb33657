// A pose mirrored left for right (mirrored_pose, what the mirror average of
// posed models feeds the network): the map by hand, and the body the body
// model poses in it against the reflection of the body in the pose itself,
// measured on the surfaces, so that a wrong sign (a twist not negated) shows.
#include <catch2/catch.hpp>

#include <drape/bodies/body.hpp>
#include <drape/bodies/pose.hpp>
#include <drape/geometry/nearest_triangles.hpp>
#include <test_support.hpp>

#include <algorithm>
#include <memory>
#include <vector>

namespace {

using namespace drape;

const BodyModel& human() {
  static const std::unique_ptr<BodyModel> model = test::parametric_body("{rig: human}");
  return *model;
}

// Every angle away from zero, the two sides apart (a pose the body accepts).
Pose lopsided() {
  Pose p;
  p.angles = {{"spine_flexion", 10},          {"spine_bend", 10},          {"spine_twist", 20},
              {"neck_flexion", 5},            {"neck_bend", 8},            {"neck_twist", 15},
              {"left_shoulder_abduction", 80}, {"right_shoulder_abduction", 35},
              {"left_shoulder_flexion", 25},  {"right_shoulder_flexion", -10},
              {"left_shoulder_rotation", 20}, {"right_shoulder_rotation", -10},
              {"left_elbow_flexion", 50},     {"right_elbow_flexion", 10},
              {"left_hip_flexion", 15},       {"right_hip_flexion", -5},
              {"left_hip_abduction", 8},      {"right_hip_abduction", 2},
              {"left_hip_rotation", 8},       {"right_hip_rotation", -5},
              {"left_knee_flexion", 25},      {"right_knee_flexion", 5}};
  return p;
}

// The 99th percentile of how far each vertex of `a`, reflected through x = 0,
// lies off the surface of `b` (same faces).
double reflected_off(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, const Eigen::MatrixX3i& faces) {
  const geometry::NearestTriangles surface(b, faces);
  std::vector<double> d;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const Eigen::Vector3d p(-a(i, 0), a(i, 1), a(i, 2));
    d.push_back((surface.nearest(p).point - p).norm());
  }
  std::sort(d.begin(), d.end());
  return d[static_cast<std::size_t>(0.99 * static_cast<double>(d.size() - 1))];
}

}  // namespace

TEST_CASE("mirrored_pose swaps the sides and negates the bends and twists", "[bodies][pose]") {
  const Pose m = mirrored_pose(lopsided(), human_pose_angles());
  CHECK(m.angles.size() == lopsided().angles.size());
  CHECK(m.angles.at("right_shoulder_abduction") == 80);
  CHECK(m.angles.at("left_shoulder_abduction") == 35);
  CHECK(m.angles.at("right_shoulder_flexion") == 25);
  CHECK(m.angles.at("left_shoulder_rotation") == -10);
  CHECK(m.angles.at("right_knee_flexion") == 25);
  CHECK(m.angles.at("spine_flexion") == 10);
  CHECK(m.angles.at("neck_flexion") == 5);
  CHECK(m.angles.at("spine_bend") == -10);
  CHECK(m.angles.at("spine_twist") == -20);
  CHECK(m.angles.at("neck_bend") == -8);
  CHECK(m.angles.at("neck_twist") == -15);
  // Twice is the pose again.
  CHECK(mirrored_pose(m, human_pose_angles()).angles == lopsided().angles);
}

TEST_CASE("a body posed in the mirrored pose is the reflection of the body in the pose", "[bodies][pose]") {
  const BodyModel& body = human();
  const Eigen::VectorXd shape = body.solve({30, 1.75, 0.0, {}});
  const Eigen::MatrixX3d rest = body.vertices(shape);
  const Eigen::MatrixX3d posed = body.posed(shape, lopsided());
  const Eigen::MatrixX3d mirror = body.posed(shape, mirrored_pose(lopsided(), body.pose_angles()));
  // The rest body's own asymmetry bounds what a right mirror can reach.
  const double asymmetry = reflected_off(rest, rest, body.faces());
  const double right = reflected_off(posed, mirror, body.faces());
  // The sides swapped but the twist and bends kept: what the test tells apart.
  Pose swapped_only = mirrored_pose(lopsided(), body.pose_angles());
  for (const char* lateral : {"spine_bend", "spine_twist", "neck_bend", "neck_twist"})
    swapped_only.angles[lateral] = -swapped_only.angles[lateral];
  const double wrong = reflected_off(posed, body.posed(shape, swapped_only), body.faces());
  INFO("rest asymmetry " << asymmetry << " m, mirrored " << right << " m, twist and bends kept " << wrong << " m");
  CHECK(right < asymmetry + 1e-3);
  CHECK(wrong > 10 * right);
}

TEST_CASE("mirrored_pose refuses an angle whose mirror the space does not give", "[bodies][pose]") {
  std::vector<PoseAngle> space = {{"left_elbow_y", -150, 10, 0, 0, "SMPL's raw axis"},
                                  {"right_elbow_y", -150, 10, 0, 0, "SMPL's raw axis"}};
  Pose p;
  p.angles["left_elbow_y"] = -30;
  CHECK_THROWS_WITH(mirrored_pose(p, space), Catch::Contains("left_elbow_y") && Catch::Contains("mirrors"));
  space[0].mirror = space[1].mirror = PoseAngle::Mirror::same;
  CHECK(mirrored_pose(p, space).angles.at("right_elbow_y") == -30);
  Pose unknown;
  unknown.angles["left_wrist"] = 5;
  CHECK_THROWS_WITH(mirrored_pose(unknown, space), Catch::Contains("left_wrist"));
  space.pop_back();  // the right side gone
  CHECK_THROWS_WITH(mirrored_pose(p, space), Catch::Contains("right_elbow_y"));
}
