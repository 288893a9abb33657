// `drape generate --girths`: drapes over the varied body space (docs/bodies.md),
// every shape parameter stored; without girths a seed draws the bodies it did.
#include <catch2/catch.hpp>

#include <drape/io/dataset.hpp>

#include <fstream>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

TEST_CASE("drape generate draws sex, height and girths and stores every shape parameter", "[cli][generate]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string generate = test::drape_program().string() + " generate " + (dir / "tiny.yaml").string() +
                               " --count 4 --bmi 15:40 --seed 6 --threads 1 ";
  std::string out;
  REQUIRE(test::run(generate + "--height 1.5:2.0 --sex 0:1 --girths 1 --out " + (dir / "varied.h5").string(), out) == 0);
  INFO(out);
  REQUIRE(test::run(generate + "--out " + (dir / "plain.h5").string(), out) == 0);
  const DatasetReader varied(dir / "varied.h5"), plain(dir / "plain.h5");
  const auto idx = varied.indices();
  REQUIRE(idx.size() == 4);
  // The parametric body's shape: height, sex, weight, then the six girths.
  const Tensor p = varied.body_params(idx), q = plain.body_params(idx);
  const Tensor bodies = varied.body_vertices(idx);
  const std::vector<double> heights = varied.stat("height", idx), sexes = varied.stat("sex", idx);
  bool some_girth = false, some_height = false;
  for (int i = 0; i < 4; ++i) {
    for (int g = 3; g < 9; ++g) {
      CHECK(std::abs(p(i, 0, g)) <= 0.15f);
      some_girth = some_girth || p(i, 0, g) != 0.0f;
      CHECK(q(i, 0, g) == 0.0f);  // no --girths: the mean build
    }
    CHECK((sexes[static_cast<std::size_t>(i)] == 0.0 || sexes[static_cast<std::size_t>(i)] == 1.0));
    CHECK(heights[static_cast<std::size_t>(i)] >= 1.5);
    CHECK(heights[static_cast<std::size_t>(i)] < 2.0);
    some_height = some_height || std::abs(heights[static_cast<std::size_t>(i)] - 1.75) > 0.01;
    // The stored body is as tall as its parameters say.
    const auto y = bodies.mat(i).col(1);
    CHECK(y.maxCoeff() - y.minCoeff() == Approx(p(i, 0, 0)).margin(1e-4));
    CHECK(q(i, 0, 0) == Approx(1.75f));
  }
  CHECK(some_girth);
  CHECK(some_height);
}
