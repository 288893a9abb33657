// A piece of the garment that slid down the body is said (scene_detail::
// pieces_slid_down): an outside check's two-piece outfit "settled" with its
// skirt 34 cm below the soles and its vest in place, without a word, since
// the garment as a whole had not fallen below the soles.
#include <catch2/catch.hpp>

#include <Eigen/Core>

#include "../../framework/src/scene/unsettled.hpp"

using namespace drape;

namespace {

// A body: two points, its soles at y = 0 and its top at `height`.
Eigen::MatrixX3d body(double height) {
  Eigen::MatrixX3d b(2, 3);
  b << 0, 0, 0, 0, height, 0;
  return b;
}

}  // namespace

TEST_CASE("a piece that slid down the body is named with how far and one that stayed or grew with the body is not",
          "[physics][unsettled]") {
  // Two pieces of one triangle each: a vest at 1.3 m, a skirt at 0.9 m, on a body 1.75 m tall.
  Eigen::MatrixX3d start(6, 3);
  start << 0, 1.3, 0, 0.1, 1.3, 0, 0, 1.4, 0,  //
      0, 0.9, 0, 0.1, 0.9, 0, 0, 1.0, 0;
  Eigen::MatrixX3i faces(2, 3);
  faces << 0, 1, 2, 3, 4, 5;
  const Eigen::MatrixX3d standing = body(1.75);
  CHECK(scene_detail::pieces_slid_down(start, standing, start, standing, faces).empty());
  // The skirt 0.75 m down: piece 2 of 2, its vertices, the distance.
  Eigen::MatrixX3d slid = start;
  slid.bottomRows(3).col(1).array() -= 0.75;
  const std::string why = scene_detail::pieces_slid_down(start, standing, slid, standing, faces);
  CHECK_THAT(why, Catch::StartsWith("piece 2 of 2 (vertices 3-5) slid 0.75 m down the body"));
  CHECK_THAT(why, !Catch::Contains("piece 1"));
  // A few centimetres (a drape settling) are nothing to say.
  Eigen::MatrixX3d settled = start;
  settled.col(1).array() -= 0.04;
  CHECK(scene_detail::pieces_slid_down(start, standing, settled, standing, faces).empty());
  // A body that grows in the morph (1.5 m to 2.0 m) carries the garment up and down with it: heights are shares of it.
  const Eigen::MatrixX3d grown = body(2.0);
  Eigen::MatrixX3d carried = start * (2.0 / 1.75);
  CHECK(scene_detail::pieces_slid_down(start, standing, carried, grown, faces).empty());
  // One piece alone is "the garment".
  Eigen::MatrixX3i one(1, 3);
  one << 0, 1, 2;
  Eigen::MatrixX3d single = start.topRows(3), down = single;
  down.col(1).array() -= 0.6;
  CHECK_THAT(scene_detail::pieces_slid_down(single, standing, down, standing, one), Catch::StartsWith("the garment (vertices 0-2) slid 0.60 m"));
}

TEST_CASE("a garment that slid is told of more friction when its scene has some", "[physics]") {
  // An outside check's scene set friction 0.3 and was told of "the barrier's `friction`, 0 by default".
  Eigen::MatrixX3d standing(2, 3), start(3, 3), down(3, 3);
  standing << 0, 0, 0, 0, 1.7, 0;
  start << 0, 1.0, 0, 0.1, 1.0, 0, 0, 1.1, 0;
  down << 0, 0.4, 0, 0.1, 0.4, 0, 0, 0.5, 0;
  Eigen::MatrixX3i one(1, 3);
  one << 0, 1, 2;
  CHECK_THAT(scene_detail::pieces_slid_down(start, standing, down, standing, one), Catch::Contains("0 by default"));
  CHECK_THAT(scene_detail::pieces_slid_down(start, standing, down, standing, one, true),
             Catch::Contains("more friction than the scene's") && !Catch::Contains("0 by default"));
}
