// The real-garment case end to end (issue 22): the MakeHuman T-shirt on
// MakeHuman bodies -- simulate to a settled drape with nothing inside and no
// crossing, a small dataset, a small model trained on it, a prediction and an
// optimisation, all through the drape program. Skips with a message when the
// CC0 MakeHuman data (../shared/assets/makehuman) is absent.
#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <drape/io/dataset.hpp>

#include <fstream>

using namespace drape;
namespace fs = std::filesystem;

namespace {

// ../shared/assets/makehuman with the outfit these tests drape, or an empty
// path after saying the test is skipped.
fs::path makehuman_assets_or_skip() {
  const fs::path data_dir = test::shared_assets().empty() ? fs::path() : test::shared_assets() / "makehuman";
  if (!data_dir.empty() && fs::exists(data_dir / "clothes/male_casualsuit04/male_casualsuit04.obj")) return data_dir;
  WARN("SKIPPED: ../shared/assets/makehuman (with clothes/male_casualsuit04) is absent; this test needs it");
  return {};
}

}  // namespace

TEST_CASE("MakeHuman T-shirt: simulate, generate, train, predict and optimise through the program", "[makehuman][cli]") {
  const fs::path data_dir = makehuman_assets_or_skip();
  if (data_dir.empty()) return;
  test::TempDir dir;
  const std::string drape = "env DRAPE_MAKEHUMAN_DIR=" + data_dir.string() + " DRAPE_CACHE_DIR=" + (dir / "cache").string() +
                            " " + test::drape_program().string();
  const std::string scene = (test::source_dir() / "graphs/scenes/makehuman_tshirt.yaml").string();
  std::string out;

  // The shipped scene as it is: a settled drape, nothing inside, nothing crossing.
  REQUIRE(test::run(drape + " simulate " + scene + " --bmi 25 --out " + (dir / "shirt.obj").string(), out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("garment 810 vertices, body 13380 vertices"));
  CHECK_THAT(out, Catch::Contains("settled") && !Catch::Contains("NOT settled"));
  CHECK_THAT(out, Catch::Contains("p = 0.000%") && Catch::Contains("surface crossings 0 garment edges / 0 body edges"));

  // A small dataset in few steps, each cut at 8 Newton iterations (a pipeline check, not good drapes: the
  // generate took 60 s of CPU uncut, 21 s cut), a model, and its use.
  std::ofstream(dir / "fast.yaml") << "base: " << scene << "\nsolver: {morph_steps: 3, settle_steps: 2, max_newton_iterations: 8}\n";
  const std::string data = (dir / "data.h5").string(), model = (dir / "model.h5").string();
  REQUIRE(test::run(drape + " generate " + (dir / "fast.yaml").string() + " --count 5 --bmi 18:36 --seed 1 --out " + data, out) == 0);
  CHECK(DatasetReader(data).indices().size() == 5);
  REQUIRE(test::run(drape + " train " + (test::source_dir() / "graphs/examples/mlp_baseline.yaml").string() + " --data " + data +
                        " --out " + model + " --epochs 2 --batch 2 --k 16 --threads 1",
                    out) == 0);
  CHECK_THAT(out, Catch::Contains("recorded the model's domain"));
  REQUIRE(test::run(drape + " predict --model " + model + " --bmi 25 --out " + (dir / "p.obj").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("810 garment vertices predicted"));
  const int optimized = test::run(drape + " optimize --model " + model + " --scene " + (dir / "fast.yaml").string() +
                                      " --bmi 25 --iters 3 --out " + (dir / "o.obj").string(),
                                  out);
  // A 2-epoch model may not be separated from the body within 3 iterations (exit 1, said so); never a crash.
  CHECK((optimized == 0 || optimized == 1));
  CHECK_THAT(out, Catch::Contains("wrote "));
}

TEST_CASE("a MakeHuman outfit fitted to another body by its sliders is told to keep their defaults", "[makehuman][cli]") {
  // An outside check's gender: 0 (a women's outfit's natural value) was
  // refused as "modelled inside the body; model it around the body model's
  // mean body": the user had modelled nothing, and the slider went unnamed.
  const fs::path data_dir = makehuman_assets_or_skip();
  if (data_dir.empty()) return;
  test::TempDir dir;
  std::ofstream(dir / "gender0.yaml") << "base: " << (test::source_dir() / "graphs/scenes/makehuman_tshirt.yaml").string()
                                      << "\ngarment: {template: makehuman_clothes, params: {outfit: male_casualsuit04, "
                                         "piece: \"0\", gender: 0}}\nmaterials: {knit: gray-interlock}\n";
  std::string out;
  CHECK(test::run("env DRAPE_MAKEHUMAN_DIR=" + data_dir.string() + " " + test::drape_program().string() + " simulate " +
                      (dir / "gender0.yaml").string() + " --bmi 25 --sex 0 --out " + (dir / "g.obj").string(),
                  out) == 2);
  CHECK_THAT(out, Catch::Contains("its parameter gender: 0 (default 1.0) fit it to another body") &&
                      Catch::Contains("keep the default") && !Catch::Contains("model it around"));
}
