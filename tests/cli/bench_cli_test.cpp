// `drape bench <name>`: the registry of benchmarks, its listing and errors, and
// the two shipped benchmarks on tiny inputs (no timing is checked).
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <regex>

#include "test_support.hpp"

using namespace drape;

TEST_CASE("drape bench lists its benchmarks and refuses unknown ones", "[cli][bench]") {
  std::string out;
  REQUIRE(test::run_drape("bench list", out) == 0);
  CHECK_THAT(out, Catch::Contains("geometry") && Catch::Contains("mesh-io") && Catch::Contains("usage: drape bench <name>"));
  REQUIRE(test::run_drape("bench --help", out) == 0);
  CHECK_THAT(out, Catch::Contains("geometry") && Catch::Contains("mesh-io"));
  CHECK(test::run_drape("bench", out) == 2);
  CHECK_THAT(out, Catch::Contains("which benchmark") && Catch::Contains("mesh-io"));
  CHECK(test::run_drape("bench geomtry", out) == 2);
  CHECK_THAT(out, Catch::Contains("unknown benchmark 'geomtry'") && Catch::Contains("did you mean 'geometry'"));
  // The old command names are gone; the error points to the new one.
  CHECK(test::run_drape("bench-geometry", out) == 2);
  CHECK_THAT(out, Catch::Contains("did you mean 'bench'"));
  REQUIRE(test::run_drape("bench geometry --help", out) == 0);
  CHECK_THAT(out, Catch::Contains("usage: drape bench geometry"));
  CHECK(test::run_drape("bench geometry --ring 2", out) == 2);
}

TEST_CASE("drape bench geometry and mesh-io run on tiny inputs", "[cli][bench]") {
  std::string out;
  REQUIRE(test::run_drape("bench geometry --ring 8 --tube 6 --queries 40 --check 40 --repeats 1", out) == 0);
  CHECK_THAT(out, Catch::Contains("48 vertices") && Catch::Contains("drape BodySurface") && Catch::Contains("max error"));
  CHECK_THAT(out, Catch::Contains("Normals::on_demand") && Catch::Contains("(locate_near)"));

  test::TempDir dir;
  std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  REQUIRE(test::run_drape("bench mesh-io " + (dir / "quad.obj").string() + " --repeats 1", out) == 0);
  CHECK_THAT(out, Catch::Contains("4 vertices, 2 triangles") && Catch::Contains(".ply") &&
                      Catch::Contains("order and count kept"));
  CHECK(out.find("CHANGED") == std::string::npos);
  CHECK(test::run_drape("bench mesh-io " + (dir / "absent.obj").string(), out) == 2);
  // A count below 1 is refused by every bench (some ran 0 and -1 as 1 without a word).
  for (const std::string& bad : {"mesh-io " + (dir / "quad.obj").string() + " --repeats 0", std::string("train --graph g.yaml --data d.h5 --steps -1"),
                                 std::string("optimize --graph g.yaml --iterations 0"), std::string("simulate --drape-repeats 0")}) {
    CHECK(test::run_drape("bench " + bad, out) == 2);
    CHECK_THAT(out, Catch::Contains(": expected at least 1"));
  }
}

TEST_CASE("the benches find shipped models, graphs and scenes by name from any folder", "[cli][bench]") {
  // An outside check ran them outside the source tree: models/... and
  // graphs/scenes/... (the defaults of bench optimize and simulate) were not
  // found, where predict and render find them.
  test::TempDir dir;
  std::string out;
  const std::string in_dir = "cd " + dir.path().string() + " && " + test::drape_program().string() + " bench ";
  REQUIRE(test::run(in_dir + "infer --model models/tshirt-coarse-human.h5 --repeats 1", out) == 0);
  CHECK_THAT(out, Catch::Contains("tshirt-coarse-human.h5") && Catch::Contains("ms per body"));
  // A dataset of another body model than the model's: the dataset's counts, said of the dataset.
  const fs::path human = test::source_dir() / "datasets/bodyspace2000-human/shard-00-of-40.h5";
  CHECK(test::run(in_dir + "tradeoff --data " + human.string() + " --model models/tshirt-coarse.h5", out) == 2);
  CHECK_THAT(out, Catch::Contains(human.string() + " has 991 garment and 6904 body vertices per sample"));
  // bench train times the shipped models of sizes and poses: their batches carry the grade and the pose
  // (it read the body and the target alone: "the graph takes input 'garment_grade', which is not available here").
  REQUIRE(test::run(in_dir + "train --model models/tshirt-coarse-human.h5 --data " + human.string() +
                        " --batch 2 --steps 1 --pool 2", out) == 0);
  CHECK_THAT(out, Catch::Contains("Training throughput") && Catch::Contains("samples/s per core"));
  const fs::path posed = test::source_dir() / "datasets/posespace-human-heldout/heldout-30.h5";
  REQUIRE(test::run(in_dir + "train --model models/tshirt-coarse-posed-human.h5 --data " + posed.string() +
                        " --batch 2 --steps 1 --pool 2", out) == 0);
  CHECK_THAT(out, Catch::Contains("Training throughput"));
}

TEST_CASE("bench simulate reports whole drapes (best and median of repeated runs) and one iteration per effect",
          "[cli][bench]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::string out;
  REQUIRE(test::run_drape("bench simulate --scene " + (dir / "tiny.yaml").string() +
                        " --coarse-scene '' --repeats 1 --drape-repeats 2 --out " + (dir / "bench.md").string(),
                    out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("best of 2 | median |"));
  std::smatch m;
  // | scene | vertices | steps | iterations | settled | p | best | median |
  const std::regex drape_row(R"(tiny\.yaml \| (\d+) \| (\d+) \| (\d+) \| (yes|no) \| ([0-9.e+-]+) \| ([0-9.e+-]+) \| ([0-9.e+-]+) \|)");
  REQUIRE(std::regex_search(out, m, drape_row));
  CHECK(std::stoi(m[1]) > 100);
  CHECK(std::stoi(m[2]) >= 2);  // at least the two morph steps
  CHECK(std::stod(m[6]) > 0);
  CHECK(std::stod(m[7]) >= std::stod(m[6]));
  for (const char* row : {"| all effects |", "| without gravity |", "| without stretching |", "| without bending |",
                          "| without collision |", "Eigen SimplicialLLT"})
    CHECK_THAT(out, Catch::Contains(row));
  // The effects' own evaluation cost: a row per configuration, the removed effect's share beside it.
  // CPU time, not the wall clock (an outside check on a loaded machine saw removing an effect "cost" -44 ms),
  // and a share below zero is shown as the noise it is, never as a negative cost.
  CHECK_THAT(out, Catch::Contains("CPU time (s), best of 2"));
  CHECK_THAT(out, Catch::Contains("| configuration | CPU ms to evaluate | relative | the removed effect's share (ms) |"));
  const std::regex evaluation_row(R"(\| without collision \| ([0-9.]+) \| ([0-9.]+) \| ([0-9.]+|~0 \(-[0-9.]+: noise\)) \|)");
  REQUIRE(std::regex_search(out, m, evaluation_row));
  CHECK(std::stod(m[1]) > 0);
  CHECK_FALSE(std::regex_search(out, std::regex(R"(\| without [a-z_]+ \| [0-9.]+ \| [0-9.]+ \| -)")));
  std::ifstream md(dir / "bench.md");
  const std::string written((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  CHECK_THAT(written, Catch::Contains("## Whole drapes") && Catch::Contains("## One solver iteration"));

  // A scene of one effect has nothing to remove: both tables keep their "all effects" row only.
  std::ofstream(dir / "gravity.yaml") << "base: tiny.yaml\neffects: [gravity]\n";
  REQUIRE(test::run_drape("bench simulate --scene " + (dir / "gravity.yaml").string() +
                        " --coarse-scene '' --repeats 1 --drape-repeats 1",
                    out) == 0);
  CHECK_THAT(out, Catch::Contains("| all effects |") && Catch::Contains("CPU ms to evaluate"));
  CHECK(out.find("| without ") == std::string::npos);
}

TEST_CASE("drape bench contact times both contacts on a small shell, and the barrier's bound stops short of the body",
          "[cli][bench][barrier]") {
  std::string out;
  REQUIRE(test::run_drape("bench contact --garment-level 2 --body-level 3 --repeats 1", out) == 0);
  CHECK_THAT(out, Catch::Contains("garment 162 vertices, 320 faces; body 642 vertices, 1280 faces"));
  // The shell moves 95 % of the way to the body: the barrier's CCD bound is
  // below 1 (and positive), the penalty's is 1 (it bounds nothing).
  std::smatch m;
  REQUIRE(std::regex_search(out, m, std::regex("\\| barrier \\|.*alpha ([0-9.]+) \\|")));
  CHECK(std::stod(m[1]) > 0.0);
  CHECK(std::stod(m[1]) < 1.0);
  CHECK(std::regex_search(out, std::regex("\\| collision \\|.*alpha 1\\.000 \\|")));
  CHECK(test::run_drape("bench contact --gap 0", out) == 2);
}

// The README's commands as written from another folder: an experiment file
// and dataset resample's --onto scene by their names in the source tree
// (they were "cannot read 'graphs/experiments/table_6_4.yaml'" and "scene
// file ... does not exist" there, an outside check).
TEST_CASE("experiment and dataset resample find shipped files by name from any folder", "[cli]") {
  test::TempDir dir;
  std::string out;
  const std::string in_dir = "cd " + dir.path().string() + " && " + test::drape_program().string() + " ";
  REQUIRE(test::run(in_dir + "experiment graphs/experiments/table_6_4.yaml --dry-run", out) == 0);
  CHECK_THAT(out, Catch::Contains("experiment table_6_4"));
  const fs::path human = test::source_dir() / "datasets/bodyspace2000-human/shard-00-of-40.h5";
  REQUIRE(test::run(in_dir + "dataset resample " + human.string() + " --onto graphs/scenes/tshirt_coarse_sized.yaml --out r.h5",
                    out) == 0);
  CHECK_THAT(out, Catch::Contains("read at the 6490 vertices of tshirt_coarse_sized.yaml's template body"));
  // A scale of nothing sensible (an outside check's inf planned 10-body sets in a folder named "-xinf").
  for (const std::string scale : {"inf", "1e300", "0", "-1"}) {
    CHECK(test::run(in_dir + "experiment graphs/experiments/table_6_4.yaml --dry-run --scale " + scale, out) == 2);
    // (inf: every number option refuses it alike, "--scale inf: not a finite number")
    CHECK_THAT(out, Catch::Contains(scale == "inf" ? "--scale inf: not a finite number" : "--scale must be a number in (0, 1000]"));
  }
  CHECK(test::run(in_dir + "experiment graphs/experiments/no_such.yaml --dry-run", out) == 2);
  CHECK_THAT(out, Catch::Contains("no_such.yaml: no such file (looked in " + dir.path().string()));
}
