// A body mesh the body model's faces read wrong -- mirrored, its vertices
// re-indexed, a vertex thrown far out -- is refused by every command that
// takes one, as predict refused it: simulate drew a pose off a mirrored body
// and started stepping, body --unpose wrote a rest body of garbage, and a
// spike was simulated as a body (found by a sweep of bad input, 2026-12-06).
#include <catch2/catch.hpp>

#include <drape/io/mesh_io.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

// mirror.obj (x -> -x, the faces kept), shuffled.obj (the vertices in
// another order, the faces re-indexed with them: the same surface, another
// order) and spike.obj (one vertex 0.8 m out) from the mannequin body m.obj.
void misread_bodies(const fs::path& dir) {
  const Mesh body = read_mesh(dir / "m.obj");
  Mesh mirror = body;
  mirror.vertices.col(0) *= -1;
  write_mesh(dir / "mirror.obj", mirror);
  std::vector<int> order(static_cast<std::size_t>(body.num_vertices()));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  Mesh shuffled = body;
  std::vector<int> where(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    shuffled.vertices.row(static_cast<Eigen::Index>(i)) = body.vertices.row(order[i]);
    where[static_cast<std::size_t>(order[i])] = static_cast<int>(i);
  }
  for (Eigen::Index f = 0; f < shuffled.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) shuffled.faces(f, c) = where[static_cast<std::size_t>(body.faces(f, c))];
  write_mesh(dir / "shuffled.obj", shuffled);
  Mesh spike = body;
  spike.vertices(3000, 2) += 0.8;
  write_mesh(dir / "spike.obj", spike);
}

}  // namespace

TEST_CASE("simulate, predict, render, optimize and body --unpose refuse a mirrored, re-indexed or spiked body mesh",
          "[cli][units]") {
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body --bmi 30 --out " + (dir / "m.obj").string(), out) == 0);
  misread_bodies(dir.path());
  const std::string env = "env -u DRAPE_MODEL DRAPE_CACHE_DIR=" + dir.path().string() + " " + test::drape_program().string();
  std::vector<std::string> commands = test::body_mesh_commands(dir.path());
  commands.push_back("body --unpose");  // the mannequin rig: the body model's default
  const std::vector<std::pair<std::string, std::string>> bodies = {
      {"mirror.obj", "turns inwards (negative volume): the body is mirrored"},
      {"shuffled.obj", "its faces are not the body model's"},
      {"spike.obj", " and 3000 is 0.8"}};
  for (const std::string& command : commands)
    for (const auto& [file, why] : bodies) {
      const bool unpose = command == "body --unpose";
      const std::string given = unpose ? " " + (dir / file).string() + " --out " + (dir / "rest.obj").string()
                                       : " --body " + (dir / file).string();
      INFO(command << given);
      const auto start = std::chrono::steady_clock::now();
      const int code = test::run("cd " + test::source_dir().string() + " && " + env + " " + command + given + " 2>&1", out);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      INFO(out);
      CHECK(code == 2);
      CHECK_THAT(out, Catch::Contains("body " + (dir / file).string()) && Catch::Contains(why));
      // Not taken for a posed body first (predict announced the model of posed drapes).
      CHECK_THAT(out, !Catch::Contains("posed"));
      CHECK(seconds < 30);
      CHECK_FALSE(fs::exists(dir / "g.obj"));
      CHECK_FALSE(fs::exists(dir / "rest.obj"));
    }
}

TEST_CASE("a body upside down is refused as leaning, and a damaged model or a folder as output are named", "[cli][units]") {
  test::TempDir dir;
  std::string out;
  const std::string env = test::drape_in_source(dir.path());
  REQUIRE(test::run(env + " body --param rig=human --bmi 30 --out " + (dir / "b.obj").string(), out) == 0);
  Mesh body = read_mesh(dir / "b.obj");
  body.vertices.col(0) *= -1;  // turned 180 degrees about z: upside down, not mirrored
  body.vertices.col(1) *= -1;
  body.vertices.col(1).array() += 1.75;
  write_mesh(dir / "upside_down.obj", body);
  // It said "the body has no torso cross-section around its vertical axis to measure".
  CHECK(test::run(env + " predict --body " + (dir / "upside_down.obj").string() + " --out " + (dir / "g.obj").string() +
                      " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("leans 180.0 degrees from upright") && !Catch::Contains("torso cross-section"));
  // Posed and upside down: unposed, it was draped upright and the drape turned back, hanging across gravity.
  REQUIRE(test::run(env + " body --param rig=human --bmi 30 --pose shoulder_abduction=60,elbow_flexion=40 --out " +
                        (dir / "p.obj").string(), out) == 0);
  Mesh posed = read_mesh(dir / "p.obj");
  posed.vertices.col(0) *= -1;
  posed.vertices.col(1) *= -1;
  posed.vertices.col(1).array() += 1.75;
  write_mesh(dir / "posed_upside_down.obj", posed);
  CHECK(test::run(env + " predict --body " + (dir / "posed_upside_down.obj").string() + " --out " +
                      (dir / "g.obj").string() + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("leans 180.0 degrees from upright"));
  // body --unpose drapes nothing: it says so and writes the body at rest as the mesh stood.
  REQUIRE(test::run(env + " body --param rig=human --unpose " + (dir / "posed_upside_down.obj").string() + " --out " +
                        (dir / "rest.obj").string() + " 2>&1", out) == 0);
  CHECK_THAT(out, Catch::Contains("note: the mesh stands 180.0 degrees from upright as a whole"));
  CHECK_FALSE(fs::exists(dir / "g.obj"));
  // A folder as a model's output: exit 2 naming it (exit 1, "cannot move the finished file into place ...: Success").
  fs::create_directories(dir / "out");
  CHECK(test::run(env + " model set models/tshirt-coarse.h5 --set post.enabled=true --out " + (dir / "out").string() +
                      " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("it is a folder") && !Catch::Contains("Success"));
}
