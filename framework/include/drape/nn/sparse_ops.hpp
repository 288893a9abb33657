#pragma once
// Sparse linear maps over the rows (vertices) of row-major [vertices, channels]
// features, applied to every sample of a batch stacked as [batch*vertices, C]:
// the graph convolutions' aggregation (fixed, or learned per vertex and per
// neighbour as in the seed's eq. 6.4), mesh up-sampling and pooling.
//
// Row-major sparse x row-major dense: each output row is a weighted sum of
// contiguous input rows, the fast layout (tensor.hpp). Backward multiplies by
// the transpose, which is kept as its own row-major matrix for the same reason.
#include <drape/node.hpp>
#include <drape/nn/refs.hpp>

#include <Eigen/SparseCore>

#include <string>
#include <vector>

namespace drape::nn {

using SparseRM = Eigen::SparseMatrix<float, Eigen::RowMajor, int>;

// A fixed map A [rows, cols]: y_b = A x_b for every sample b.
class SparseOperator {
 public:
  SparseOperator() = default;
  explicit SparseOperator(SparseRM a);

  int rows() const { return static_cast<int>(a_.rows()); }
  int cols() const { return static_cast<int>(a_.cols()); }
  Eigen::Index nonzeros() const { return a_.nonZeros(); }
  const SparseRM& matrix() const { return a_; }

  // x [batch*cols, C] -> y [batch*rows, C] (overwritten).
  void apply(ConstMatRef x, int batch, MatRef y) const;
  // g [batch*rows, C] -> gx [batch*cols, C] = A^T g per sample (overwritten).
  void apply_transpose(ConstMatRef g, int batch, MatRef gx) const;

 private:
  SparseRM a_, at_;
};

// A square map whose non-zero values are learned weights (eq. 6.4:
// A[i, j] = theta[i, j]), on a fixed pattern (a vertex's 1-ring and itself).
// The weight "<name>" [1, nnz] holds the values in the pattern's row-major order.
class LearnedAggregation {
 public:
  LearnedAggregation() = default;
  // The pattern's values are the initial weights.
  explicit LearnedAggregation(SparseRM pattern);

  void create_weights(Node& owner, const std::string& name);

  int rows() const { return static_cast<int>(pattern_.rows()); }
  Eigen::Index nonzeros() const { return pattern_.nonZeros(); }

  // x [batch*n, C] -> y [batch*n, C] = A_theta x per sample (overwritten).
  void apply(ConstMatRef x, int batch, MatRef y) const;
  // For y = A_theta u (u [batch*n, C] what apply() multiplied, g = dLoss/dy):
  // accumulates dLoss/dtheta[i, j] = sum_b <g_b[i], u_b[j]> into the weight's
  // gradient, and writes gu = A_theta^T g per sample when gu is given.
  void backward(ConstMatRef u, ConstMatRef g, int batch, MatRef* gu);

 private:
  Eigen::Map<const SparseRM> values_view() const;

  SparseRM pattern_;
  // The transpose's pattern (row-major) and, for each of its entries, the
  // index of the same entry in pattern_'s order (to refill its values).
  SparseRM transpose_;
  std::vector<int> transpose_source_;
  Weight* theta_ = nullptr;
};

}  // namespace drape::nn
