#pragma once
// Why a run did not settle, for SimulationResult::unsettled: the stationarity
// against the tolerance, the region of the largest unbalanced forces, and
// whether the steps had stopped moving (line searches finding no decrease),
// and whether the garment is smaller than the body (`ease`, garment_size.hpp:
// negative when its girth is below the body's; NaN when not measured).
#include <drape/simulation.hpp>

#include <string>

namespace drape::scene_detail {

std::string why_unsettled(const SimulationResult& result, const Eigen::MatrixX3d& x, double tolerance, int settle_steps,
                          double at_rest_limit, double ease);

}  // namespace drape::scene_detail
