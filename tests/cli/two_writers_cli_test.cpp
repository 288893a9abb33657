// Two jobs started at the same instant on one output: one runs, the other is
// refused (exit 2) whatever its flags, and the output is valid (issue 58).
// The race itself is scripts/two_writers.sh (20 rounds for the measurement);
// here 3 rounds of each of generate, train (the second with --force),
// optimize and dataset merge.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

TEST_CASE("generate, train, optimize and dataset merge started twice at once on one output: one runs, one is refused",
          "[cli][lock]") {
  test::TempDir dir;
  std::string out;
  const int code = test::run("cd " + test::source_dir().string() + " && env -u DRAPE_MODEL DRAPE=" +
                                 test::drape_program().string() + " TMPDIR=" + dir.path().string() +
                                 " bash scripts/two_writers.sh 3",
                             out);
  INFO(out);
  CHECK(code == 0);
  // The script's line per command, its name padded to 14 (printf %-14s).
  for (std::string command : {"generate", "train", "optimize", "merge"}) {
    command.resize(14, ' ');
    CHECK_THAT(out, Catch::Contains(command + " 3 rounds: one ran and one was refused with a valid output 3,"));
  }
}

TEST_CASE("outputs are checked before any work: a missing folder, an unknown mesh format", "[cli][outputs]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string drape = "env -u DRAPE_MODEL DRAPE_CACHE_DIR=" + dir.path().string() + " " + test::drape_program().string();
  std::string out;
  const std::string missing = (dir / "missing" / "g.obj").string();
  for (const std::string command :
       {" simulate " + (dir / "tiny.yaml").string() + " --bmi 30 --out " + missing, " predict --bmi 30 --out " + missing,
        " predict --bmi 30 --out " + (dir / "g.obj").string() + " --body-out " + missing, " body --bmi 30 --out " + missing,
        " train graphs/examples/mlp_baseline.yaml --data none.h5 --out " + (dir / "missing" / "m.h5").string(),
        " generate " + (dir / "tiny.yaml").string() + " --count 2 --out " + (dir / "missing" / "d.h5").string()}) {
    INFO(command);
    CHECK(test::run("cd " + test::source_dir().string() + " && " + drape + command, out) == 2);
    INFO(out);
    CHECK_THAT(out, Catch::Contains("folder") && Catch::Contains("does not exist"));
    CHECK_THAT(out, !Catch::Contains("simulating"));  // refused before the work started
  }
  CHECK(test::run(drape + " predict --bmi 30 --out " + (dir / "g.stl").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("unknown mesh format '.stl'") && !Catch::Contains("predicted"));
  CHECK_FALSE(fs::exists(dir / "missing"));
}
