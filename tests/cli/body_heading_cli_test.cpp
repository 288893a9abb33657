// A body given turned about the vertical, re-centred or leaning (issue 54's
// "a body a user brings"): predict and simulate drape it as the body the model
// makes and move the drape back; a body leaning past the limit is refused by
// every command before any work (body_heading.hpp, body_anchor.hpp).
#include <catch2/catch.hpp>

#include <drape/io/mesh_io.hpp>

#include <chrono>
#include <cmath>
#include <fstream>
#include <numbers>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

// The body turned by `degrees` about the vertical (+z towards +x), then moved
// so that its centroid lies at x = 0, z = 4 mm: a few millimetres off, as
// another tool might leave it (within the 9 mm a placement by the centroid
// let pass, which moved the network's drape by about 2 mm a millimetre).
struct Turned {
  Eigen::Matrix3d rotation;
  Eigen::RowVector3d shift;
  Eigen::MatrixX3d apply(const Eigen::MatrixX3d& v) const { return (v * rotation.transpose()).rowwise() + shift; }
};

Turned turned_and_centred(const Eigen::MatrixX3d& body, double degrees) {
  const double t = degrees * std::numbers::pi / 180.0;
  Turned m;
  m.rotation << std::cos(t), 0, std::sin(t), 0, 1, 0, -std::sin(t), 0, std::cos(t);
  m.shift.setZero();
  const Eigen::RowVector3d c = m.apply(body).colwise().mean();
  m.shift << -c[0], 0.0, 0.004 - c[2];
  return m;
}

// Makes a human-rig body with `body_options` (FILE.obj), and writes it turned
// and re-centred (FILE-turned.obj); returns the move.
Turned human_body_and_turned(const std::string& env, const fs::path& file, const std::string& body_options) {
  std::string out;
  REQUIRE(test::run(env + " body --param rig=human " + body_options + " --out " + file.string(), out) == 0);
  Mesh body = read_mesh(file);
  const Turned turn = turned_and_centred(body.vertices, 150.0);
  body.vertices = turn.apply(body.vertices);
  write_mesh(fs::path(file).replace_extension().string() + "-turned.obj", body);
  return turn;
}

}  // namespace

TEST_CASE("predict and simulate drape a body turned about the vertical and re-centred as the body the model made, "
          "the drape turned back", "[cli][heading]") {
  test::TempDir dir;
  std::string out;
  const std::string env = test::drape_in_source(dir.path());
  // The human rig, whose anchor places a body exactly (the mannequin's z is placed within its bodies' spread).
  SECTION("predict") {
    const Turned turn = human_body_and_turned(env, dir / "b.obj", "--bmi 38 --sex 0 --height 1.62");
    const std::string model = " predict --model models/tshirt-coarse-human.h5 --out ";
    REQUIRE(test::run(env + model + (dir / "g.obj").string() + " --body " + (dir / "b.obj").string() + " 2>&1", out) == 0);
    const int code = test::run(env + model + (dir / "gt.obj").string() + " --body " + (dir / "b-turned.obj").string() + " 2>&1", out);
    INFO(out);
    REQUIRE(code == 0);
    CHECK_THAT(out, Catch::Contains("faces 150.0 degrees from the way the body model's bodies face") &&
                        Catch::Contains("stands ("));
    const Eigen::MatrixX3d expected = turn.apply(read_mesh(dir / "g.obj").vertices);
    CHECK((read_mesh(dir / "gt.obj").vertices - expected).cwiseAbs().maxCoeff() < 1e-4);
    // render draws the body as given and that garment on it (drawn on the body turned back, 24 % of it was inside).
    REQUIRE(test::run(env + " render --model models/tshirt-coarse-human.h5 --body " + (dir / "b-turned.obj").string() +
                          " --garment " + (dir / "gt.obj").string() + " --out " + (dir / "r.html").string() + " 2>&1",
                      out) == 0);
    CHECK_THAT(out, Catch::Contains("p = 0.00% of the vertices inside the body"));
  }
  SECTION("simulate (a tiny scene): the same drape, turned back") {
    // A body the scene's shirt fits: its few unsettled steps then end the same on bodies a rounding apart (on the
    // BMI 38 body, too small around, they part by centimetres even for a body moved by a rounding only).
    const Turned turn24 = human_body_and_turned(env, dir / "b24.obj", "--bmi 24");
    std::string scene = test::tiny_human_simulation_scene();
    std::ofstream(dir / "tiny.yaml") << scene;
    const std::string simulate = " simulate " + (dir / "tiny.yaml").string() + " --threads 1 --out ";
    int code = test::run(env + simulate + (dir / "s.obj").string() + " --body " + (dir / "b24.obj").string() + " 2>&1", out);
    REQUIRE((code == 0 || code == 1));  // 1: the tiny scene's few steps need not settle
    code = test::run(env + simulate + (dir / "st.obj").string() + " --body " + (dir / "b24-turned.obj").string() + " 2>&1", out);
    INFO(out);
    REQUIRE((code == 0 || code == 1));
    CHECK_THAT(out, Catch::Contains("note: the body faces 150.0 degrees") && Catch::Contains("note: the body stands ("));
    const Eigen::MatrixX3d expected = turn24.apply(read_mesh(dir / "s.obj").vertices);
    CHECK((read_mesh(dir / "st.obj").vertices - expected).cwiseAbs().maxCoeff() < 1e-3);
  }
}

TEST_CASE("a body leaning 30 degrees is refused by simulate, predict, optimize and render within seconds, naming the lean",
          "[cli][heading]") {
  test::TempDir dir;
  std::string out;
  const std::string env = test::drape_in_source(dir.path());
  REQUIRE(test::run(env + " body --bmi 30 --out " + (dir / "m.obj").string(), out) == 0);
  Mesh body = read_mesh(dir / "m.obj");
  const double t = 30.0 * std::numbers::pi / 180.0;
  Eigen::Matrix3d lean;
  lean << 1, 0, 0, 0, std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t);
  body.vertices = body.vertices * lean.transpose();
  write_mesh(dir / "lean.obj", body);
  for (const std::string& command : test::body_mesh_commands(dir.path())) {
    INFO(command);
    const auto start = std::chrono::steady_clock::now();
    const int code = test::run(env + " " + command + " --body " + (dir / "lean.obj").string() + " 2>&1", out);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO(out);
    CHECK(code == 2);
    CHECK_THAT(out, Catch::Contains("leans 30.") && Catch::Contains("stand it upright"));
    CHECK(seconds < 30);
  }
}

TEST_CASE("predict warns that a body mesh given posed looks posed, naming the limbs, and --strict refuses it",
          "[cli][heading]") {
  test::TempDir dir;
  std::string out;
  const std::string env = test::drape_in_source(dir.path());
  REQUIRE(test::run(env + " body --param rig=human --bmi 27 --pose elbow_flexion=40 --out " + (dir / "posed.obj").string(),
                    out) == 0);
  const std::string predict = " predict --model models/tshirt-coarse-human.h5 --body " + (dir / "posed.obj").string();
  REQUIRE(test::run(env + predict + " --out " + (dir / "g.obj").string() + " 2>&1", out) == 0);
  CHECK_THAT(out, Catch::Contains("warning: the body looks posed") && Catch::Contains("left_forearm 40 degrees") &&
                      Catch::Contains("right_forearm 40 degrees") && !Catch::Contains("left_thigh") &&
                      Catch::Contains("drapes the A-pose only"));
  CHECK(test::run(env + predict + " --strict --out " + (dir / "g2.obj").string() + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("--strict: the body looks posed"));
  // The same body at rest: no word of a pose.
  REQUIRE(test::run(env + " body --param rig=human --bmi 27 --out " + (dir / "rest.obj").string(), out) == 0);
  REQUIRE(test::run(env + " predict --model models/tshirt-coarse-human.h5 --body " + (dir / "rest.obj").string() +
                        " --out " + (dir / "g3.obj").string() + " 2>&1",
                    out) == 0);
  CHECK_THAT(out, !Catch::Contains("posed"));
}
