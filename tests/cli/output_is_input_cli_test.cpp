// A job whose output is one of its inputs is refused before any work, and
// the input is left as it was (found by a sweep of long jobs, 2026-12-06):
// dataset unpose and resample with --force deleted their input before
// reading it, train --data X --out X --force wrote a model over the dataset
// after an epoch, and model domain/set turned a dataset into a model file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("a job writing over its own input is refused, and the input kept", "[cli][data]") {
  test::TempDir dir;
  std::string out;
  const fs::path data = dir / "d.h5";
  fs::copy_file(test::source_dir() / "datasets/bodyspace2000/shard-00-of-40.h5", data);
  const std::string before = bytes_of(data);
  const std::string src = test::source_dir().string();
  const std::string same = (dir / "." / "d.h5").string();  // the same file by another path
  const std::vector<std::string> commands = {
      "dataset unpose " + data.string() + " --out " + same + " --force",
      "dataset resample " + data.string() + " --onto " + src + "/graphs/scenes/tshirt_coarse_human.yaml --out " + same +
          " --force",
      "train " + src + "/graphs/examples/mlp_baseline.yaml --data " + data.string() + " --out " + same +
          " --epochs 1 --force",
      "model domain " + src + "/models/tshirt-coarse.h5 --data " + data.string() + " --out " + same,
      "optimize --scene " + src + "/graphs/scenes/tshirt_coarse.yaml --data " + data.string() + " --iters 1 --out " + same};
  for (const std::string& command : commands) {
    INFO(command);
    CHECK(test::run_drape(command, out) == 2);
    CHECK_THAT(out, Catch::Contains("is also an input") && Catch::Contains("write over what it reads"));
    REQUIRE(fs::exists(data));
    CHECK(bytes_of(data) == before);
  }
  // model set replaces a model in place, never a dataset.
  CHECK(test::run_drape("model set " + src + "/models/tshirt-coarse.h5 --set post.enabled=true --out " + data.string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("exists and is not a drape model"));
  CHECK(bytes_of(data) == before);
  // A dataset given as MODEL without --out is named as MODEL (it was "--out", an option not given).
  CHECK(test::run_drape("model set " + data.string() + " --set post.enabled=true", out) == 2);
  CHECK_THAT(out, Catch::Contains("MODEL (replaced without --out) " + data.string()) && !Catch::Contains("--out " + data.string()));
  CHECK(bytes_of(data) == before);
  // In place on a model (its copy), as before.
  fs::copy_file(test::source_dir() / "models/tshirt-coarse.h5", dir / "m.h5");
  CHECK(test::run_drape("model set " + (dir / "m.h5").string() + " --set post.enabled=true", out) == 0);
}

TEST_CASE("a mesh or pose output naming the input file is refused, and an empty path is named", "[cli]") {
  // An outside check: predict --body b.obj --out b.obj wrote the garment over
  // the user's body, and body --unpose's --pose-out replaced its own mesh.
  test::TempDir dir;
  std::string out;
  const std::string body = (dir / "b.obj").string(), posed = (dir / "p.obj").string();
  REQUIRE(test::run_drape("body --bmi 30 --out " + body, out) == 0);
  REQUIRE(test::run_drape("body --param rig=human --bmi 30 --pose shoulder_abduction=60 --out " + posed, out) == 0);
  const std::string body_bytes = bytes_of(body), posed_bytes = bytes_of(posed);
  CHECK(test::run_drape("predict --model " + (test::source_dir() / "models/tshirt-coarse.h5").string() + " --body " +
                            body + " --out " + (dir / "." / "b.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--out") && Catch::Contains("is also an input (--body"));
  CHECK(bytes_of(body) == body_bytes);
  CHECK(test::run_drape("body --param rig=human --unpose " + posed + " --out " + (dir / "r.obj").string() +
                            " --pose-out " + posed, out) == 2);
  CHECK_THAT(out, Catch::Contains("--pose-out") && Catch::Contains("is also an input (--unpose"));
  CHECK(bytes_of(posed) == posed_bytes);
  CHECK_FALSE(fs::exists(dir / "r.obj"));
  // Two outputs alike, as predict's --out and --body-out were already.
  CHECK(test::run_drape("body --param rig=human --unpose " + posed + " --out " + (dir / "r.obj").string() +
                            " --pose-out " + (dir / "r.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--out and --pose-out name the same file"));
  // A path given empty (a shell variable never set): exit 2, named, not a filesystem error.
  for (const std::string command : {"body --bmi 30 --out ''", "predict --bmi 30 --out ''", "body --sample 2 --out-dir ''"}) {
    INFO(command);
    CHECK(test::run_drape(command, out) == 2);
    CHECK_THAT(out, Catch::Contains("is empty (a shell variable never set?)"));
  }
}
