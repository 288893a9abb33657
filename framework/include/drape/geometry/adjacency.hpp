#pragma once
// Edges and vertex neighbourhoods of triangle meshes.
#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::geometry {

// Every undirected edge once, as (smaller, larger) vertex index, sorted.
std::vector<std::array<int, 2>> edge_list(const Eigen::MatrixX3i& faces);

// Sorted neighbour lists of each vertex (size num_vertices; isolated vertices get none).
std::vector<std::vector<int>> vertex_neighbours(const Eigen::MatrixX3i& faces, int num_vertices);

}  // namespace drape::geometry
