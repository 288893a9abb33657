#pragma once
// A vertex order in which index neighbours are mesh neighbours, for encoders
// that convolve over vertex indices (the seed's 1D CNN).
#include <Eigen/Core>

#include <vector>

namespace drape::parametric {

// A walk over the mesh (Warnsdorff's rule: step to the unvisited neighbour with
// the fewest unvisited neighbours, which keeps the walk hugging what it already
// covered, so it spirals), starting at the highest vertex; when stuck it jumps
// to the nearest unvisited vertex by hops. Returns order[new] = old.
std::vector<int> locality_order(const std::vector<std::vector<int>>& neighbours, const Eigen::MatrixX3d& vertices);

}  // namespace drape::parametric
