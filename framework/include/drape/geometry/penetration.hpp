#pragma once
// How much of a garment is inside the body: the seed's penetration metric p.
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

namespace drape::geometry {

// The fraction (in [0, 1]) of garment vertices whose signed distance to the
// body is below -tolerance, i.e. deeper inside than `tolerance` meters (0:
// every vertex strictly inside counts). Signs follow BodySurface, so the body
// must be a closed, outward-oriented mesh. Throws Error when there are no
// vertices, a vertex is not finite, or the tolerance is negative or not finite.
double penetration_ratio(const BodySurface& body, const Eigen::MatrixX3d& garment_vertices, double tolerance = 0);

}  // namespace drape::geometry
