#pragma once
// Which side of a closed surface a point is on, when the surface may pass
// through itself. A body shrunk along its normals to separate a garment from
// it (the barrier's start, scene/separated_start.cpp) turns thin parts inside
// out, and there the closest face's pseudo-normal, which BodySurface's signed
// distance trusts, points the wrong way: points outside the shrunk body were
// reported 5-10 cm inside it. The winding number counts how often the surface
// wraps the point, and does not care.
#include <Eigen/Core>

#include <vector>

namespace drape::geometry {

// The winding number of a closed, consistently oriented triangle mesh
// (counter-clockwise seen from outside) around each point: 1 inside, 0
// outside, 2 where two closed parts overlap, -1 inside a part turned inside
// out. Counted exactly as the signed crossings of a ray from the point
// (orientation signs in exact arithmetic); a ray that meets an edge or a
// vertex, or lies in a face's plane, is cast again in another direction. A
// point on the surface itself gets kOnSurface. Throws Error when a face index
// is out of range or a coordinate is not finite.
constexpr int kOnSurface = 1 << 20;
std::vector<int> winding_numbers(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& vertices,
                                 const Eigen::MatrixX3i& faces);

}  // namespace drape::geometry
