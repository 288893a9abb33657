#include <drape/errors.hpp>
#include <drape/nn/gemm.hpp>
#include <drape/nn/graph_conv.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/linear.hpp>

#include <algorithm>

namespace drape::nn {

namespace {
void check_sizes(int n, int in, int out) {
  if (n < 1 || in < 1 || out < 1)
    throw ConfigError("a graph convolution needs positive sizes (vertices " + std::to_string(n) + ", channels " +
                      std::to_string(in) + " -> " + std::to_string(out) + ")");
}
}  // namespace

GraphConvLayer::GraphConvLayer(std::shared_ptr<const SparseOperator> aggregation, int in, int out,
                               Activation activation)
    : fixed_(std::move(aggregation)), in_(in), out_channels_(out), activation_(activation) {
  if (!fixed_ || fixed_->rows() != fixed_->cols()) throw Error("GraphConvLayer needs a square aggregation matrix");
  n_ = fixed_->rows();
  check_sizes(n_, in_, out_channels_);
}

GraphConvLayer::GraphConvLayer(const SparseRM& pattern, int in, int out, Activation activation)
    : learned_(pattern), n_(static_cast<int>(pattern.rows())), in_(in), out_channels_(out), activation_(activation) {
  check_sizes(n_, in_, out_channels_);
}

void GraphConvLayer::create_weights(Node& owner, const std::string& prefix, std::uint64_t seed) {
  Weight& w = owner.weights()[prefix + "w"];
  w = Weight{Tensor(1, in_, out_channels_), Tensor(1, in_, out_channels_)};
  // A's rows average (ring_mean, Kipf's matrix has spectral radius 1), so the
  // aggregated features keep roughly the input's scale: He for fan-in `in`.
  fill_normal(w.value, he_std(activation_, in_), seed);
  Weight& b = owner.weights()[prefix + "b"];
  b = Weight{Tensor(1, 1, out_channels_), Tensor(1, 1, out_channels_)};
  w_ = &w;
  b_ = &b;
  if (learned()) learned_.create_weights(owner, prefix + "a");
}

void GraphConvLayer::aggregate(ConstMatRef x, int batch, MatRef y) const {
  if (fixed_) fixed_->apply(x, batch, y);
  else learned_.apply(x, batch, y);
}

void GraphConvLayer::aggregate_backward(ConstMatRef u, ConstMatRef g, int batch, MatRef* gu) {
  if (!fixed_) learned_.backward(u, g, batch, gu);
  else if (gu) fixed_->apply_transpose(g, batch, *gu);
}

const MatrixRM& GraphConvLayer::forward(ConstMatRef x, int batch) {
  if (!w_) throw Error("GraphConvLayer::forward before create_weights");
  const Eigen::Index rows = Eigen::Index(batch) * n_;
  if (x.rows() != rows || x.cols() != in_)
    throw Error("GraphConvLayer::forward: input is not [batch*" + std::to_string(n_) + ", " + std::to_string(in_) + "]");
  out_.resize(rows, out_channels_);
  if (aggregate_first()) {
    mid_.resize(rows, in_);
    aggregate(x, batch, mid_);
    linear_forward(mid_, w_->value.mat(0), b_->value.mat(0), out_);
  } else {
    mid_.resize(rows, out_channels_);
    gemm(Op::None, Op::None, 1.0f, x, w_->value.mat(0), 0.0f, mid_);
    aggregate(mid_, batch, out_);
    out_.rowwise() += b_->value.mat(0).row(0);
  }
  activate(activation_, out_);
  return out_;
}

void GraphConvLayer::backward(ConstMatRef x, ConstMatRef gy, int batch, MatrixRM* gx) {
  MatrixRM gz = gy;
  activation_backward(activation_, out_, gz);
  auto gw = w_->grad.mat(0);
  auto gb = b_->grad.mat(0);
  if (aggregate_first()) {
    // z = (A x) W + b
    linear_backward_weights(mid_, gz, gw, gb);
    if (!gx && !learned()) return;
    MatrixRM gmid(gz.rows(), in_);
    linear_backward_input(w_->value.mat(0), gz, gmid);
    if (gx) {
      gx->resize(x.rows(), in_);
      MatRef gx_ref(*gx);
      aggregate_backward(x, gmid, batch, &gx_ref);
    } else {
      aggregate_backward(x, gmid, batch, nullptr);
    }
  } else {
    // z = A (x W) + b
    gb.row(0) += gz.colwise().sum();
    MatrixRM gmid(gz.rows(), out_channels_);
    MatRef gmid_ref(gmid);
    aggregate_backward(mid_, gz, batch, &gmid_ref);
    gemm(Op::Transpose, Op::None, 1.0f, x, gmid, 1.0f, gw);
    if (gx) {
      gx->resize(x.rows(), in_);
      linear_backward_input(w_->value.mat(0), gmid, *gx);
    }
  }
}

double GraphConvLayer::flops_per_sample() const {
  return double(n_) * in_ * out_channels_ + double(nonzeros()) * std::min(in_, out_channels_);
}

}  // namespace drape::nn
