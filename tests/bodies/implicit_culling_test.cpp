// The parametric body's implicit surface skips the parts a bound proves
// cannot change the union (plugins/bodies/parametric/implicit_body.cpp). With
// DRAPE_BODY_CHECK_CULLING=1 every evaluation is made again with every part
// and any bit of difference is an error: here over both rigs' templates
// meshed afresh (grid nodes deep inside and far outside the body), the
// extreme bodies, and a posed one.
#include <catch2/catch.hpp>

#include <string>

#include "test_support.hpp"

TEST_CASE("parametric body: skipping parts never changes a bit of the implicit surface", "[bodies][implicit]") {
  test::TempDir dir;
  int run = 0;
  for (const std::string args : {"--bmi 24", "--param rig=human --bmi 24", "--bmi 65 --height 2.0 --sex 1",
                                 "--bmi 10 --height 1.5 --sex 0", "--param rig=human --bmi 60 --sex 0",
                                 "--bmi 30 --pose shoulder_abduction=40,elbow_flexion=100,spine_twist=20"}) {
    INFO(args);
    std::string out;
    // An empty cache folder: the template is meshed here, not read back.
    const std::string cache = (dir / ("cache-" + std::to_string(run++))).string();
    CHECK(test::run("env DRAPE_BODY_CHECK_CULLING=1 DRAPE_CACHE_DIR=" + cache + " " + test::drape_program().string() +
                        " body " + args + " --out " + (dir / "b.obj").string(),
                    out) == 0);
    INFO(out);
    CHECK_THAT(out, !Catch::Contains("skipping parts changed"));
  }
}
