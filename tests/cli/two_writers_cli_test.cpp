// Two jobs started at the same instant on one output: one runs, the other is
// refused (exit 2) whatever its flags, and the output is valid (issue 58).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

struct Outcome {
  int first = -1, second = -1;
  std::string first_log, second_log;
};

// Starts both commands in the background, held at a barrier (a file both
// wait for), releases them together and waits for both.
Outcome race(const fs::path& dir, const std::string& first, const std::string& second, int round) {
  const std::string tag = std::to_string(round);
  const fs::path go = dir / ("go" + tag);
  auto job = [&](const std::string& command, const std::string& name) {
    const fs::path log = dir / (name + tag + ".log"), rc = dir / (name + tag + ".rc");
    return "(while [ ! -e " + go.string() + " ]; do :; done; " + command + " > " + log.string() + " 2>&1; echo $? > " +
           rc.string() + ") &";
  };
  std::string out;
  test::run(job(first, "a") + " " + job(second, "b") + " sleep 0.3; touch " + go.string() + "; wait", out);
  Outcome o;
  std::ifstream(dir / ("a" + tag + ".rc")) >> o.first;
  std::ifstream(dir / ("b" + tag + ".rc")) >> o.second;
  auto read = [](const fs::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  };
  o.first_log = read(dir / ("a" + tag + ".log"));
  o.second_log = read(dir / ("b" + tag + ".log"));
  return o;
}

void check_one_ran(const Outcome& o) {
  INFO("first (" << o.first << "):\n" << o.first_log << "\nsecond (" << o.second << "):\n" << o.second_log);
  CHECK(((o.first == 0 && o.second == 2) || (o.first == 2 && o.second == 0)));
  const std::string& refused = o.first == 2 ? o.first_log : o.second_log;
  // Refused while the other runs, or after it ended (the output then exists).
  CHECK_THAT(refused, Catch::Contains("is in use") || Catch::Contains("exists"));
  CHECK_THAT(refused, !Catch::Contains("corrupt"));
}

}  // namespace

TEST_CASE("train, optimize and dataset merge started twice at once on one output: one runs, one is refused", "[cli][lock]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string drape = "env -u DRAPE_MODEL DRAPE_CACHE_DIR=" + dir.path().string() + " " + test::drape_program().string();
  std::string out;
  REQUIRE(test::run(drape + " generate " + (dir / "tiny.yaml").string() + " --count 6 --bmi 15:30 --seed 3 --shard 0/2 --out " +
                        (dir / "s0.h5").string(),
                    out) == 0);
  REQUIRE(test::run(drape + " generate " + (dir / "tiny.yaml").string() + " --count 6 --bmi 15:30 --seed 3 --shard 1/2 --out " +
                        (dir / "s1.h5").string(),
                    out) == 0);
  REQUIRE(test::run(drape + " dataset merge --out " + (dir / "d.h5").string() + " " + (dir / "s0.h5").string() + " " +
                        (dir / "s1.h5").string(),
                    out) == 0);
  for (int round = 0; round < 3; ++round) {
    const fs::path model = dir / ("m" + std::to_string(round) + ".h5");
    const std::string train = drape + " train " + (test::source_dir() / "graphs/examples/mlp_baseline.yaml").string() +
                              " --data " + (dir / "d.h5").string() + " --epochs 3 --threads 1 -q --out " + model.string();
    // The second with --force: the flag that would have rewritten a running job's file.
    check_one_ran(race(dir.path(), train, train + " --force", round));
    CHECK(test::run(drape + " model info " + model.string(), out) == 0);
    CHECK_FALSE(fs::exists(model.string() + ".lock"));

    const fs::path merged = dir / ("merged" + std::to_string(round) + ".h5");
    const std::string merge = drape + " dataset merge --out " + merged.string() + " " + (dir / "s0.h5").string() + " " +
                              (dir / "s1.h5").string();
    check_one_ran(race(dir.path(), merge, merge, 10 + round));
    CHECK(test::run(drape + " dataset info " + merged.string(), out) == 0);
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
