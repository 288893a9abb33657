// One writer per output (issue 58), checked by scripts/two_writers.sh (20
// rounds for the measurement; 3 here): two flag-free jobs started at the same
// instant (generate, train, optimize, dataset merge), of which exactly one
// may run whatever the timing; and, with the lock held from outside, every
// command refused whatever its flags (--force, --resume).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

TEST_CASE("two writers on one output: one runs, the other is refused", "[cli][lock]") {
  test::TempDir dir;
  std::string out;
  const int code = test::run("cd " + test::source_dir().string() + " && env -u DRAPE_MODEL DRAPE=" +
                                 test::drape_program().string() + " TMPDIR=" + dir.path().string() +
                                 " bash scripts/two_writers.sh 3",
                             out);
  // Only the script's verdict lines: the jobs' own output stays in its logs.
  std::istringstream lines(out);
  std::string verdicts;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("race ", 0) == 0 || line.rfind("held ", 0) == 0 || line.rfind("round ", 0) == 0)
      verdicts += line.substr(0, 300) + "\n";
  INFO(verdicts);
  CHECK(code == 0);
  // The script's line per command, its name padded to 10 (printf %-10s).
  for (std::string command : {"generate", "train", "optimize", "merge"}) {
    command.resize(10, ' ');
    CHECK_THAT(verdicts, Catch::Contains("race " + command + " 3 rounds: one ran and one was refused with a valid output 3,"));
  }
  for (const std::string held : {"generate   (none)    refused", "train      --force   refused", "train      --resume  refused",
                                 "optimize   (none)    refused", "merge      --force   refused",
                                 "train      a running train holds its lock, refuses"})
    CHECK_THAT(verdicts, Catch::Contains("held " + held));
}

TEST_CASE("a job stopped by SIGTERM or SIGHUP or SIGPIPE leaves no lock file beside the output it never wrote", "[cli][lock]") {
  // An outside check: an optimisation stopped with Ctrl-C left o.obj.lock
  // (holding "pid N, drape optimize") next to an o.obj that was never
  // written. The kernel dropped the lock; the file now goes too. Another:
  // `drape train ... | head -1` (SIGPIPE) left it, and so would a closed terminal (SIGHUP).
  test::TempDir dir;
  std::string out;
  const std::string job = test::drape_program().string() + " optimize --model " +
                          (test::source_dir() / "models/tshirt-coarse.h5").string() + " --scene " +
                          (test::source_dir() / "graphs/scenes/tshirt_coarse.yaml").string() +
                          " --bmi 30 --iters 1000000 --out " + (dir / "o.obj").string();
  for (const auto& [signal, status] : {std::pair<const char*, int>{"TERM", 143}, {"HUP", 129}, {"PIPE", 141}}) {
    CHECK(test::run("env -u DRAPE_MODEL DRAPE_CACHE_DIR=" + dir.path().string() + " " + job +
                        " > /dev/null 2> " + (dir / "err.txt").string() + " & pid=$!; for i in $(seq 100); do [ -e " + (dir / "o.obj.lock").string() +
                        " ] && break; sleep 0.1; done; sleep 1; kill -" + signal + " $pid; wait $pid; echo \"status $?\"",
                    out) == 0);
    INFO(signal << ": " << out);
    CHECK_THAT(out, Catch::Contains("status " + std::to_string(status)));  // ended by the signal's default action
    CHECK_FALSE(fs::exists(dir / "o.obj.lock"));
    CHECK_FALSE(fs::exists(dir / "o.obj"));
    // And it says why it ended (an experiment stopped so ended with no word: an outside check).
    if (std::string(signal) != "PIPE")
      CHECK_THAT(test::read_file(dir / "err.txt"),
                 Catch::Contains(std::string("drape: stopped by SIG") + signal + ": nothing was written"));  // one body: no resume
  }
}

TEST_CASE("a resumable job stopped by SIGTERM says what it kept is kept", "[cli][lock]") {
  // The single-body optimize above keeps nothing and says so; generate keeps
  // its finished samples in the .partial and a second run goes on.
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::string out;
  const std::string job = test::drape_program().string() + " generate " + (dir / "tiny.yaml").string() +
                          " --count 1000 --seed 1 --threads 1 --out " + (dir / "d.h5").string();
  CHECK(test::run("env DRAPE_CACHE_DIR=" + dir.path().string() + " " + job + " > /dev/null 2> " + (dir / "err.txt").string() +
                      " & pid=$!; for i in $(seq 100); do [ -e " + (dir / "d.h5.lock").string() +
                      " ] && break; sleep 0.1; done; sleep 1; kill -TERM $pid; wait $pid; echo \"status $?\"",
                  out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("status 143"));
  CHECK_THAT(test::read_file(dir / "err.txt"), Catch::Contains("drape: stopped by SIGTERM: what was finished is kept"));
}

TEST_CASE("outputs are checked before any work: a missing folder, an unknown mesh format", "[cli][outputs]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string drape = "env -u DRAPE_MODEL DRAPE_CACHE_DIR=" + dir.path().string() + " " + test::drape_program().string();
  std::string out;
  const std::string missing = (dir / "missing" / "g.obj").string();
  for (const std::string& command :
       {" simulate " + (dir / "tiny.yaml").string() + " --bmi 30 --out " + missing, " predict --bmi 30 --out " + missing,
        " predict --bmi 30 --out " + (dir / "g.obj").string() + " --body-out " + missing, " body --bmi 30 --out " + missing,
        " train graphs/examples/mlp_baseline.yaml --data none.h5 --out " + (dir / "missing" / "m.h5").string(),
        " generate " + (dir / "tiny.yaml").string() + " --count 2 --out " + (dir / "missing" / "d.h5").string(),
        // (--before was refused after the optimisation, its --out written: an outside check.)
        " optimize --scene graphs/scenes/tshirt_coarse.yaml --bmi 30 --iters 1 --out " + (dir / "o.obj").string() +
            " --before " + missing}) {
    INFO(command);
    CHECK(test::run("cd " + test::source_dir().string() + " && " + drape + command, out) == 2);
    INFO(out);
    CHECK_THAT(out, Catch::Contains("folder") && Catch::Contains("does not exist"));
    CHECK_THAT(out, !Catch::Contains("simulating"));  // refused before the work started
  }
  CHECK(test::run(drape + " predict --bmi 30 --out " + (dir / "g.stl").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("unknown mesh format '.stl'") && !Catch::Contains("predicted"));
  CHECK_FALSE(fs::exists(dir / "missing"));
  CHECK_FALSE(fs::exists(dir / "o.obj"));  // optimize's --out not written before its --before was refused
}

TEST_CASE("a job stopped by SIGTERM while it writes its output leaves no temporary of it", "[cli][lock]") {
  // An outside check: a dataset expand stopped by Ctrl-C left its 18 MB temporary until the next write of that
  // output. The signal's handler removes the temporaries being written with the lock.
  test::TempDir dir;
  std::string out;
  const std::string shards = (test::source_dir() / "datasets/bodyspace2000-human/shard-0[0-3]-of-40.h5").string();
  const std::string job = test::drape_program().string() + " dataset expand --out " + (dir / "ex.h5").string() + " " + shards;
  CHECK(test::run(job + " > /dev/null 2>&1 & pid=$!; for i in $(seq 200); do ls -a " + dir.path().string() +
                      " | grep -q '^\\.ex\\.tmp' && break; sleep 0.05; done; kill -TERM $pid; wait $pid; echo \"status $?\"",
                  out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("status 143"));
  for (const auto& e : fs::directory_iterator(dir.path())) CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
  CHECK_FALSE(fs::exists(dir / "ex.h5.lock"));
}
