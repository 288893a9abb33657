// `drape generate`: determinism per sample (independent of threads and
// shards), shards that merge into the whole set, and resuming after SIGKILL
// without losing or duplicating a sample.
#include <catch2/catch.hpp>

#include <drape/io/dataset.hpp>

#include <chrono>
#include <cstdio>
#include <csignal>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

std::string generate(const fs::path& scene, const std::string& args) {
  return test::drape_program().string() + " generate " + scene.string() + " --bmi 15:50 --seed 4 " + args;
}

Tensor garments(const fs::path& file) {
  DatasetReader r(file);
  return r.garment_vertices(r.indices());
}

// Per sample of two sets of the same bodies: the largest vertex difference and
// each side's solver record, so that a mismatch says which sample differs and
// whether its solve took another path (iterations, settling) or only rounded
// differently.
std::string sample_differences(const fs::path& a_file, const fs::path& b_file) {
  const DatasetReader a(a_file), b(b_file);
  std::ostringstream o;
  const auto ia = a.indices(), ib = b.indices();
  for (std::size_t k = 0; k < std::min(ia.size(), ib.size()); ++k) {
    const Tensor ga = a.garment_vertices({ia[k]}), gb = b.garment_vertices({ib[k]});
    o << "sample " << k << ": max |diff| " << (ga.flat() - gb.flat()).cwiseAbs().maxCoeff();
    for (const char* stat : {"bmi", "iterations", "steps", "converged", "stationarity"})
      o << ", " << stat << " " << a.stat(stat, {ia[k]})[0] << " vs " << b.stat(stat, {ib[k]})[0];
    o << "\n";
  }
  return o.str();
}

}  // namespace

TEST_CASE("generate writes every sample once, with stats and the 8:1:1 split, and never overwrites", "[generate]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::string out;
  REQUIRE(test::run(generate(dir / "tiny.yaml", "--count 10 --threads 2 --out " + (dir / "a.h5").string()), out) == 0);
  INFO(out);
  const DatasetReader r(dir / "a.h5");
  CHECK(r.size() == 10);
  CHECK(r.indices().size() == 10);
  CHECK(r.indices(Split::Train).size() == 8);
  CHECK(r.indices(Split::Val).size() == 1);
  CHECK(r.indices(Split::Test).size() == 1);
  CHECK(r.layout().scene.find("stretching") != std::string::npos);
  for (const char* stat : {"energy_gravity", "energy_stretching", "energy_collision", "penetration", "iterations", "bmi"})
    for (double v : r.stat(stat, r.indices())) CHECK(std::isfinite(v));
  for (double bmi : r.stat("bmi", r.indices())) CHECK((bmi >= 15 && bmi <= 50));
  CHECK(garments(dir / "a.h5").flat().allFinite());
  // A finished dataset is never overwritten. The same job again (a job array's retry) has nothing to do and
  // succeeds, without touching it; another job is refused, naming the difference.
  const auto written = fs::last_write_time(dir / "a.h5");
  CHECK(test::run(generate(dir / "tiny.yaml", "--count 10 --threads 2 --out " + (dir / "a.h5").string()), out) == 0);
  CHECK_THAT(out, Catch::Contains("nothing to do") && Catch::Contains("finished (10 samples)"));
  CHECK(fs::last_write_time(dir / "a.h5") == written);
  CHECK(test::run(test::drape_program().string() + " generate " + (dir / "tiny.yaml").string() +
                      " --bmi 15:40 --seed 4 --count 10 --out " + (dir / "a.h5").string(),
                  out) == 2);
  CHECK_THAT(out, Catch::Contains("already exists, a finished dataset made otherwise") && Catch::Contains("bmi 15:40"));
  CHECK(test::run(generate(dir / "tiny.yaml", "--count 12 --out " + (dir / "a.h5").string()), out) == 2);
  CHECK_THAT(out, Catch::Contains("made otherwise"));
}

TEST_CASE("shards made separately merge into the same set one job makes", "[generate]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::string out, log;
  REQUIRE(test::run(generate(dir / "tiny.yaml", "--count 4 --threads 1 --out " + (dir / "all.h5").string()), out) == 0);
  log += out;
  for (int s = 0; s < 2; ++s) {
    INFO(log);
    REQUIRE(test::run(generate(dir / "tiny.yaml", "--count 4 --shard " + std::to_string(s) + "/2 --out " +
                                                     (dir / ("s" + std::to_string(s) + ".h5")).string()),
                      out) == 0);
    log += out;
  }
  REQUIRE(test::run(test::drape_program().string() + " dataset merge --out " + (dir / "merged.h5").string() + " " +
                        (dir / "s0.h5").string() + " " + (dir / "s1.h5").string(),
                    out) == 0);
  const Tensor a = garments(dir / "all.h5"), b = garments(dir / "merged.h5");
  REQUIRE(a.flat().size() == b.flat().size());
  const float max_difference = (a.flat() - b.flat()).cwiseAbs().maxCoeff();
  // Read the per-sample record only when it is needed (INFO builds its text at once).
  if (max_difference != 0.0f) UNSCOPED_INFO(log << sample_differences(dir / "all.h5", dir / "merged.h5"));
  CHECK(max_difference == 0.0f);
  CHECK(DatasetReader(dir / "all.h5").splits() == DatasetReader(dir / "merged.h5").splits());
}

// Starts `command` (a generate of `count` samples) in the background and
// kills it (-9) once its progress says `samples` or more are done; how many
// were done by then.
std::size_t start_and_kill_after(const std::string& command, const test::TempDir& dir, std::size_t samples, std::size_t count) {
  std::string out;
  REQUIRE(test::run("(" + command + " > " + (dir / "log").string() + " 2>&1 & echo $! > " + (dir / "pid").string() + ")", out) == 0);
  // The progress lines (one per sample at this size) say how many are done.
  std::size_t done = 0;
  const std::string format = " %zu/" + std::to_string(count);
  for (int k = 0; k < 1200 && done < samples; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::ifstream log(dir / "log");
    std::string line;
    while (std::getline(log, line, ']')) {
      std::size_t n = 0;
      if (std::sscanf(line.c_str(), format.c_str(), &n) == 1) done = std::max(done, n);
    }
  }
  long pid = 0;
  std::ifstream(dir / "pid") >> pid;
  REQUIRE(pid > 0);
  ::kill(static_cast<pid_t>(pid), SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  return done;
}

TEST_CASE("a generate job killed mid-run resumes without losing or duplicating a sample", "[generate]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const fs::path file = dir / "k.h5", partial = dir / "k.h5.partial";
  std::string out;
  // Start in the background, wait until some (not all) samples are done, kill -9.
  const std::string cmd = generate(dir / "tiny.yaml", "--count 8 --threads 1 --out " + file.string());
  REQUIRE(start_and_kill_after(cmd, dir, 3, 8) >= 3);
  REQUIRE_FALSE(fs::exists(file));
  // Resumed with another seed or body range, it filled the missing rows with
  // other drapes while the file recorded the first run's: refused, the partial kept.
  const std::string scene = (dir / "tiny.yaml").string(), rest = " --count 8 --threads 1 --out " + file.string();
  for (const std::string other : {" --bmi 15:50 --seed 9", " --bmi 20:30 --seed 4", " --bmi 15:50 --seed 4 --girths 1"}) {
    INFO(other);
    CHECK(test::run(test::drape_program().string() + " generate " + scene + other + rest, out) == 2);
    CHECK_THAT(out, Catch::Contains("cannot resume, it was begun as") && Catch::Contains("run it as it was begun"));
  }
  REQUIRE(fs::exists(partial));
  // The same command again finishes the job.
  REQUIRE(test::run(cmd, out) == 0);
  CHECK_THAT(out, Catch::Contains("resuming"));
  // An uninterrupted run gives the same samples.
  REQUIRE(test::run(generate(dir / "tiny.yaml", "--count 8 --threads 2 --out " + (dir / "ref.h5").string()), out) == 0);
  const Tensor a = garments(file), b = garments(dir / "ref.h5");
  REQUIRE(a.flat().size() == b.flat().size());
  CHECK((a.flat() - b.flat()).cwiseAbs().maxCoeff() == 0.0f);
  CHECK(DatasetReader(file).indices().size() == 8);
}

TEST_CASE("a resumed generate names the drapes of earlier runs that cross themselves", "[generate]") {
  // The resumed run named only its own (an outside check: "--drop 7" where the uninterrupted run said
  // "--drop 0,3,7"); the earlier runs' are now read back from the file and named with them.
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const auto run_of = [&](const std::string& out_name) {
    return test::drape_program().string() + " generate " + (dir / "tiny.yaml").string() + " --count 8 --threads 1 --out " +
           (dir / out_name).string();
  };
  std::string whole, resumed;
  REQUIRE(test::run(run_of("ref.h5"), whole) == 0);
  const std::regex named("garments crossing themselves: sample ([0-9,]+)");
  std::smatch in_whole, in_resumed;
  REQUIRE(std::regex_search(whole, in_whole, named));  // this scene's seed 0 has some (samples 2 and 3)
  const std::size_t first_crossing = std::stoul(in_whole[1].str());
  const std::size_t done = start_and_kill_after(run_of("k.h5"), dir, first_crossing + 2, 8);
  REQUIRE(done > first_crossing);
  REQUIRE(done < 8);
  REQUIRE(test::run(run_of("k.h5"), resumed) == 0);
  INFO(resumed);
  REQUIRE(std::regex_search(resumed, in_resumed, named));
  CHECK(in_resumed[1].str() == in_whole[1].str());
  CHECK_THAT(resumed, Catch::Contains("drapes of earlier runs, read back from the file"));
}

// The case on a scene that drapes in a second: the barrier contact (as
// every shipped scene), two samples in flight at the kill and started together
// again by the resumed job, which gave drapes up to 5.5 cm off while CHOLMOD's
// orderings ran concurrently. Meanwhile a second job on the same file is told
// the file is in use, never to delete it.
TEST_CASE("a 2-thread generate job killed mid-run resumes to the bits of an uninterrupted run, and a second job is told the file is in use",
          "[generate]") {
  test::TempDir dir;
  std::ofstream(dir / "barrier.yaml") << "body: {model: parametric}\n"
                                         "garment: {template: tshirt, params: {resolution: 300}}\n"
                                         "effects: {gravity: {}, stretching: {}, bending: {}, barrier: {}}\n"
                                         "solver: {morph_steps: 2, settle_steps: 3, max_newton_iterations: 8}\n";
  const fs::path file = dir / "k.h5", partial = dir / "k.h5.partial";
  // Light bodies: two morph steps are too few for the barrier to dress a heavy one.
  const auto job = [&](const std::string& args) {
    return test::drape_program().string() + " generate " + (dir / "barrier.yaml").string() + " --bmi 10:25 --seed 3 " + args;
  };
  // 8 samples (about a second each, the steps cut at 8 Newton iterations: the
  // resume is what is tested, not the drapes): after the first 2, enough left
  // (~3 s) for the second job and the reader to find it busy.
  const std::string cmd = job("--count 8 --threads 2 --out " + file.string());
  std::string out;
  REQUIRE(test::run("(" + cmd + " > " + (dir / "log").string() + " 2>&1 & echo $! > " + (dir / "pid").string() + ")", out) == 0);
  std::size_t done_at_kill = 0;
  for (int k = 0; k < 1200 && done_at_kill < 2; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::ifstream log(dir / "log");
    std::string line;
    while (std::getline(log, line, ']')) {
      std::size_t n = 0;
      if (std::sscanf(line.c_str(), " %zu/8", &n) == 1) done_at_kill = std::max(done_at_kill, n);
    }
  }
  // While it writes: a second job, and a reader, on the same file.
  std::string second, reader;
  const int second_code = test::run(cmd, second), reader_code = test::run(test::drape_program().string() + " dataset info " + partial.string(), reader);
  long pid = 0;
  std::ifstream(dir / "pid") >> pid;
  REQUIRE(pid > 0);
  ::kill(static_cast<pid_t>(pid), SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  REQUIRE(done_at_kill >= 2);
  REQUIRE_FALSE(fs::exists(file));
  INFO(second << reader);
  CHECK(second_code == 2);
  CHECK(reader_code == 2);
  CHECK_THAT(second, Catch::Contains("is in use") && !Catch::Contains("delete") && !Catch::Contains("corrupt"));
  CHECK_THAT(reader, Catch::Contains("is in use") && !Catch::Contains("delete") && !Catch::Contains("corrupt"));

  REQUIRE(test::run(cmd, out) == 0);
  CHECK_THAT(out, Catch::Contains("resuming"));
  REQUIRE(test::run(job("--count 8 --threads 2 --out " + (dir / "ref.h5").string()), out) == 0);
  INFO(sample_differences(file, dir / "ref.h5"));
  const DatasetReader a(file), b(dir / "ref.h5");
  REQUIRE(a.indices().size() == 8);
  const Tensor ga = a.garment_vertices(a.indices()), gb = b.garment_vertices(b.indices());
  CHECK((ga.flat() - gb.flat()).cwiseAbs().maxCoeff() == 0.0f);
  for (const char* stat : {"energy_total", "iterations", "stationarity", "bmi"})
    CHECK(a.stat(stat, a.indices()) == b.stat(stat, b.indices()));
}
