#pragma once
// 1D convolution along the rows of row-major [rows, channels] features (rows =
// the body's vertex order). "Same" zero padding centred on the kernel: output
// row o looks at input rows o*stride - pad + j, j < kernel, pad = (kernel-1)/2,
// so out_rows = ceil(in_rows / stride) and output row o sits at input row o*stride.
// Implemented as im2col + one matrix product over the whole batch.
#include <drape/node.hpp>
#include <drape/nn/activation.hpp>
#include <drape/nn/refs.hpp>

#include <cstdint>
#include <string>

namespace drape::nn {

struct Conv1dGeometry {
  int in_rows = 0;
  int in_channels = 0;
  int kernel = 1;
  int stride = 1;
  int pad() const { return (kernel - 1) / 2; }
  int out_rows() const { return (in_rows + stride - 1) / stride; }
  int patch() const { return kernel * in_channels; }  // columns of im2col
};

// cols [out_rows, patch]: row o is the input rows o*stride - pad + j side by side (zeros outside).
void im2col(const Conv1dGeometry& g, ConstMatRef x, MatRef cols);
// gx [in_rows, in_channels] += the patch gradients scattered back to their input rows.
void col2im_add(const Conv1dGeometry& g, ConstMatRef gcols, MatRef gx);

// One convolution + activation over a batch stacked as [batch*in_rows, in_channels].
// Weights: "<prefix>w" [kernel*in_channels, out_channels] (row j*in_channels + c is
// kernel tap j of input channel c), "<prefix>b" [1, out_channels].
class Conv1dLayer {
 public:
  Conv1dLayer() = default;
  Conv1dLayer(Conv1dGeometry geometry, int out_channels, Activation activation);

  void create_weights(Node& owner, const std::string& prefix, std::uint64_t seed);
  // x [batch*in_rows, in_channels] -> [batch*out_rows, out_channels], valid until the next forward.
  const MatrixRM& forward(ConstMatRef x, int batch);
  // gy = dLoss/d(output); accumulates weight gradients; writes dLoss/dx into gx when given.
  void backward(ConstMatRef gy, int batch, MatrixRM* gx);

  const Conv1dGeometry& geometry() const { return geometry_; }
  int out_channels() const { return out_channels_; }
  double flops_per_sample() const { return double(geometry_.out_rows()) * geometry_.patch() * out_channels_; }

 private:
  Conv1dGeometry geometry_;
  int out_channels_ = 0;
  Activation activation_;
  Weight* w_ = nullptr;
  Weight* b_ = nullptr;
  MatrixRM cols_;  // im2col of the last forward's input (what the weight gradient needs)
  MatrixRM out_;   // the activated output of the last forward
};

}  // namespace drape::nn
