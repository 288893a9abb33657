#pragma once
// Triangle-triangle intersection and the self-intersections of a mesh.
#include <Eigen/Core>

#include <utility>
#include <vector>

namespace drape::geometry {

// True when the closed triangles (a0, a1, a2) and (b0, b1, b2) share a point.
// Touching counts as intersecting.
bool triangles_intersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                         const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2);

// Pairs of faces (i < j) that intersect, skipping pairs that share a vertex.
// Candidates come from a uniform grid over the faces' bounding boxes, so the
// cost is about linear in the face count. Stops after `max_pairs` pairs.
std::vector<std::pair<int, int>> self_intersections(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                                    std::size_t max_pairs = 100);

}  // namespace drape::geometry
