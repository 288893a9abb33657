// Two garment sizes in one model (seed Table 6.7): datasets of the small and
// the regular shirt record garment_size, merge with --mixed-sizes (and only
// with it), a graph with the size flag trains on the union, and eval, predict
// and optimize feed the flag.
#include <catch2/catch.hpp>

#include <drape/dataset.hpp>

#include <fstream>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

std::string tiny_scene(const char* size) {
  return std::string("body: {model: parametric}\ngarment: {template: tshirt, params: {resolution: 300, size: ") + size +
         "}}\neffects: [gravity, stretching, bending, collision]\nsolver: {morph_steps: 2, settle_steps: 2}\n";
}

}  // namespace

TEST_CASE("two garment sizes: merge, train with the size flag, evaluate and predict each size", "[sizes]") {
  test::TempDir dir;
  std::ofstream(dir / "regular.yaml") << tiny_scene("regular");
  std::ofstream(dir / "small.yaml") << tiny_scene("small");
  const std::string drape = test::drape_program().string() + " ";
  std::string out;
  for (const char* size : {"regular", "small"})
    REQUIRE(test::run(drape + "generate " + (dir / (std::string(size) + ".yaml")).string() +
                          " --count 10 --bmi 15:40 --seed 5 --out " + (dir / (std::string(size) + ".h5")).string(),
                      out) == 0);
  CHECK(DatasetReader(dir / "small.h5").stat("garment_size", {0})[0] == 1.0);
  CHECK(DatasetReader(dir / "regular.h5").stat("garment_size", {0})[0] == 0.0);
  CHECK(DatasetReader(dir / "small.h5").layout().template_hash != DatasetReader(dir / "regular.h5").layout().template_hash);

  const std::string parts = " " + (dir / "regular.h5").string() + " " + (dir / "small.h5").string();
  CHECK(test::run(drape + "dataset merge --out " + (dir / "refused.h5").string() + parts, out) == 2);
  CHECK_THAT(out, Catch::Contains("template"));
  REQUIRE(test::run(drape + "dataset merge --mixed-sizes --out " + (dir / "both.h5").string() + parts, out) == 0);
  const DatasetReader both(dir / "both.h5");
  CHECK(both.size() == 20);
  CHECK(both.layout().template_hash == DatasetReader(dir / "regular.h5").layout().template_hash);
  CHECK(both.layout().attributes.at("templates").find(',') != std::string::npos);

  const std::string graph = (test::source_dir() / "graphs/sizes/drape_size_flag.yaml").string();
  REQUIRE(test::run(drape + "train " + graph + " --data " + (dir / "both.h5").string() + " --out " +
                        (dir / "m.h5").string() + " --epochs 1 --k 16 -q",
                    out) == 0);
  // The flag comes from the data: a set without garment_size cannot feed it.
  CHECK(test::run(drape + "train " + graph + " --data " + (dir / "missing.h5").string() + " --out " +
                      (dir / "x.h5").string() + " --epochs 1 -q",
                  out) != 0);
  std::string small, regular;
  REQUIRE(test::run(drape + "eval --model " + (dir / "m.h5").string() + " --data " + (dir / "both.h5").string() +
                        " --split all --where garment_size=1",
                    small) == 0);
  CHECK_THAT(small, Catch::Contains("(10 samples)"));
  REQUIRE(test::run(drape + "eval --model " + (dir / "m.h5").string() + " --data " + (dir / "both.h5").string() +
                        " --split all --where garment_size=0",
                    regular) == 0);
  CHECK_THAT(regular, Catch::Contains("(10 samples)"));
  CHECK(test::run(drape + "eval --model " + (dir / "m.h5").string() + " --data " + (dir / "both.h5").string() +
                      " --where garment_size",
                  out) == 2);

  // Predicting needs the size; the two sizes give two different garments.
  CHECK(test::run(drape + "predict --model " + (dir / "m.h5").string() + " --bmi 30 --out " + (dir / "g.obj").string(), out) != 0);
  CHECK_THAT(out, Catch::Contains("--garment-size"));
  REQUIRE(test::run(drape + "predict --model " + (dir / "m.h5").string() + " --bmi 30 --garment-size small --out " +
                        (dir / "s.obj").string(),
                    out) == 0);
  REQUIRE(test::run(drape + "predict --model " + (dir / "m.h5").string() + " --bmi 30 --garment-size regular --out " +
                        (dir / "r.obj").string(),
                    out) == 0);
  std::ifstream s(dir / "s.obj"), r(dir / "r.obj");
  const std::string s_text((std::istreambuf_iterator<char>(s)), {}), r_text((std::istreambuf_iterator<char>(r)), {});
  CHECK(s_text != r_text);
}
