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

// The same neighbourhoods of an edge list in two flat arrays (no allocation
// per vertex, for a pass over a garment at every call): vertex v's
// neighbours are neighbours[start[v] .. start[v + 1]), in the edges' order.
struct VertexAdjacency {
  std::vector<int> start;       // num_vertices + 1 offsets
  std::vector<int> neighbours;  // two entries per edge
};
VertexAdjacency vertex_adjacency(const std::vector<std::array<int, 2>>& edges, int num_vertices);

// For each face, the face across each of its edges: slot k is across the edge
// from corner k to corner k + 1 (mod 3); -1 on a border, or where the edge is
// shared by more than two faces (non-manifold: no single neighbour).
std::vector<std::array<int, 3>> face_neighbours(const Eigen::MatrixX3i& faces);

}  // namespace drape::geometry
