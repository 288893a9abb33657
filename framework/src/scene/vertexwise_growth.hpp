#pragma once
// A barrier's body that starts shrunk (separated_start.hpp) must grow back to
// its true shape without passing through the garment. One collision check of
// the whole body's move gives one fraction for every vertex, so the single
// closest pair (an armpit) holds the whole body back at its pace, and the
// cloth elsewhere is not reached and pushed out until that pair is cleared.
// This moves each body vertex on its own instead, as far as the continuous
// collision checks of the pairs it belongs to allow: far from the cloth the
// body is back at once, and every close region grows at the pace of its own
// gap, so the barrier pushes the cloth out everywhere at the same time.
#include <drape/energy.hpp>
#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::scene_detail {

// Grows one body back around one garment; the two meshes' faces and edges are
// found once, the positions change at every call.
class VertexwiseGrowth {
 public:
  VertexwiseGrowth(const Eigen::MatrixX3i& body_faces, const Eigen::MatrixX3i& garment_faces);

  // `now` moved towards `target` (the body's vertices), the garment x standing
  // still. Each contact pair (garment vertex - body face, body vertex -
  // garment face, garment edge - body edge) whose boxes, swept by the whole
  // move, meet is checked by CCD (geometry/ccd.hpp) with the whole move, and
  // every body vertex of the pair may go at most the pair's fraction of its
  // own way; a vertex in no such pair goes all the way. Corners of one face
  // that go different fractions follow a path the pairs' checks did not see,
  // so the caller confirms the returned move with its contact's own check
  // (Energy::max_step) before taking it.
  // `min_separation`: the share of a pair's gap the checks keep (the barrier's).
  // `floor`: no pair closes below this distance (m) while its body vertices
  // have farther than it still to go, so that a region's gap is not squeezed
  // to nothing over many calls before the cloth has been pushed away; near the
  // end of the way (less than `floor` left) only min_separation holds.
  Eigen::MatrixX3d step(const Eigen::MatrixX3d& now, const Eigen::MatrixX3d& target, const Eigen::MatrixX3d& x,
                        double floor, double min_separation = 0.1) const;

 private:
  Eigen::MatrixX3i body_faces_, garment_faces_;
  std::vector<std::array<int, 2>> body_edges_, garment_edges_;
};

}  // namespace drape::scene_detail
