#pragma once
// A body mesh that passes through itself has no inside where it does: the
// contact pushes cloth out of one sheet into the other, and p (vertices
// inside the body) means nothing there. A scene refuses such a body where the
// garment lies, naming the place, instead of returning a drape and a wrong p.
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <string>

namespace drape::scene_detail {

// Where `target` (a body of the topology of `dressed_on`) intersects itself
// within `reach` of the garment: the faces considered are those within
// `reach` of the garment vertices `garment` on `dressed_on` (the body the
// garment was dressed on, the simulation's own closest-point structure), so
// the check follows the garment through the morph. Empty when the body is
// clear there.
std::string body_overlap_near_garment(const geometry::BodySurface& dressed_on, const Eigen::MatrixX3d& target,
                                      const Eigen::MatrixX3d& garment, double reach);

}  // namespace drape::scene_detail
