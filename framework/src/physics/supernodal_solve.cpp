#include "supernodal_solve.hpp"

#include <Eigen/Dense>

#include <algorithm>

namespace drape::physics {

void FloatSupernodalFactor::set_pattern(int n, int supernodes, const int* perm, const int* super, const int* row_start,
                                        const int* value_start, const int* rows) {
  n_ = n;
  supernodes_ = supernodes;
  perm_.assign(perm, perm + n);
  super_.assign(super, super + supernodes + 1);
  row_start_.assign(row_start, row_start + supernodes + 1);
  value_start_.assign(value_start, value_start + supernodes + 1);
  rows_.assign(rows, rows + row_start[supernodes]);
  widest_ = 0;
  for (int s = 0; s < supernodes; ++s) widest_ = std::max(widest_, row_start[s + 1] - row_start[s]);
  y_.resize(n_);
  gathered_.resize(widest_);
}

void FloatSupernodalFactor::set_values(const double* values, std::size_t count) {
  values_.resize(count);
  std::copy(values, values + count, values_.begin());  // rounds each value to the nearest float
}

void FloatSupernodalFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  using Block = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;
  for (int k = 0; k < n_; ++k) y_[k] = static_cast<float>(b[perm_[k]]);
  // L y = P b, supernode by supernode: the diagonal block's triangle, then the
  // rows below it take the block's contribution (gathered, multiplied, scattered).
  for (int s = 0; s < supernodes_; ++s) {
    const int first = super_[s], columns = super_[s + 1] - first;
    const int height = row_start_[s + 1] - row_start_[s], below = height - columns;
    const Block block(values_.data() + value_start_[s], height, columns, Eigen::OuterStride<>(height));
    auto ys = y_.segment(first, columns);
    block.topRows(columns).triangularView<Eigen::Lower>().solveInPlace(ys);
    if (below == 0) continue;
    auto t = gathered_.head(below);
    t.noalias() = block.bottomRows(below) * ys;
    const int* r = rows_.data() + row_start_[s] + columns;
    for (int i = 0; i < below; ++i) y_[r[i]] -= t[i];
  }
  // L' z = y, in reverse: the rows below contribute first, then the transposed triangle.
  for (int s = supernodes_; s-- > 0;) {
    const int first = super_[s], columns = super_[s + 1] - first;
    const int height = row_start_[s + 1] - row_start_[s], below = height - columns;
    const Block block(values_.data() + value_start_[s], height, columns, Eigen::OuterStride<>(height));
    auto ys = y_.segment(first, columns);
    if (below > 0) {
      auto t = gathered_.head(below);
      const int* r = rows_.data() + row_start_[s] + columns;
      for (int i = 0; i < below; ++i) t[i] = y_[r[i]];
      ys.noalias() -= block.bottomRows(below).transpose() * t;
    }
    block.topRows(columns).transpose().triangularView<Eigen::Upper>().solveInPlace(ys);
  }
  x.resize(n_);
  for (int k = 0; k < n_; ++k) x[perm_[k]] = static_cast<double>(y_[k]);
}

}  // namespace drape::physics
