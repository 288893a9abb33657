#include <drape/errors.hpp>
#include <drape/nn/conv1d.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/linear.hpp>

namespace drape::nn {

void im2col(const Conv1dGeometry& g, ConstMatRef x, MatRef cols) {
  const int c = g.in_channels;
  for (int o = 0; o < g.out_rows(); ++o) {
    const int first = o * g.stride - g.pad();
    for (int j = 0; j < g.kernel; ++j) {
      const int r = first + j;
      if (r >= 0 && r < g.in_rows) cols.block(o, j * c, 1, c) = x.row(r);
      else cols.block(o, j * c, 1, c).setZero();
    }
  }
}

void col2im_add(const Conv1dGeometry& g, ConstMatRef gcols, MatRef gx) {
  const int c = g.in_channels;
  for (int o = 0; o < g.out_rows(); ++o) {
    const int first = o * g.stride - g.pad();
    for (int j = 0; j < g.kernel; ++j) {
      const int r = first + j;
      if (r >= 0 && r < g.in_rows) gx.row(r) += gcols.block(o, j * c, 1, c);
    }
  }
}

Conv1dLayer::Conv1dLayer(Conv1dGeometry geometry, int out_channels, Activation activation)
    : geometry_(geometry), out_channels_(out_channels), activation_(activation) {
  if (geometry_.in_rows < 1 || geometry_.in_channels < 1 || geometry_.kernel < 1 || geometry_.stride < 1 ||
      out_channels_ < 1)
    throw ConfigError("a 1D convolution needs positive sizes (rows " + std::to_string(geometry_.in_rows) +
                      ", channels " + std::to_string(geometry_.in_channels) + " -> " + std::to_string(out_channels_) +
                      ", kernel " + std::to_string(geometry_.kernel) + ", stride " + std::to_string(geometry_.stride) +
                      ")");
}

void Conv1dLayer::create_weights(Node& owner, const std::string& prefix, std::uint64_t seed) {
  Weight& w = owner.weights()[prefix + "w"];
  w = Weight{Tensor(1, geometry_.patch(), out_channels_), Tensor(1, geometry_.patch(), out_channels_)};
  fill_normal(w.value, he_std(activation_, geometry_.patch()), seed);
  Weight& b = owner.weights()[prefix + "b"];
  b = Weight{Tensor(1, 1, out_channels_), Tensor(1, 1, out_channels_)};
  w_ = &w;
  b_ = &b;
}

const MatrixRM& Conv1dLayer::forward(ConstMatRef x, int batch) {
  const Conv1dGeometry& g = geometry_;
  if (!w_) throw Error("Conv1dLayer::forward before create_weights");
  if (x.rows() != Eigen::Index(batch) * g.in_rows || x.cols() != g.in_channels)
    throw Error("Conv1dLayer::forward: input is not [batch*" + std::to_string(g.in_rows) + ", " +
                std::to_string(g.in_channels) + "]");
  const int in_rows = g.in_rows, out_rows = g.out_rows();
  cols_.resize(Eigen::Index(batch) * out_rows, g.patch());
#pragma omp parallel for schedule(static) if (batch > 1)
  for (int b = 0; b < batch; ++b)
    im2col(g, x.middleRows(Eigen::Index(b) * in_rows, in_rows), cols_.middleRows(Eigen::Index(b) * out_rows, out_rows));
  out_.resize(cols_.rows(), out_channels_);
  linear_forward(cols_, w_->value.mat(0), b_->value.mat(0), out_);
  activate(activation_, out_);
  return out_;
}

void Conv1dLayer::backward(ConstMatRef gy, int batch, MatrixRM* gx) {
  const Conv1dGeometry& g = geometry_;
  MatrixRM gz = gy;
  activation_backward(activation_, out_, gz);
  auto gw = w_->grad.mat(0);
  auto gb = b_->grad.mat(0);
  linear_backward_weights(cols_, gz, gw, gb);
  if (!gx) return;
  MatrixRM gcols(gz.rows(), g.patch());
  linear_backward_input(w_->value.mat(0), gz, gcols);
  gx->setZero(Eigen::Index(batch) * g.in_rows, g.in_channels);
  const int in_rows = g.in_rows, out_rows = g.out_rows();
#pragma omp parallel for schedule(static) if (batch > 1)
  for (int b = 0; b < batch; ++b)
    col2im_add(g, gcols.middleRows(Eigen::Index(b) * out_rows, out_rows), gx->middleRows(Eigen::Index(b) * in_rows, in_rows));
}

}  // namespace drape::nn
