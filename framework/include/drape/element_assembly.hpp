#pragma once
// Deterministic parallel assembly for energies that are sums over elements
// (faces, edges, ...) of a few vertices each. Results never depend on the number
// of threads: values are summed in fixed chunks in a fixed order, per-element
// gradients are written to fixed slots and summed per vertex in a fixed order,
// and Hessian blocks are written as triplets at fixed offsets.
//
// Threads are used only where the work pays for them: sums and gathers over a
// few thousand elements take a fraction of a millisecond serially, less than
// what starting threads can cost on a busy machine, so they run in parallel
// from kParallelSumMinimum elements on; Hessian loops (tens of flops and 81-144
// triplets per element) from kParallelHessianMinimum on.
#include <drape/energy.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <numeric>
#include <vector>

namespace drape {

inline constexpr int kParallelSumMinimum = 16384;
inline constexpr int kParallelHessianMinimum = 1024;

// Calls body(i) for i in [0, n), in parallel, and returns the sum of the results,
// accumulated element by element within chunks of a fixed size and then over the
// chunks in order.
template <class Body>
double deterministic_sum(int n, Body&& body) {
  constexpr int kChunk = 256;
  const int chunks = (n + kChunk - 1) / kChunk;
  std::vector<double> partial(static_cast<std::size_t>(chunks), 0.0);
#pragma omp parallel for schedule(static) if (n >= kParallelSumMinimum)
  for (int c = 0; c < chunks; ++c) {
    double sum = 0.0;
    const int end = std::min(n, (c + 1) * kChunk);
    for (int i = c * kChunk; i < end; ++i) sum += body(i);
    partial[static_cast<std::size_t>(c)] = sum;
  }
  return std::accumulate(partial.begin(), partial.end(), 0.0);
}

// Per vertex, the element corners (slot = element * corners + corner) that touch
// it, in increasing order, so that per-corner gradients are summed without races.
class CornerGather {
 public:
  // vertex_of(element, corner) -> vertex index in [0, num_vertices).
  template <class VertexOf>
  void build(int num_vertices, int num_elements, int corners, VertexOf&& vertex_of) {
    corners_ = corners;
    start_.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
    for (int e = 0; e < num_elements; ++e)
      for (int k = 0; k < corners; ++k) ++start_[static_cast<std::size_t>(vertex_of(e, k)) + 1];
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    slots_.resize(static_cast<std::size_t>(num_elements) * static_cast<std::size_t>(corners));
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int e = 0; e < num_elements; ++e)
      for (int k = 0; k < corners; ++k) slots_[static_cast<std::size_t>(fill[static_cast<std::size_t>(vertex_of(e, k))]++)] = e * corners + k;
  }

  int num_vertices() const { return static_cast<int>(start_.size()) - 1; }
  std::size_t num_slots() const { return slots_.size(); }

  // g.row(v) += the sum of per_corner[slot] over the slots of v.
  void add_to(const std::vector<Eigen::Vector3d>& per_corner, Eigen::MatrixX3d& g) const {
    const int n = num_vertices();
#pragma omp parallel for schedule(static) if (slots_.size() >= static_cast<std::size_t>(kParallelSumMinimum))
    for (int v = 0; v < n; ++v) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int s = start_[static_cast<std::size_t>(v)]; s < start_[static_cast<std::size_t>(v) + 1]; ++s)
        sum += per_corner[static_cast<std::size_t>(slots_[static_cast<std::size_t>(s)])];
      g.row(v) += sum.transpose();
    }
  }

 private:
  int corners_ = 0;
  std::vector<int> start_;
  std::vector<int> slots_;
};

// Writes the N x N blocks (3 x 3 each) of an element's Hessian over vertices
// `vertex` as triplets starting at `out` (9 N^2 entries), on the flattened
// index 3 * vertex + axis.
template <int N>
inline void write_hessian_blocks(const Eigen::Matrix<double, 3 * N, 3 * N>& h, const int* vertex,
                                 Eigen::Triplet<double>* out) {
  for (int a = 0; a < N; ++a)
    for (int b = 0; b < N; ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) *out++ = Eigen::Triplet<double>(3 * vertex[a] + i, 3 * vertex[b] + j, h(3 * a + i, 3 * b + j));
}

// The entries of an element's Hessian on or below the global diagonal (row >=
// column), what a solver that stores a symmetric matrix's lower triangle needs:
// kLowerEntries<N> triplets, about half of write_hessian_blocks' 9 N^2, written
// from `out`. Each pair of element vertices a > b fills one 3 x 3 block, placed
// below the diagonal by their global order; a vertex repeated within the
// element (a degenerate element) folds its two blocks into one lower triangle
// of 6 entries, padded with 3 zeros, so that every element writes the same
// count and elements can be written in parallel at fixed offsets.
template <int N>
inline constexpr int kLowerEntries = 3 * N * (3 * N + 1) / 2;

template <int N>
inline void write_lower_hessian_blocks(const Eigen::Matrix<double, 3 * N, 3 * N>& h, const int* vertex,
                                       Eigen::Triplet<double>* out) {
  for (int a = 0; a < N; ++a) {
    const int va = vertex[a];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j <= i; ++j) *out++ = Eigen::Triplet<double>(3 * va + i, 3 * va + j, h(3 * a + i, 3 * a + j));
    for (int b = 0; b < a; ++b) {
      const int vb = vertex[b];
      if (va == vb) {
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j <= i; ++j)
            *out++ = Eigen::Triplet<double>(3 * va + i, 3 * va + j, h(3 * a + i, 3 * b + j) + h(3 * b + i, 3 * a + j));
        for (int k = 0; k < 3; ++k) *out++ = Eigen::Triplet<double>(3 * va, 3 * va, 0.0);
        continue;
      }
      // The block of the larger vertex's rows and the smaller one's columns.
      const int hi = va > vb ? a : b, lo = va > vb ? b : a;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          *out++ = Eigen::Triplet<double>(3 * vertex[hi] + i, 3 * vertex[lo] + j, h(3 * hi + i, 3 * lo + j));
    }
  }
}

// Triplets per element of either form, and the writer of that form: what an
// element energy's add_hessian (lower = false) and add_hessian_lower (true) share.
template <int N>
constexpr std::size_t hessian_entries(bool lower) {
  return lower ? kLowerEntries<N> : 9 * N * N;
}

template <int N>
inline void write_element_hessian(const Eigen::Matrix<double, 3 * N, 3 * N>& h, const int* vertex, bool lower,
                                  Eigen::Triplet<double>* out) {
  if (lower)
    write_lower_hessian_blocks<N>(h, vertex, out);
  else
    write_hessian_blocks<N>(h, vertex, out);
}

}  // namespace drape
