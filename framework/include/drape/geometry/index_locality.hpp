#pragma once
// How well the vertex order follows the mesh: 1D convolutions over vertex
// indices (the seed's encoder) only see geometry if index neighbours are mesh neighbours.
#include <Eigen/Core>

namespace drape::geometry {

struct IndexLocality {
  double one_hop = 0;  // fraction of consecutive indices (i, i+1) joined by an edge
  double two_hop = 0;  // fraction of (i, i+1) at most two edges apart
};

IndexLocality index_locality(const Eigen::MatrixX3i& faces, int num_vertices);

}  // namespace drape::geometry
