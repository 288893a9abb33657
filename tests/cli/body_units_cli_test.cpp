// A body mesh in other units or Z up is refused by every command that takes
// one, before it computes anything (issue 58: a centimetre body used to
// simulate for 13 minutes and predict exited 0 with 19.7 % inside).
#include <catch2/catch.hpp>

#include <drape/io/mesh_io.hpp>

#include <chrono>
#include <fstream>

#include "test_support.hpp"

using namespace drape;

TEST_CASE("simulate, predict, optimize and render refuse a body in centimetres or Z up within seconds", "[cli][units]") {
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body --bmi 30 --out " + (dir / "m.obj").string(), out) == 0);
  Mesh body = read_mesh(dir / "m.obj");
  Mesh cm = body;
  cm.vertices *= 100;
  write_mesh(dir / "cm.obj", cm);
  Mesh z_up = body;
  z_up.vertices.col(1).swap(z_up.vertices.col(2));
  write_mesh(dir / "z.obj", z_up);
  const std::string env = "env -u DRAPE_MODEL DRAPE_CACHE_DIR=" + dir.path().string() + " " + test::drape_program().string();
  for (const std::string& command : test::body_mesh_commands(dir.path())) {
    for (const char* file : {"cm.obj", "z.obj"}) {
      INFO(command << " --body " << file);
      const auto start = std::chrono::steady_clock::now();
      const int code = test::run("cd " + test::source_dir().string() + " && " + env + " " + command + " --body " +
                                     (dir / file).string() + " 2>&1",
                                 out);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      INFO(out);
      CHECK(code == 2);
      CHECK_THAT(out, Catch::Contains(std::string(file) == "cm.obj" ? "scaled by 0.01" : "longer along z"));
      CHECK(seconds < 30);  // the refusal comes before any simulation or optimisation
    }
  }
  // In millimetres its coordinates pass 1 km: refused as millimetres, without the far body's note first.
  Mesh mm = body;
  mm.vertices *= 1000;
  write_mesh(dir / "mm.obj", mm);
  CHECK(test::run("cd " + test::source_dir().string() + " && " + env + " predict --model models/tshirt-coarse.h5 --out " + (dir / "g.obj").string() +
                      " --body " + (dir / "mm.obj").string() + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("likely in millimetres") && !Catch::Contains("from the origin"));
}

TEST_CASE("a body mesh of another rig than the model's is refused naming the shipped models that take it",
          "[cli][units]") {
  test::TempDir dir;
  std::string out;
  const std::string env = test::drape_in_source(dir.path());
  // The mannequin's body (the body model's default rig) given to the human rig's model, the default.
  REQUIRE(test::run(env + " body --bmi 30 --out " + (dir / "mannequin.obj").string(), out) == 0);
  const int code = test::run(env + " predict --model models/tshirt-coarse-human.h5 --body " +
                                 (dir / "mannequin.obj").string() + " --out " + (dir / "g.obj").string() + " 2>&1",
                             out);
  INFO(out);
  CHECK(code == 2);
  CHECK_THAT(out, Catch::Contains("has 6490 vertices, expected 6904") && Catch::Contains("tshirt-coarse.h5") &&
                      Catch::Contains("take bodies of 6490 vertices (--model)") &&
                      !Catch::Contains("tshirt-coarse-posed-human.h5"));
}

TEST_CASE("without --model a body mesh of the mannequin rig is draped by the mannequin's shipped models", "[cli][units]") {
  // The default model is the human rig's: a mannequin body given with --body
  // was refused by its count (predict, optimize, render), where --bmi on a
  // mannequin scene found the mannequin's model (an outside check following
  // docs/optimization.md).
  test::TempDir dir;
  std::string out;
  const std::string env = test::drape_in_source(dir.path());
  REQUIRE(test::run(env + " body --bmi 30 --out " + (dir / "rest.obj").string(), out) == 0);
  REQUIRE(test::run(env + " body --bmi 30 --pose shoulder_abduction=60 --out " + (dir / "posed.obj").string(), out) == 0);
  REQUIRE(test::run(env + " predict --body " + (dir / "rest.obj").string() + " --out " + (dir / "g.obj").string() + " 2>&1", out) == 0);
  CHECK_THAT(out, Catch::Contains("has 6490 vertices (another rig than tshirt-coarse-human.h5's): draped by the shipped") &&
                      Catch::Contains("models/tshirt-coarse.h5, the model of that rig"));
  // Posed: the mannequin's model of posed drapes, the pose read off the mesh.
  REQUIRE(test::run(env + " predict --body " + (dir / "posed.obj").string() + " --out " + (dir / "p.obj").string() + " 2>&1", out) == 0);
  CHECK_THAT(out, Catch::Contains("models/tshirt-coarse-posed.h5, the model of that rig") &&
                      Catch::Contains("model: ") && Catch::Contains("of posed drapes") &&
                      Catch::Contains("the body mesh is posed"));
  // optimize on the mannequin's scene, as docs/optimization.md shows it.
  REQUIRE(test::run(env + " optimize --scene graphs/scenes/tshirt_coarse_contact.yaml --body " + (dir / "rest.obj").string() +
                        " --iters 2 --out " + (dir / "o.obj").string() + " 2>&1", out) == 0);
  CHECK_THAT(out, Catch::Contains("models/tshirt-coarse.h5, the model of that rig"));
  // The human rig's body keeps the default.
  REQUIRE(test::run(env + " body --param rig=human --bmi 30 --out " + (dir / "human.obj").string(), out) == 0);
  REQUIRE(test::run(env + " predict --body " + (dir / "human.obj").string() + " --out " + (dir / "h.obj").string() + " 2>&1", out) == 0);
  CHECK_THAT(out, Catch::Contains("tshirt-coarse-human.h5") && !Catch::Contains("another rig"));
}

TEST_CASE("predict drapes a body a thousand kilometres from the origin as it drapes it at the origin", "[cli][units]") {
  // An outside check: the body was rounded to single precision before it was
  // moved near where the training bodies stood; at 1e6 m its drape came out
  // 3-12 cm off, through the body, in another size.
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body --param rig=human --bmi 30 --out " + (dir / "b.obj").string(), out) == 0);
  Mesh far = read_mesh(dir / "b.obj");
  const Eigen::RowVector3d offset(1e6, 0.0, -2.5e6);
  far.vertices.rowwise() += offset;
  write_mesh(dir / "far.obj", far);
  const std::string model = " --model " + (test::source_dir() / "models/tshirt-coarse-human.h5").string();
  REQUIRE(test::run_drape("predict" + model + " --body " + (dir / "b.obj").string() + " --out " + (dir / "g.obj").string(), out) == 0);
  REQUIRE(test::run_drape("predict" + model + " --body " + (dir / "far.obj").string() + " --out " +
                              (dir / "g_far.obj").string() + " --body-out " + (dir / "b_far.obj").string(),
                          out) == 0);
  CHECK_THAT(out, Catch::Contains("m from the origin; it is draped moved near it in double precision"));
  const Mesh near_drape = read_mesh(dir / "g.obj"), far_drape = read_mesh(dir / "g_far.obj");
  REQUIRE(far_drape.num_vertices() == near_drape.num_vertices());
  CHECK(((far_drape.vertices.rowwise() - offset) - near_drape.vertices).cwiseAbs().maxCoeff() < 1e-5);
  CHECK((read_mesh(dir / "b_far.obj").vertices - far.vertices).cwiseAbs().maxCoeff() < 1e-5);
}

TEST_CASE("a MakeHuman body given to a model names the scenes that simulate it", "[cli][units]") {
  // It said only "has 13380 vertices, expected 6904": no model drapes it, a
  // scene of its body model simulates it (an outside check).
  const auto makehuman = test::shared_assets() / "makehuman";
  if (test::shared_assets().empty() || !std::filesystem::exists(makehuman / "base/base.obj")) {
    WARN("SKIPPED: ../shared/assets/makehuman is absent; this test needs it");
    return;
  }
  test::TempDir dir;
  std::string out;
  const std::string env = test::drape_in_source(dir.path());
  REQUIRE(test::run(env + " body --model makehuman --bmi 25 --out " + (dir / "mh.obj").string() + " 2>&1", out) == 0);
  CHECK(test::run(env + " predict --body " + (dir / "mh.obj").string() + " --out " + (dir / "g.obj").string() + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("no shipped model drapes bodies of 13380 vertices") &&
                      Catch::Contains("graphs/scenes/makehuman_tshirt.yaml") && Catch::Contains("drape simulate SCENE --body"));
  CHECK_FALSE(std::filesystem::exists(dir / "g.obj"));
}
