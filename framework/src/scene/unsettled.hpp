#pragma once
// Why a run did not settle, for SimulationResult::unsettled: the stationarity
// against the tolerance, the region of the largest unbalanced forces, and
// whether the steps had stopped moving (line searches finding no decrease),
// and whether the garment is smaller than the body (`ease`, garment_size.hpp:
// negative when its girth is below the body's; NaN when not measured), or
// whether it fell off the body.
#include <drape/scene/simulation.hpp>

#include <string>

namespace drape::scene_detail {

std::string why_unsettled(const SimulationResult& result, const Eigen::MatrixX3d& x, double tolerance, int settle_steps,
                          double at_rest_limit, double ease, const Eigen::MatrixX3d& body, bool sized,
                          bool has_friction = false);

// The garment has fallen off the body: half of it or more below the body's
// lowest point (a loose tube slides down over the hips and legs: the contact
// has no friction, so only a garment that hangs from the shoulders or grips
// the body stays on it; a skirt that slid to the ankles and hung from the
// feet "settled" with exit 0 while all of it had to be below the soles: an
// outside check). Nothing can bring it back, so the settling stops, and it
// is no drape.
bool fell_off_body(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body);

// A piece of the garment that slid down the body by more than
// kSlidShare of its height from where it was put on (a skirt of a two-piece
// outfit that slid from the hips to the feet "settled" beside a vest that
// stayed, with no word: fell_off_body asks the whole garment to be below
// the soles). Heights are measured from each body's soles, as shares of its
// height, so a body that grows or shrinks in the morph moves nothing. One
// sentence per such piece ("piece 2 of 2 (vertices 1048-2135) slid 0.75 m
// down ..."), "" when none.
inline constexpr double kSlidShare = 0.15;
// has_friction: the scene's contact has friction already, so the advice
// asks for more, not for some (an outside check's scene set 0.3 and was told
// of "the barrier's `friction`, 0 by default").
std::string pieces_slid_down(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& start_body, const Eigen::MatrixX3d& x,
                             const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces, bool has_friction = false);

}  // namespace drape::scene_detail
