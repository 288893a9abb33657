#pragma once
// What the barrier contact keeps of the garment and the body (barrier.hpp):
// shared by its pair code (barrier.cpp) and its friction (friction.cpp).
#include "barrier.hpp"

#include <drape/geometry/box_pairs.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace drape::barrier {

// The garment's primitives and their material-space weights, and the body's
// faces and edges: fixed at bind.
struct BarrierContact::Topology {
  Eigen::MatrixX3i garment_faces;
  std::vector<std::array<int, 2>> garment_edges;  // geometry::edge_list: sorted
  Eigen::VectorXd garment_vertex_area;   // m^2, material space
  Eigen::VectorXd garment_edge_area;     // m^2: a third of each adjacent face's material area
  Eigen::VectorXd garment_edge_rest2;    // m^2: squared material-space length (the mollifier's scale)
  int garment_vertices = 0;
  Eigen::MatrixX3i body_faces;
  std::vector<std::array<int, 2>> body_edges;
};

// Of the body at one revision: its vertices' lumped areas (the weights of
// body vertex pairs), its squared edge lengths (the mollifier's scale) and the
// boxes of its vertices, faces and edges in grids (the broad phase, queried
// by every line-search trial while the body stands still).
struct BarrierContact::BodyState {
  std::uint64_t revision = 0;
  Eigen::VectorXd vertex_area;
  Eigen::VectorXd edge_length2;
  geometry::BoxGrid points, faces, edges;
};

}  // namespace drape::barrier
