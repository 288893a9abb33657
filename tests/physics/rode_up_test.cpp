// garment_rode_up: a note when a draped garment spans less than half the
// height it was modelled with (drape simulate prints it, Python warns it).
#include <drape/scene/rode_up.hpp>

#include <catch2/catch.hpp>

using namespace drape;

TEST_CASE("a garment that rode up into a band is noted with its heights", "[physics][fit]") {
  // A modelled garment 0.70 m tall, from y = 0.82 to 1.52 (the coarse tee).
  Eigen::MatrixX3d modelled(3, 3);
  modelled << 0.0, 0.82, 0.1, 0.2, 1.52, 0.0, -0.2, 1.2, 0.0;
  // Hanging as designed, or a crop top of 0.36 m (over half): nothing.
  Eigen::MatrixX3d draped = modelled;
  CHECK(garment_rode_up(modelled, draped).empty());
  draped.col(1) << 1.16, 1.52, 1.3;
  CHECK(garment_rode_up(modelled, draped).empty());
  // A band of 0.23 m round the chest (an outside check's too-small tee): 33 % of 0.70.
  draped.col(1) << 1.28, 1.51, 1.4;
  const std::string note = garment_rode_up(modelled, draped);
  CHECK(note == "the garment rode up: it spans 0.23 m from top to bottom, 33 % of the 0.70 m it was modelled with; it is "
                "too small round this body to hang as designed (the fit note says how much)");
  // Nothing to say of an empty garment or a flat one.
  CHECK(garment_rode_up(Eigen::MatrixX3d(0, 3), draped).empty());
  Eigen::MatrixX3d flat = modelled;
  flat.col(1).setConstant(1.0);
  CHECK(garment_rode_up(flat, draped).empty());
}
