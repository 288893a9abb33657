#pragma once
// The fixed sparsity pattern of the cloth Newton matrix and a fast assembly
// into it.
//
// Every energy's Hessian couples vertices that share a face (stretching) or
// the four vertices around an edge (bending); collision and inertia sit on
// the diagonal blocks. The pattern is built once from the garment's topology
// as full 3x3 blocks, lower triangle only (what the Cholesky reads), so the
// symbolic factorisation is computed once per garment. Assembly adds each
// triplet at its slot by a binary search in its column instead of sorting
// millions of triplets at every iteration (what setFromTriplets would do).
// Triplets outside the pattern (an energy coupling vertices the topology does
// not) grow it, which triggers a new symbolic analysis; nothing is dropped.
// The energies emit their triplets in the same order at every iteration, so
// the slot of each is remembered: while the (row, column) sequence repeats,
// assembly is one comparison and one addition per triplet, no search.
#include <drape/energy.hpp>
#include <drape/mesh.hpp>

#include <Eigen/SparseCore>

#include <cstdint>
#include <utility>
#include <vector>

namespace drape::physics {

class HessianPattern {
 public:
  HessianPattern() = default;
  explicit HessianPattern(const Mesh& mesh);

  // out = diag(diagonal) + sum of the triplets (lower triangle kept), on the pattern.
  void assemble(const Triplets& triplets, const Eigen::VectorXd& diagonal, Eigen::SparseMatrix<double>& out);

  Eigen::Index nonzeros() const { return pattern_.nonZeros(); }

 private:
  void build(std::vector<std::pair<int, int>> vertex_pairs);
  bool assemble_cached(const Triplets& triplets, const Eigen::VectorXd& diagonal, Eigen::SparseMatrix<double>& out) const;
  Eigen::SparseMatrix<double> pattern_;  // values unused
  // The last triplet sequence: (row << 32 | column) and its value slot (-1: upper triangle, skipped).
  std::vector<std::uint64_t> cached_keys_;
  std::vector<int> cached_slots_;
  std::vector<int> diagonal_slots_;
  std::vector<std::pair<int, int>> pairs_;  // vertex pairs (a >= b) of the blocks
  int vertices_ = 0;
};

}  // namespace drape::physics
