#pragma once
// A barrier contact keeps separated surfaces separated; it cannot untangle a
// garment that starts inside or through the body (every state it accepts is
// reached from the start without crossing). So a run with a barrier starts
// only from a garment with no vertex inside the body and no surface crossing
// (geometry::surface_crossings), and says where it fails otherwise.
#include <drape/energy.hpp>
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <string>

namespace drape::scene_detail {

// What keeps the garment x from being separated from the body, naming the
// region (garment_region.hpp): vertices inside (by the body's winding number
// when it is closed and oriented, else by the sign of the distance), or edges
// of either surface through the other. Empty when there is nothing.
std::string separation_problem(const Eigen::MatrixX3d& x, const geometry::BodySurface& body,
                               const Eigen::MatrixX3i& garment_faces);

// Throws ConfigError with separation_problem's words when there is one;
// `morphs`: the run tried start bodies shrunk first (separated_start_body),
// else it has no morph steps and says so.
void check_separated_start(const Eigen::MatrixX3d& x, const geometry::BodySurface& body, const Eigen::MatrixX3i& garment_faces,
                           bool morphs = true);

// A body the garment x is separated from, to start the morph with: `body`
// itself when it is, else `body` shrunk along its vertex normals by the least
// of 0.5, 1, 2, 3, 4, 6 cm that separates them (a garment pushed a few
// centimetres into the body then starts around it). The morph grows the body
// back into the garment, which the barrier handles. A garment whose triangles
// pass through a limb (the T-shirt template's armholes, docs/scenes.md) is
// not separated by any shrink.
// Throws check_separated_start's error for the unshrunk body when none does.
Eigen::MatrixX3d separated_start_body(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body,
                                      const Eigen::MatrixX3i& body_faces, const Eigen::MatrixX3i& garment_faces,
                                      double* shrink = nullptr);

// After a refused start (separated_start_body threw): the vertical
// translation of the garment as placed before dressing (`undressed`, the
// vertices of `garment`), up to 45 cm either way, where it lies closest
// around `body` (separated_start.cpp), said as a hint ("moved about 20 cm
// down, the garment would lie closest around the body and start clear of
// it ...") when it lies there at most half as far from the body and,
// dressed on `body` as a run's start is, starts clear of it. A mesh garment
// modelled for another body or with another floor is refused as crossing;
// this names the offset. Empty otherwise (a garment too small, one through a
// limb, one moved forward or aside).
std::string clear_offset_hint(const Garment& garment, const Eigen::MatrixX3d& undressed, const Eigen::MatrixX3d& body,
                              const Eigen::MatrixX3i& body_faces);

}  // namespace drape::scene_detail
