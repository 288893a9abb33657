#pragma once
// 2D convolution on square images stored as row-major [pixels, channels]
// (pixel (row, col) -> row * size + col), stride 1, "same" zero padding, an
// odd kernel. im2col + one matrix product over the whole batch, like
// nn::Conv1dLayer: column (dy * kernel + dx) * channels + c of the patch
// matrix is input channel c at offset (dy - pad, dx - pad).
#include <drape/node.hpp>
#include <drape/nn/activation.hpp>
#include <drape/nn/refs.hpp>

#include <cstdint>
#include <string>

namespace drape::uvcnn {

struct Conv2dGeometry {
  int size = 0;  // image side in pixels
  int in_channels = 0;
  int kernel = 3;
  int pad() const { return kernel / 2; }
  int pixels() const { return size * size; }
  int patch() const { return kernel * kernel * in_channels; }
};

// cols [pixels, patch] from x [pixels, in_channels] (zeros outside the image).
void im2col(const Conv2dGeometry& g, nn::ConstMatRef x, nn::MatRef cols);
// gx [pixels, in_channels] += the patch gradients scattered back.
void col2im_add(const Conv2dGeometry& g, nn::ConstMatRef gcols, nn::MatRef gx);

// Weights "<prefix>w" [patch, out_channels], "<prefix>b" [1, out_channels].
class Conv2dLayer {
 public:
  Conv2dLayer() = default;
  Conv2dLayer(Conv2dGeometry geometry, int out_channels, nn::Activation activation);

  void create_weights(Node& owner, const std::string& prefix, std::uint64_t seed);
  // x [batch*pixels, in_channels] -> [batch*pixels, out_channels], valid until the next forward.
  const MatrixRM& forward(nn::ConstMatRef x, int batch);
  // gy = dLoss/d(output); accumulates the weight gradients; writes dLoss/dx into gx when given.
  void backward(nn::ConstMatRef gy, int batch, MatrixRM* gx);

  double flops_per_sample() const { return double(geometry_.pixels()) * geometry_.patch() * out_channels_; }

 private:
  Conv2dGeometry geometry_;
  int out_channels_ = 0;
  nn::Activation activation_;
  Weight* w_ = nullptr;
  Weight* b_ = nullptr;
  MatrixRM cols_;  // im2col of the last forward's input
  MatrixRM out_;   // the activated output of the last forward
};

}  // namespace drape::uvcnn
