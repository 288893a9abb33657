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

// The bound a count of a garment's crossings of itself is taken to (predict,
// render, optimize, dressing): far above any drape's, so a count is a count.
inline constexpr std::size_t kCrossingsCountedAtMost = 100000;

// (edge, face) pairs where an edge of the mesh (its two vertex indices, each
// undirected edge once) passes through one of its faces that shares no vertex
// with the edge (segment_pierces_triangle, surface_crossings.hpp: touching
// counts). Unlike self_intersections this sees a fold of one edge's size: an
// edge through a face that shares a vertex with the edge's own faces. The
// count scripts/count_self_crossings.py makes (it leaves touching out).
// Stops after `max_pairs` pairs.
std::vector<std::pair<std::pair<int, int>, int>> self_edge_crossings(const Eigen::MatrixX3d& vertices,
                                                                     const Eigen::MatrixX3i& faces,
                                                                     std::size_t max_pairs = 100);

}  // namespace drape::geometry
