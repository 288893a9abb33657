// --girth: a body of the body space named by its proportions is the same
// body whichever command makes it (drape body, predict, optimize, render,
// simulate), and a girth that cannot be used is refused before anything runs.
#include <catch2/catch.hpp>

#include <drape/io/mesh_io.hpp>

#include <fstream>

#include "test_support.hpp"

using namespace drape;

namespace {

// A woman of 1.65 m at BMI 40 with a wider belly and a narrower chest than
// the body model's mean build at that BMI.
const std::string kBody = "--bmi 40 --sex 0 --height 1.65";
const std::string kGirths = " --girth belly=0.1 --girth chest=-0.05";

double largest_difference(const Mesh& a, const Mesh& b) {
  REQUIRE(a.vertices.rows() == b.vertices.rows());
  return (a.vertices - b.vertices).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("predict and simulate --girth make the body that drape body --girth makes", "[cli][girth]") {
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body " + kBody + kGirths + " --out " + (dir / "made.obj").string(), out) == 0);
  REQUIRE(test::run_drape("body " + kBody + " --out " + (dir / "plain.obj").string(), out) == 0);
  const Mesh made = read_mesh(dir / "made.obj"), plain = read_mesh(dir / "plain.obj");
  // The girths change the body by centimetres (else the checks below could not tell).
  REQUIRE(largest_difference(made, plain) > 0.01);

  // predict: the body it drapes on (--body-out) and the drape itself are those of the mesh.
  // The mannequin's model: drape body makes the mannequin by default (the default model is the human rig's).
  const std::string env = "env -u DRAPE_MODEL DRAPE_CACHE_DIR=" + dir.path().string() + " " + test::drape_program().string() +
                          " predict --model " + (test::source_dir() / "models/tshirt-coarse.h5").string();
  REQUIRE(test::run(env + " " + kBody + kGirths + " --out " + (dir / "g_girth.obj").string() + " --body-out " +
                        (dir / "b_girth.obj").string(),
                    out) == 0);
  INFO(out);
  REQUIRE(test::run(env + " --body " + (dir / "made.obj").string() + " --out " + (dir / "g_mesh.obj").string(), out) == 0);
  CHECK(largest_difference(read_mesh(dir / "b_girth.obj"), made) < 1e-5);
  CHECK(largest_difference(read_mesh(dir / "g_girth.obj"), read_mesh(dir / "g_mesh.obj")) < 1e-5);

  // simulate: the scene's target body (its BMI, height and sex overridden) with the girths.
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const int code = test::run_drape("simulate " + (dir / "tiny.yaml").string() + " " + kBody + kGirths + " --body-out " +
                                 (dir / "b_sim.obj").string(),
                             out);
  CHECK((code == 0 || code == 1));  // 1: not settled within the tiny scene's few steps; the body is written either way
  CHECK(largest_difference(read_mesh(dir / "b_sim.obj"), made) < 1e-5);
}

TEST_CASE("a --girth that cannot be used is refused with the reason", "[cli][girth]") {
  test::TempDir dir;
  std::string out;
  const std::string garment = " --out " + (dir / "g.obj").string();
  CHECK(test::run_drape("predict --bmi 40 --girth belly" + garment, out) == 2);
  CHECK_THAT(out, Catch::Contains("--girth wants name=value, got 'belly'"));
  CHECK(test::run_drape("predict --bmi 40 --girth belly=wide" + garment, out) == 2);
  CHECK_THAT(out, Catch::Contains("--girth belly=wide: the value is not a number"));
  CHECK(test::run_drape("predict --bmi 40 --girth belly=0.1x" + garment, out) == 2);
  CHECK_THAT(out, Catch::Contains("the value is not a number"));
  CHECK(test::run_drape("predict --bmi 40 --girth belly=0.1 --girth belly=0.05" + garment, out) == 2);
  CHECK_THAT(out, Catch::Contains("--girth belly is given twice"));
  // The body model's own checks: the name and the range it holds.
  CHECK(test::run_drape("predict --bmi 40 --girth nose=0.1" + garment, out) == 2);
  CHECK_THAT(out, Catch::Contains("no proportion 'nose'") && Catch::Contains("belly"));
  CHECK(test::run_drape("predict --bmi 40 --girth belly=0.9" + garment, out) == 2);
  CHECK_THAT(out, Catch::Contains("'belly' = 0.9 is outside [-0.15, 0.15]"));
  CHECK_FALSE(std::filesystem::exists(dir / "g.obj"));

  // A mesh is the body itself: a girth beside it is refused, by every command.
  REQUIRE(test::run_drape("body --bmi 30 --out " + (dir / "b.obj").string(), out) == 0);
  const std::string mesh = " --body " + (dir / "b.obj").string() + " --girth belly=0.1";
  CHECK(test::run_drape("predict" + mesh + garment, out) == 2);
  CHECK_THAT(out, Catch::Contains("--girth go with --bmi"));
  CHECK(test::run_drape("optimize --scene " + (test::source_dir() / "graphs/scenes/tshirt_coarse.yaml").string() + mesh + garment,
                  out) == 2);
  CHECK_THAT(out, Catch::Contains("--girth go with --bmi"));
  CHECK(test::run_drape("render" + mesh + " --out " + (dir / "g.html").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--girth go with --bmi"));
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  CHECK(test::run_drape("simulate " + (dir / "tiny.yaml").string() + mesh + garment, out) == 2);
  CHECK_THAT(out, Catch::Contains("drop --bmi/--height/--sex/--girth"));
  CHECK_FALSE(std::filesystem::exists(dir / "g.obj"));
}
