#include <drape/tensor.hpp>

namespace drape {

std::string Shape::str() const { return "[" + std::to_string(rows) + ", " + std::to_string(cols) + "]"; }

Tensor::Tensor(int batch, int rows, int cols, float fill)
    : batch_(batch), rows_(rows), cols_(cols),
      data_(static_cast<std::size_t>(batch) * rows * cols, fill) {}

void Tensor::resize(int batch, int rows, int cols) {
  batch_ = batch;
  rows_ = rows;
  cols_ = cols;
  data_.resize(static_cast<std::size_t>(batch) * rows * cols);
}

void Tensor::set_zero() { std::fill(data_.begin(), data_.end(), 0.0f); }

MatrixMap Tensor::mat(int b) { return MatrixMap(data_.data() + index(b, 0, 0), rows_, cols_); }
ConstMatrixMap Tensor::mat(int b) const { return ConstMatrixMap(data_.data() + index(b, 0, 0), rows_, cols_); }
MatrixMap Tensor::flat() { return MatrixMap(data_.data(), static_cast<Eigen::Index>(batch_) * rows_, cols_); }
ConstMatrixMap Tensor::flat() const {
  return ConstMatrixMap(data_.data(), static_cast<Eigen::Index>(batch_) * rows_, cols_);
}
Eigen::Map<Eigen::VectorXf> Tensor::vec() {
  return Eigen::Map<Eigen::VectorXf>(data_.data(), static_cast<Eigen::Index>(data_.size()));
}
Eigen::Map<const Eigen::VectorXf> Tensor::vec() const {
  return Eigen::Map<const Eigen::VectorXf>(data_.data(), static_cast<Eigen::Index>(data_.size()));
}

std::string Tensor::shape_str() const {
  return "[" + std::to_string(batch_) + ", " + std::to_string(rows_) + ", " + std::to_string(cols_) + "]";
}

}  // namespace drape
