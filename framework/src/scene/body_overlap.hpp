#pragma once
// A body mesh that passes through itself has no inside where it does: the
// contact pushes cloth out of one sheet into the other, and p (vertices
// inside the body) means nothing there. A scene refuses such a body where the
// garment lies, naming the place, instead of returning a drape and a wrong p.
#include <Eigen/Core>

#include <string>

namespace drape::scene_detail {

// Where `target` (a body of the scene's topology `faces`) intersects itself
// within `reach` of the garment: the faces considered are those within
// `reach` of the garment vertices `garment` on `start` (the body the garment
// was dressed on, same topology), so the check follows the garment through
// the morph. Empty when the body is clear there.
std::string body_overlap_near_garment(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& target,
                                      const Eigen::MatrixX3i& faces, const Eigen::MatrixX3d& garment, double reach);

}  // namespace drape::scene_detail
