#include "conv2d.hpp"

#include <drape/errors.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/linear.hpp>

#include <cstring>

namespace drape::uvcnn {

void im2col(const Conv2dGeometry& g, nn::ConstMatRef x, nn::MatRef cols) {
  const int n = g.size, c = g.in_channels, k = g.kernel, pad = g.pad();
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      float* dst = cols.row(Eigen::Index(row) * n + col).data();
      for (int dy = 0; dy < k; ++dy) {
        const int r = row + dy - pad;
        for (int dx = 0; dx < k; ++dx, dst += c) {
          const int q = col + dx - pad;
          if (r >= 0 && r < n && q >= 0 && q < n) std::memcpy(dst, x.row(Eigen::Index(r) * n + q).data(), sizeof(float) * c);
          else std::memset(dst, 0, sizeof(float) * c);
        }
      }
    }
}

void col2im_add(const Conv2dGeometry& g, nn::ConstMatRef gcols, nn::MatRef gx) {
  const int n = g.size, c = g.in_channels, k = g.kernel, pad = g.pad();
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      const float* src = gcols.row(Eigen::Index(row) * n + col).data();
      for (int dy = 0; dy < k; ++dy) {
        const int r = row + dy - pad;
        for (int dx = 0; dx < k; ++dx, src += c) {
          const int q = col + dx - pad;
          if (r < 0 || r >= n || q < 0 || q >= n) continue;
          float* dst = gx.row(Eigen::Index(r) * n + q).data();
          for (int j = 0; j < c; ++j) dst[j] += src[j];
        }
      }
    }
}

Conv2dLayer::Conv2dLayer(Conv2dGeometry geometry, int out_channels, nn::Activation activation)
    : geometry_(geometry), out_channels_(out_channels), activation_(activation) {
  if (geometry_.size < 1 || geometry_.in_channels < 1 || geometry_.kernel < 1 || geometry_.kernel % 2 == 0 ||
      out_channels_ < 1)
    throw ConfigError("a 2D convolution needs positive sizes and an odd kernel (image " + std::to_string(geometry_.size) +
                      ", channels " + std::to_string(geometry_.in_channels) + " -> " + std::to_string(out_channels_) +
                      ", kernel " + std::to_string(geometry_.kernel) + ")");
}

void Conv2dLayer::create_weights(Node& owner, const std::string& prefix, std::uint64_t seed) {
  Weight& w = owner.weights()[prefix + "w"];
  w = Weight{Tensor(1, geometry_.patch(), out_channels_), Tensor(1, geometry_.patch(), out_channels_)};
  nn::fill_normal(w.value, nn::he_std(activation_, geometry_.patch()), seed);
  Weight& b = owner.weights()[prefix + "b"];
  b = Weight{Tensor(1, 1, out_channels_), Tensor(1, 1, out_channels_)};
  w_ = &w;
  b_ = &b;
}

const MatrixRM& Conv2dLayer::forward(nn::ConstMatRef x, int batch) {
  const Conv2dGeometry& g = geometry_;
  if (!w_) throw Error("Conv2dLayer::forward before create_weights");
  const Eigen::Index pixels = g.pixels();
  if (x.rows() != batch * pixels || x.cols() != g.in_channels)
    throw Error("Conv2dLayer::forward: input is not [batch*" + std::to_string(pixels) + ", " +
                std::to_string(g.in_channels) + "]");
  cols_.resize(batch * pixels, g.patch());
#pragma omp parallel for schedule(static) if (batch > 1)
  for (int b = 0; b < batch; ++b) im2col(g, x.middleRows(b * pixels, pixels), cols_.middleRows(b * pixels, pixels));
  out_.resize(cols_.rows(), out_channels_);
  nn::linear_forward(cols_, w_->value.mat(0), b_->value.mat(0), out_);
  nn::activate(activation_, out_);
  return out_;
}

void Conv2dLayer::backward(nn::ConstMatRef gy, int batch, MatrixRM* gx) {
  const Conv2dGeometry& g = geometry_;
  MatrixRM gz = gy;
  nn::activation_backward(activation_, out_, gz);
  auto gw = w_->grad.mat(0);
  auto gb = b_->grad.mat(0);
  nn::linear_backward_weights(cols_, gz, gw, gb);
  if (!gx) return;
  MatrixRM gcols(gz.rows(), g.patch());
  nn::linear_backward_input(w_->value.mat(0), gz, gcols);
  const Eigen::Index pixels = g.pixels();
  gx->setZero(batch * pixels, g.in_channels);
#pragma omp parallel for schedule(static) if (batch > 1)
  for (int b = 0; b < batch; ++b)
    col2im_add(g, gcols.middleRows(b * pixels, pixels), gx->middleRows(b * pixels, pixels));
}

}  // namespace drape::uvcnn
