#pragma once
// Broad phase for contact: the pairs of axis-aligned boxes that overlap, say
// the swept boxes of the cloth's primitives against the body's.
#include <Eigen/Core>

#include <array>
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

// The boxes of every vertex, face and edge of a mesh moving from x to x_end
// (x_end null: standing), each grown by `inflate` on every side: the broad
// phase's input for a contact between two meshes.
struct MeshBoxes {
  std::vector<Box> points, faces, edges;
};
MeshBoxes mesh_boxes(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d* x_end, const Eigen::MatrixX3i& faces,
                     const std::vector<std::array<int, 2>>& edges, double inflate);

// The test overlapping_boxes reports a pair by: both boxes valid (finite,
// lo <= hi) and overlapping as closed boxes.
bool boxes_overlap(const Box& a, const Box& b);

// A Verlet list's promise for a move: true when every primitive's box swept
// from x to x + dx (mesh_boxes with x_end and no growth) lies inside its box
// at x0 grown by `inflate`, so that every pair whose swept boxes overlap was
// already a pair of the list found at x0 with boxes grown that much. Holds
// when max |x - x0| + max |dx| <= inflate over every coordinate; a nanometre
// and the coordinates' rounding are kept in hand.
bool sweep_within(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, double inflate);

// The same with b's grid built once and kept: a body that stands still is
// queried by every line-search trial, and rebuilding its grid each time cost
// more than the query (a third of a barrier drape's time).
class BoxGrid {
 public:
  BoxGrid() = default;
  explicit BoxGrid(std::vector<Box> boxes, double cell_size = 0);

  // All (i, j) with a[i] overlapping boxes()[j], as overlapping_boxes(a, boxes()).
  std::vector<std::pair<int, int>> overlapping(const std::vector<Box>& a) const;
  const std::vector<Box>& boxes() const { return boxes_; }

 private:
  struct Item {
    int box;
    std::array<int, 3> low;  // the box's low cell
  };
  std::vector<Box> boxes_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Box bounds_{Eigen::Vector3d::Zero(), -Eigen::Vector3d::Ones()};  // empty until a valid box is added
  double cell_ = 1;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> start_;  // cell c holds items_[start_[c] .. start_[c + 1])
  std::vector<Item> items_;

  std::array<int, 3> cell_of(const Eigen::Vector3d& p) const;
  std::size_t index(int x, int y, int z) const;
};

}  // namespace drape::geometry
