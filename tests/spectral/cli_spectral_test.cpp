// `drape spectral` and `drape hierarchy` on a small written garment, and their usage errors.
#include "../hierarchy/sewn_tube.hpp"

#include <fstream>

#include <drape/io/mesh_io.hpp>

#include <catch2/catch.hpp>
#include <test_support.hpp>

using namespace drape;

TEST_CASE("drape spectral prints the error table and drape hierarchy the levels") {
  test::TempDir dir;
  const auto file = dir / "tube.obj";
  write_mesh(file, test::sewn_tube(8, 10));  // 160 vertices
  std::string out;
  const std::string drape = test::drape_program().string();
  REQUIRE(test::run(drape + " spectral --mesh " + file.string() + " --k 4,all", out) == 0);
  CHECK_THAT(out, Catch::Contains("160 vertices"));
  CHECK_THAT(out, Catch::Contains("dense solver"));
  CHECK_THAT(out, Catch::Contains("     160        0.000        0.000"));
  REQUIRE(test::run(drape + " hierarchy --mesh " + file.string() + " --out " + (dir / "levels").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("    1        40"));
  CHECK(std::filesystem::exists(dir / "levels" / "level3.obj"));
  CHECK_THAT(out, !Catch::Contains("note: levels"));
  // Levels past where the mesh stops coarsening are said, not printed as ratio 1.00 without a word.
  REQUIRE(test::run(drape + " hierarchy --mesh " + file.string() + " --levels 9", out) == 0);
  CHECK_THAT(out, Catch::Contains("the mesh coarsens no further"));
  // An --out that is a file: refused before the work, exit 2.
  std::ofstream(dir / "afile.txt") << "x";
  CHECK(test::run(drape + " hierarchy --mesh " + file.string() + " --out " + (dir / "afile.txt").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("is a file, not a folder"));

  CHECK(test::run(drape + " spectral --mesh " + file.string() + " --k 4,x", out) == 2);
  CHECK_THAT(out, Catch::Contains("'x' is not a positive integer"));
  CHECK(test::run(drape + " spectral --mesh " + (dir / "missing.obj").string(), out) == 2);
  CHECK(test::run(drape + " spectral --mesh " + file.string() + " --operator heat", out) == 2);
}
