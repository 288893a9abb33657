#pragma once
// Float32 tensors shaped [batch, rows, cols], row-major and contiguous, so that
// each sample is a row-major [rows, cols] matrix (vertices x channels) that Eigen
// maps without copying. Row-major features make sparse x dense products ~7x faster
// than column-major on this CPU (see NOTES-deps).
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace drape {

using MatrixRM = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using MatrixMap = Eigen::Map<MatrixRM>;
using ConstMatrixMap = Eigen::Map<const MatrixRM>;

// Per-sample shape; the batch size is chosen at run time.
struct Shape {
  int rows = 0;
  int cols = 0;
  bool operator==(const Shape&) const = default;
  std::string str() const;  // "[rows, cols]"
};

class Tensor {
 public:
  Tensor() = default;
  Tensor(int batch, int rows, int cols, float fill = 0.0f);
  Tensor(int batch, Shape shape, float fill = 0.0f) : Tensor(batch, shape.rows, shape.cols, fill) {}

  int batch() const { return batch_; }
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  Shape shape() const { return {rows_, cols_}; }
  std::size_t size() const { return data_.size(); }
  bool empty() const { return data_.empty(); }

  void resize(int batch, int rows, int cols);  // contents unspecified afterwards
  void set_zero();

  float* data() { return data_.data(); }
  const float* data() const { return data_.data(); }
  float& operator()(int b, int r, int c) { return data_[index(b, r, c)]; }
  float operator()(int b, int r, int c) const { return data_[index(b, r, c)]; }

  // Sample b as a [rows, cols] row-major matrix.
  MatrixMap mat(int b);
  ConstMatrixMap mat(int b) const;
  // All samples stacked as a [batch*rows, cols] matrix (for per-row operations).
  MatrixMap flat();
  ConstMatrixMap flat() const;
  // Every element as one column vector.
  Eigen::Map<Eigen::VectorXf> vec();
  Eigen::Map<const Eigen::VectorXf> vec() const;

  std::string shape_str() const;  // "[batch, rows, cols]"

 private:
  std::size_t index(int b, int r, int c) const {
    return (static_cast<std::size_t>(b) * rows_ + r) * cols_ + c;
  }
  int batch_ = 0, rows_ = 0, cols_ = 0;
  std::vector<float> data_;
};

}  // namespace drape
