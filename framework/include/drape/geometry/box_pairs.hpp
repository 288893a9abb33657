#pragma once
// Broad phase for contact: the pairs of axis-aligned boxes that overlap, say
// the swept boxes of the cloth's primitives against the body's.
#include <Eigen/Core>

#include <utility>
#include <vector>

namespace drape::geometry {

// A closed axis-aligned box [lo, hi].
struct Box {
  Eigen::Vector3d lo, hi;
};

// All (i, j) with a[i] and b[j] overlapping as closed boxes (touching counts),
// sorted by (i, j), without duplicates. Boxes with lo > hi on some axis, or a
// non-finite coordinate, overlap nothing.
//
// b's boxes go into a uniform grid; each box of a visits the cells it covers,
// so the cost is about linear in the box and pair counts when b's boxes have
// similar sizes (mesh faces, edges, vertices padded by a contact distance).
// The cell size is the median of b's largest box extents (cell_size <= 0) or
// cell_size, enlarged when the grid would hold more than a few cells or cell
// entries per box of b, so memory stays linear in b. Queries run in parallel
// (OpenMP) in fixed chunks of a; the output does not depend on the thread count.
std::vector<std::pair<int, int>> overlapping_boxes(const std::vector<Box>& a, const std::vector<Box>& b,
                                                   double cell_size = 0);

}  // namespace drape::geometry
