#include <drape/errors.hpp>
#include "matrix_dims.hpp"
#include <drape/nn/sparse_ops.hpp>

#include <string>

namespace drape::nn {

namespace {


void check_batch(const char* what, Eigen::Index in_rows, Eigen::Index in_cols, Eigen::Index out_rows,
                 Eigen::Index out_cols, int batch, Eigen::Index a_rows, Eigen::Index a_cols) {
  if (batch < 1 || in_rows != batch * a_cols || out_rows != batch * a_rows || in_cols != out_cols)
    throw Error(std::string(what) + ": a " + dims(a_rows, a_cols) + " map over a batch of " + std::to_string(batch) +
                " does not fit input " + dims(in_rows, in_cols) + " and output " + dims(out_rows, out_cols));
}

// y = A x (A compressed row-major with `rows` rows) with C
// channels at compile time: each output row accumulates in registers and is
// stored once (Eigen's generic product adds into the output row for every
// non-zero, 2-3x slower at 32-64 channels).
template <int C>
void sparse_rows_fixed(const int* outer, const int* inner, const float* values, int rows, const float* x,
                       Eigen::Index x_stride, float* y, Eigen::Index y_stride) {
  using Row = Eigen::Matrix<float, 1, C>;
  for (int i = 0; i < rows; ++i) {
    Row acc = Row::Zero();
    for (int k = outer[i]; k < outer[i + 1]; ++k)
      acc.noalias() += values[k] * Eigen::Map<const Row>(x + Eigen::Index(inner[k]) * x_stride);
    Eigen::Map<Row>(y + Eigen::Index(i) * y_stride) = acc;
  }
}

// Any channel count: blocks of 16 channels in registers, then the rest.
void sparse_rows_any(const int* outer, const int* inner, const float* values, int rows, const float* x,
                     Eigen::Index x_stride, int c, float* y, Eigen::Index y_stride) {
  constexpr int kBlock = 16;
  const int blocked = c - c % kBlock;
  for (int start = 0; start < blocked; start += kBlock)
    sparse_rows_fixed<kBlock>(outer, inner, values, rows, x + start, x_stride, y + start, y_stride);
  if (blocked == c) return;
  Eigen::RowVectorXf acc(c - blocked);
  for (int i = 0; i < rows; ++i) {
    acc.setZero();
    for (int k = outer[i]; k < outer[i + 1]; ++k)
      acc.noalias() += values[k] * Eigen::Map<const Eigen::RowVectorXf>(x + Eigen::Index(inner[k]) * x_stride + blocked, c - blocked);
    Eigen::Map<Eigen::RowVectorXf>(y + Eigen::Index(i) * y_stride + blocked, c - blocked) = acc;
  }
}

// y_b = A x_b for every sample; samples are independent, so they run in parallel.
template <typename Sparse>
void per_sample_product(const Sparse& a, ConstMatRef x, int batch, MatRef y) {
  const Eigen::Index r = a.rows(), c = a.cols();
  const int channels = static_cast<int>(x.cols());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const float* values = a.valuePtr();
#pragma omp parallel for schedule(static) if (batch > 1)
  for (int b = 0; b < batch; ++b) {
    const float* xb = x.data() + b * c * x.outerStride();
    float* yb = y.data() + b * r * y.outerStride();
    const int rows = static_cast<int>(r);
    switch (channels) {
      // 3: a body's or garment's coordinates (resample_body: six times faster than the rest's loop).
      case 3: sparse_rows_fixed<3>(outer, inner, values, rows, xb, x.outerStride(), yb, y.outerStride()); break;
      case 8: sparse_rows_fixed<8>(outer, inner, values, rows, xb, x.outerStride(), yb, y.outerStride()); break;
      case 16: sparse_rows_fixed<16>(outer, inner, values, rows, xb, x.outerStride(), yb, y.outerStride()); break;
      case 32: sparse_rows_fixed<32>(outer, inner, values, rows, xb, x.outerStride(), yb, y.outerStride()); break;
      case 64: sparse_rows_fixed<64>(outer, inner, values, rows, xb, x.outerStride(), yb, y.outerStride()); break;
      default: sparse_rows_any(outer, inner, values, rows, xb, x.outerStride(), channels, yb, y.outerStride());
    }
  }
}

}  // namespace

SparseOperator::SparseOperator(SparseRM a) : a_(std::move(a)) {
  a_.makeCompressed();
  at_ = SparseRM(a_.transpose());
  at_.makeCompressed();
}

void SparseOperator::apply(ConstMatRef x, int batch, MatRef y) const {
  check_batch("SparseOperator::apply", x.rows(), x.cols(), y.rows(), y.cols(), batch, a_.rows(), a_.cols());
  per_sample_product(a_, x, batch, y);
}

void SparseOperator::apply_transpose(ConstMatRef g, int batch, MatRef gx) const {
  check_batch("SparseOperator::apply_transpose", g.rows(), g.cols(), gx.rows(), gx.cols(), batch, at_.rows(),
              at_.cols());
  per_sample_product(at_, g, batch, gx);
}

LearnedAggregation::LearnedAggregation(SparseRM pattern) : pattern_(std::move(pattern)) {
  if (pattern_.rows() != pattern_.cols())
    throw Error("LearnedAggregation needs a square pattern, got " + dims(pattern_.rows(), pattern_.cols()));
  pattern_.makeCompressed();
  // Counting sort of the entries by column gives the transpose in row-major
  // order together with where each entry came from.
  const int n = static_cast<int>(pattern_.rows());
  const Eigen::Index nnz = pattern_.nonZeros();
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  std::vector<int> t_outer(static_cast<std::size_t>(n) + 1, 0);
  for (Eigen::Index k = 0; k < nnz; ++k) ++t_outer[static_cast<std::size_t>(inner[k]) + 1];
  for (int j = 0; j < n; ++j) t_outer[j + 1] += t_outer[j];
  std::vector<int> next(t_outer.begin(), t_outer.end() - 1);
  std::vector<int> t_inner(static_cast<std::size_t>(nnz));
  transpose_source_.assign(static_cast<std::size_t>(nnz), 0);
  for (int i = 0; i < n; ++i)
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const int slot = next[inner[k]]++;
      t_inner[slot] = i;
      transpose_source_[slot] = k;
    }
  std::vector<float> zeros(static_cast<std::size_t>(nnz), 0.0f);
  transpose_ = Eigen::Map<const SparseRM>(n, n, nnz, t_outer.data(), t_inner.data(), zeros.data());
  transpose_.makeCompressed();
}

void LearnedAggregation::create_weights(Node& owner, const std::string& name) {
  const int nnz = static_cast<int>(pattern_.nonZeros());
  Weight& w = owner.weights()[name];
  w = Weight{Tensor(1, 1, nnz), Tensor(1, 1, nnz)};
  std::copy(pattern_.valuePtr(), pattern_.valuePtr() + nnz, w.value.data());
  theta_ = &w;
}

Eigen::Map<const SparseRM> LearnedAggregation::values_view() const {
  if (!theta_) throw Error("LearnedAggregation used before create_weights");
  return {pattern_.rows(), pattern_.cols(), pattern_.nonZeros(), pattern_.outerIndexPtr(), pattern_.innerIndexPtr(),
          theta_->value.data()};
}

void LearnedAggregation::apply(ConstMatRef x, int batch, MatRef y) const {
  check_batch("LearnedAggregation::apply", x.rows(), x.cols(), y.rows(), y.cols(), batch, pattern_.rows(),
              pattern_.cols());
  per_sample_product(values_view(), x, batch, y);
}

void LearnedAggregation::backward(ConstMatRef u, ConstMatRef g, int batch, MatRef* gu) {
  check_batch("LearnedAggregation::backward", u.rows(), u.cols(), g.rows(), g.cols(), batch, pattern_.rows(),
              pattern_.cols());
  const auto a = values_view();
  const int n = rows();
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  float* grad = theta_->grad.data();
  // dLoss/dtheta[i, j] = sum_b <g_b[i], u_b[j]>; each entry belongs to one row i,
  // so rows are independent.
  const double work = double(pattern_.nonZeros()) * double(u.cols()) * batch;
#pragma omp parallel for schedule(static) if (work > 4e5)
  for (int i = 0; i < n; ++i)
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      float s = 0.0f;
      for (int b = 0; b < batch; ++b) s += g.row(Eigen::Index(b) * n + i).dot(u.row(Eigen::Index(b) * n + inner[k]));
      grad[k] += s;
    }
  if (!gu) return;
  if (gu->rows() != u.rows() || gu->cols() != u.cols())
    throw Error("LearnedAggregation::backward: gu is " + dims(gu->rows(), gu->cols()) + ", not " +
                dims(u.rows(), u.cols()));
  float* t_values = transpose_.valuePtr();
  const Eigen::Index nnz = pattern_.nonZeros();
  for (Eigen::Index k = 0; k < nnz; ++k) t_values[k] = a.valuePtr()[transpose_source_[static_cast<std::size_t>(k)]];
  per_sample_product(transpose_, g, batch, *gu);
}

}  // namespace drape::nn
