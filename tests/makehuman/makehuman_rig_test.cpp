// The MakeHuman body posed by MakeHuman's own rig (rigs/default.mhskel and
// rigs/default_weights.mhw in ../shared/assets/makehuman, CC0). Every test
// skips with a message when the assets or the rig files are absent.
#include <drape/bodies/body.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/winding.hpp>
#include <drape/training/rng.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

fs::path assets() { return test::shared_assets() / "makehuman"; }

bool rig_present() {
  if (test::shared_assets().empty() || !fs::exists(assets() / "base/base.obj")) {
    WARN("SKIPPED: ../shared/assets/makehuman is absent; the MakeHuman rig tests need it");
    return false;
  }
  if (!fs::exists(assets() / "rigs/default.mhskel") || !fs::exists(assets() / "rigs/default_weights.mhw")) {
    WARN("SKIPPED: ../shared/assets/makehuman/rigs/ lacks default.mhskel or default_weights.mhw (docs/poses.md)");
    return false;
  }
  return true;
}

std::unique_ptr<BodyModel> body_at(const fs::path& folder) {
  const auto& d = test::plugins().get("makehuman");
  return test::plugins().create_body("makehuman", Params(d.params, {{"path", {YAML::Node(folder.string()), {}}}}, "makehuman"));
}

const BodyModel& mh() {
  static const std::unique_ptr<BodyModel> body = body_at(assets());
  return *body;
}

// Sliders: gender, muscle, weight, height, proportions, african, asian, caucasian.
Eigen::VectorXd sliders(double gender, double muscle, double weight, double height) {
  Eigen::VectorXd s(8);
  s << gender, muscle, weight, height, 0.5, 1.0 / 3, 1.0 / 3, 1.0 / 3;
  return s;
}

int bone(const std::string& name) {
  const auto joints = mh().joints();
  for (std::size_t b = 0; b < joints.size(); ++b)
    if (joints[b].name == name) return static_cast<int>(b);
  FAIL("no bone " << name);
  return -1;
}

Pose pose_of(const std::string& text) { return parse_pose(text, mh().pose_angles(), "test"); }

double degrees(double r) { return r * 180.0 / M_PI; }
double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return degrees(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
}

// Each bone head carried into the pose: head b moves with its own transform
// (which turns about it), written out here rather than taken from the plugin.
Eigen::MatrixX3d posed_joints(const Eigen::VectorXd& shape, const Pose& pose) {
  const Eigen::MatrixX3d rest = mh().joint_positions(shape);
  const auto g = mh().joint_transforms(mh().vertices(shape), pose);
  Eigen::MatrixX3d out(rest.rows(), 3);
  for (Eigen::Index b = 0; b < rest.rows(); ++b)
    out.row(b) = (g[static_cast<std::size_t>(b)].r * rest.row(b).transpose() + g[static_cast<std::size_t>(b)].t).transpose();
  return out;
}

Eigen::Vector3d head(const Eigen::MatrixX3d& joints, const std::string& name) { return joints.row(bone(name)).transpose(); }

// The bones at and below `root` in the rig.
std::set<int> subtree(const std::string& root) {
  const auto joints = mh().joints();
  std::set<int> out{bone(root)};
  for (std::size_t b = 0; b < joints.size(); ++b)
    if (out.count(joints[b].parent)) out.insert(static_cast<int>(b));
  return out;
}

}  // namespace

TEST_CASE("MakeHuman's rig: bone heads lie inside the body and follow its shape", "[makehuman][pose]") {
  if (!rig_present()) {
    SUCCEED("skipped");
    return;
  }
  REQUIRE(mh().poseable());
  REQUIRE(mh().joints().size() == 163);  // MakeHuman's default skeleton
  CHECK(mh().joints().front().parent == -1);
  const char* key[] = {"spine05", "spine03", "spine01", "neck02", "head", "upperarm01.L", "upperarm01.R", "lowerarm01.L",
                       "lowerarm01.R", "wrist.L", "upperleg01.L", "upperleg01.R", "lowerleg01.L", "lowerleg01.R", "foot.R"};
  for (const Eigen::VectorXd& shape : {mh().mean_shape(), sliders(0, 0, 1, 0.5), sliders(1, 0, 0, 0.8)}) {
    const Eigen::MatrixX3d v = mh().vertices(shape), j = mh().joint_positions(shape);
    Eigen::MatrixX3d points(std::size(key), 3);
    for (std::size_t k = 0; k < std::size(key); ++k) points.row(static_cast<Eigen::Index>(k)) = j.row(bone(key[k]));
    const auto inside = geometry::winding_numbers(points, v, mh().faces());
    for (std::size_t k = 0; k < std::size(key); ++k) {
      INFO(key[k] << " at " << points.row(static_cast<Eigen::Index>(k)));
      CHECK(inside[k] == 1);
    }
  }
  // A taller body has every joint of the legs, trunk and arms higher.
  const Eigen::MatrixX3d short_j = mh().joint_positions(sliders(1, 0.5, 0.5, 0.2));
  const Eigen::MatrixX3d tall_j = mh().joint_positions(sliders(1, 0.5, 0.5, 0.8));
  for (const char* b : {"lowerleg01.L", "upperleg01.R", "spine02", "neck01", "upperarm01.L", "lowerarm01.R", "wrist.L"}) {
    INFO(b << ": " << short_j(bone(b), 1) << " m against " << tall_j(bone(b), 1) << " m");
    CHECK(tall_j(bone(b), 1) > short_j(bone(b), 1) + 0.02);
  }
}

TEST_CASE("MakeHuman's skinning weights cover the skin and sum to 1", "[makehuman][pose]") {
  if (!rig_present()) {
    SUCCEED("skipped");
    return;
  }
  const Eigen::MatrixXd w = mh().skinning_weights();
  REQUIRE(w.rows() == mh().num_vertices());
  REQUIRE(w.cols() == static_cast<Eigen::Index>(mh().joints().size()));
  CHECK(w.minCoeff() >= 0);
  CHECK((w.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
  // The forearm's skin follows the forearm's bones.
  Eigen::Index moved = 0;
  for (int b : subtree("lowerarm01.L")) moved += (w.col(b).array() > 0.5).count();
  CHECK(moved > 300);
}

TEST_CASE("MakeHuman's rest angles give its own mesh back bit for bit", "[makehuman][pose]") {
  if (!rig_present()) {
    SUCCEED("skipped");
    return;
  }
  for (const Eigen::VectorXd& shape : {mh().mean_shape(), sliders(0, 0, 1, 0.3)}) {
    const Eigen::MatrixX3d v = mh().vertices(shape);
    const Pose rest = mh().rest_pose(shape);
    CHECK(rest.angles.size() == mh().pose_angles().size());
    INFO(format_pose(rest));
    // MakeHuman's stance: arms down and out about 40 degrees, elbows bent.
    CHECK(rest.angles.at("left_shoulder_abduction") == Approx(40).margin(5));
    CHECK(rest.angles.at("right_shoulder_abduction") == Approx(40).margin(5));
    CHECK(rest.angles.at("left_elbow_flexion") == Approx(45).margin(10));
    CHECK(rest.angles.at("spine_twist") == 0);
    CHECK(mh().posed(shape, rest) == v);
    CHECK(mh().posed(shape, Pose{}) == v);
    CHECK(mh().posed_vertices(v, rest, 0.5) == v);
    CHECK(mh().posed_vertices(v, pose_of("elbow_flexion=90"), 0) == v);
    CHECK(mh().rest_pose_of(v).angles == rest.angles);
    for (const auto& g : mh().joint_transforms(v, rest)) CHECK(g.identity());
  }
}

TEST_CASE("an elbow flexion moves the forearm and leaves the trunk alone", "[makehuman][pose]") {
  if (!rig_present()) {
    SUCCEED("skipped");
    return;
  }
  const Eigen::VectorXd shape = mh().mean_shape();
  const Eigen::MatrixX3d v = mh().vertices(shape);
  const Eigen::MatrixX3d posed = mh().posed(shape, pose_of("left_elbow_flexion=100"));
  const Eigen::MatrixXd w = mh().skinning_weights();
  const std::set<int> forearm = subtree("lowerarm01.L");
  int forearm_moved = 0, forearm_vertices = 0, still = 0, others_moved = 0;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    double on_forearm = 0;
    for (int b : forearm) on_forearm += w(i, b);
    const double moved = (posed.row(i) - v.row(i)).norm();
    if (on_forearm > 0.99) {
      ++forearm_vertices;
      forearm_moved += moved > 0.01;
    } else if (on_forearm == 0) {
      ++still;
      others_moved += moved != 0;
    }
  }
  INFO(forearm_vertices << " forearm vertices, " << forearm_moved << " moved over 1 cm; " << still << " others, " << others_moved << " moved");
  CHECK(forearm_vertices > 300);
  CHECK(forearm_moved > 0.9 * forearm_vertices);
  CHECK(still > 10000);
  CHECK(others_moved == 0);
}

TEST_CASE("MakeHuman's posed joints have the angles asked for, measured by hand", "[makehuman][pose]") {
  if (!rig_present()) {
    SUCCEED("skipped");
    return;
  }
  for (const Eigen::VectorXd& shape : {mh().mean_shape(), sliders(0, 0, 1, 0.3)}) {
    const Pose rest = mh().rest_pose(shape);
    const Pose pose = pose_of(
        "left_shoulder_abduction=70,left_shoulder_flexion=25,left_shoulder_rotation=20,left_elbow_flexion=100,"
        "right_shoulder_abduction=90,right_elbow_flexion=10,right_hip_flexion=30,right_knee_flexion=45,left_hip_abduction=20");
    const Eigen::MatrixX3d j = posed_joints(shape, pose);
    // Left arm: abduction is the upper arm's angle out of the sagittal plane,
    // flexion its forward turn in it, the elbow the angle between the bones.
    const Eigen::Vector3d upper = head(j, "lowerarm01.L") - head(j, "upperarm01.L");
    const Eigen::Vector3d fore = head(j, "wrist.L") - head(j, "lowerarm01.L");
    CHECK(degrees(std::asin(upper.normalized().x())) == Approx(70).margin(1e-6));
    CHECK(degrees(std::atan2(upper.z(), -upper.y())) == Approx(25).margin(1e-6));
    CHECK(angle_between(upper, fore) == Approx(100).margin(1e-6));
    // Right arm (x < 0 is its outside): raised to horizontal, elbow nearly straight.
    const Eigen::Vector3d r_upper = head(j, "lowerarm01.R") - head(j, "upperarm01.R");
    CHECK(degrees(std::asin(-r_upper.normalized().x())) == Approx(90).margin(1e-6));
    CHECK(std::abs(r_upper.y()) < 1e-9 * r_upper.norm() + 1e-9);
    CHECK(angle_between(r_upper, head(j, "wrist.R") - head(j, "lowerarm01.R")) == Approx(10).margin(1e-6));
    // Right leg: thigh forward 30 degrees, the shin bent back 45 from its line
    // (in the sagittal plane), the hip's sideways angle left at rest.
    const Eigen::Vector3d thigh = head(j, "lowerleg01.R") - head(j, "upperleg01.R");
    const Eigen::Vector3d shin = head(j, "foot.R") - head(j, "lowerleg01.R");
    CHECK(degrees(std::atan2(thigh.z(), -thigh.y())) == Approx(30).margin(1e-6));
    CHECK(degrees(std::asin(-thigh.normalized().x())) == Approx(rest.angles.at("right_hip_abduction")).margin(1e-6));
    CHECK(degrees(std::atan2(thigh.z(), -thigh.y()) - std::atan2(shin.z(), -shin.y())) == Approx(45).margin(1e-6));
    // Left leg: out to 20 degrees.
    const Eigen::Vector3d l_thigh = head(j, "lowerleg01.L") - head(j, "upperleg01.L");
    CHECK(degrees(std::asin(l_thigh.normalized().x())) == Approx(20).margin(1e-6));
    // The upper arm's twist turns the elbow's hinge, not the upper arm's direction.
    const Eigen::MatrixX3d untwisted = posed_joints(shape, pose_of("left_shoulder_abduction=70,left_shoulder_flexion=25,left_elbow_flexion=100"));
    CHECK((head(untwisted, "lowerarm01.L") - head(j, "lowerarm01.L")).norm() < 1e-9);
    CHECK((head(untwisted, "wrist.L") - head(j, "wrist.L")).norm() > 0.02);
  }
  // The trunk: a twist of 30 turns the shoulders' line by 30 about the vertical.
  const Eigen::VectorXd shape = mh().mean_shape();
  const Eigen::MatrixX3d rest_j = mh().joint_positions(shape), j = posed_joints(shape, pose_of("spine_twist=30"));
  const Eigen::Vector3d a = head(rest_j, "upperarm01.L") - head(rest_j, "upperarm01.R");
  const Eigen::Vector3d b = head(j, "upperarm01.L") - head(j, "upperarm01.R");
  CHECK(degrees(std::atan2(a.z(), a.x()) - std::atan2(b.z(), b.x())) == Approx(30).margin(1e-6));
}

TEST_CASE("MakeHuman bodies in drawn poses do not pass through themselves", "[makehuman][pose]") {
  if (!rig_present()) {
    SUCCEED("skipped");
    return;
  }
  Rng rng(11);
  int redraws = 0;
  for (const Eigen::VectorXd& shape : {mh().mean_shape(), sliders(0, 0, 1, 0.5), sliders(1, 0.2, 0.1, 0.7)}) {
    const DrawnPose d = draw_free_pose(mh(), shape, rng);
    redraws += d.redraws;
    INFO(format_pose(d.pose));
    // Edges through faces, a test other than the face pairs' that drew it,
    // beyond those the unposed MakeHuman mesh has.
    const auto rest = geometry::self_edge_crossings(mh().vertices(shape), mh().faces(), 1000);
    const auto posed = geometry::self_edge_crossings(d.vertices, mh().faces(), 1000);
    CHECK(posed.size() <= rest.size());
  }
  INFO("redraws " << redraws);
  CHECK(redraws < 30);
}

TEST_CASE("a MakeHuman pose that makes the body pass through itself is refused naming the bones", "[makehuman][pose]") {
  if (!rig_present()) {
    SUCCEED("skipped");
    return;
  }
  const std::string m =
      test::message_of([] { pose_body(mh(), "makehuman", mh().mean_shape(), pose_of("hip_abduction=-25")); });
  INFO(m);
  CHECK(m.find("body makehuman: this pose makes the body pass through itself: ") != std::string::npos);
  CHECK(m.find("upperleg") != std::string::npos);
  CHECK(m.find("left_hip_abduction=-25") != std::string::npos);
  CHECK_NOTHROW(pose_body(mh(), "makehuman", mh().mean_shape(), pose_of("shoulder_abduction=30,left_elbow_flexion=60")));
}

TEST_CASE("without its rig files the MakeHuman body is refused a pose naming them", "[makehuman][pose]") {
  if (test::shared_assets().empty() || !fs::exists(assets() / "base/base.obj")) {
    SUCCEED("skipped");
    return;
  }
  test::TempDir dir;
  for (const char* part : {"base", "targets"}) fs::create_directory_symlink(assets() / part, dir / part);
  const auto body = body_at(dir.path());
  CHECK_FALSE(body->poseable());
  const std::string m = test::message_of([&] { pose_body(*body, "makehuman", body->mean_shape(), Pose{{{"left_elbow_flexion", 10}}}); });
  INFO(m);
  CHECK(m.find("cannot be posed") != std::string::npos);
  CHECK(m.find((dir / "rigs" / "default.mhskel").string()) != std::string::npos);
  CHECK(m.find("default_weights.mhw") != std::string::npos);

  // Malformed rig files: one line naming the file and what is wrong.
  fs::create_directory(dir / "rigs");
  std::ofstream(dir / "rigs" / "default_weights.mhw") << R"({"weights": {}})";
  const auto refused = [&](const std::string& skeleton) {
    test::TempDir copy;
    for (const char* part : {"base", "targets"}) fs::create_directory_symlink(assets() / part, copy / part);
    fs::create_directory(copy / "rigs");
    fs::copy_file(dir / "rigs" / "default_weights.mhw", copy / "rigs" / "default_weights.mhw");
    std::ofstream(copy / "rigs" / "default.mhskel") << skeleton;
    const auto b = body_at(copy.path());
    return test::message_of([&] { b->posed(b->mean_shape(), Pose{{{"left_elbow_flexion", 10}}}); });
  };
  const std::string broken = refused("{\"bones\": {");
  CHECK(broken.find("default.mhskel: not JSON") != std::string::npos);
  const std::string parent = refused(R"({"joints": {"a": [1], "b": [2]}, "bones": {"root": {"head": "a", "tail": "b", "parent": null},
      "arm": {"head": "a", "tail": "b", "parent": "torso"}}})");
  CHECK(parent.find("bone \"arm\" has parent \"torso\", which is no bone") != std::string::npos);
  const std::string vertex = refused(R"({"joints": {"a": [1], "b": [99999]}, "bones": {"root": {"head": "a", "tail": "b"}}})");
  CHECK(vertex.find("joint \"b\" refers to vertex 99999, the base mesh has 19158") != std::string::npos);
}

TEST_CASE("drape body --model makehuman --pose writes a posed MakeHuman body", "[makehuman][pose][cli]") {
  if (!rig_present()) {
    SUCCEED("skipped");
    return;
  }
  test::TempDir dir;
  std::string out;
  const std::string obj = (dir / "posed.obj").string();
  REQUIRE(test::run_drape("body --model makehuman --bmi 25 --pose shoulder_abduction=30,left_elbow_flexion=60 --out " + obj, out) == 0);
  INFO(out);
  CHECK(out.find("posed: left_elbow_flexion=60,left_shoulder_abduction=30,right_shoulder_abduction=30") != std::string::npos);
  CHECK(fs::exists(obj));
  const std::string refused = (dir / "refused.obj").string();
  CHECK(test::run_drape("body --model makehuman --bmi 25 --pose hip_abduction=-25 --out " + refused, out) == 2);
  INFO(out);
  CHECK(out.find("body makehuman: this pose makes the body pass through itself") != std::string::npos);
  CHECK_FALSE(fs::exists(refused));
}
