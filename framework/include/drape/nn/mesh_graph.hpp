#pragma once
// The sparse matrices graph convolutions need on a mesh's vertex graph (given
// as sorted neighbour lists, geometry::vertex_neighbours): the aggregation of a
// vertex's 1-ring and itself, fixed (Kipf & Welling) or as the initial values of
// learned weights (the seed's eq. 6.4), and the maps between resolutions.
#include <drape/nn/sparse_ops.hpp>

#include <vector>

namespace drape::nn {

using Neighbours = std::vector<std::vector<int>>;

// Pattern: each vertex's 1-ring and itself; values 1 / (degree + 1), the mean
// over that neighbourhood (the learned aggregation's starting point).
SparseRM ring_mean(const Neighbours& neighbours);

// Kipf & Welling's propagation matrix D^-1/2 (A + I) D^-1/2 with D the degrees
// of A + I: symmetric, isotropic (one value per vertex pair, fixed by the graph).
SparseRM kipf_adjacency(const Neighbours& neighbours);

// Mean pooling of consecutive vertex blocks: block p holds vertices
// [p*stride, min((p+1)*stride, n)). `pool` [blocks, n] averages each block;
// `neighbours` is the pooled graph: two blocks are adjacent when any of their
// vertices are. Throws ConfigError for stride < 1.
struct BlockPooling {
  SparseRM pool;
  Neighbours neighbours;
};
BlockPooling pool_consecutive(const Neighbours& neighbours, int stride);

// The pooling matched to an up-sampling U [fine, coarse] (rows of barycentric
// weights): R = diag(1 / column sums of U) U^T [coarse, fine], so each coarse
// vertex takes the average of the fine vertices that interpolate from it,
// weighted as they use it (constants stay constant). Throws Error when a coarse
// vertex is used by no fine vertex.
SparseRM restriction_of(const SparseRM& upsample);

}  // namespace drape::nn
