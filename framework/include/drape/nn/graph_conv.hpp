#pragma once
// One graph convolution over a batch stacked as [batch*vertices, channels]:
//   y = f(A x W + b)        (the seed's eq. 6.1/6.2, f_theta = dense map + activation)
// A aggregates each vertex's 1-ring and itself. It is either fixed and shared
// between layers (Kipf & Welling's isotropic D^-1/2 (A + I) D^-1/2), or learned
// per vertex and per neighbour, independent of the features (eq. 6.4).
// W [in, out] and b [1, out] are shared by all vertices.
//
// A (x W) = (A x) W, so the layer aggregates on the narrower side: A x first
// when in <= out, x W first otherwise.
#include <drape/nn/activation.hpp>
#include <drape/nn/sparse_ops.hpp>

#include <cstdint>
#include <memory>
#include <string>

namespace drape::nn {

class GraphConvLayer {
 public:
  GraphConvLayer() = default;
  // Fixed aggregation (square, shared with other layers on the same graph).
  GraphConvLayer(std::shared_ptr<const SparseOperator> aggregation, int in, int out, Activation activation);
  // Learned aggregation on `pattern`, whose values are the initial weights.
  GraphConvLayer(const SparseRM& pattern, int in, int out, Activation activation);

  // Weights "<prefix>w" [in, out] (He-initialised), "<prefix>b" [1, out] (zero)
  // and, when learned, "<prefix>a" [1, nnz] (the pattern's values).
  void create_weights(Node& owner, const std::string& prefix, std::uint64_t seed);

  // x [batch*n, in] -> [batch*n, out], valid until the next forward.
  const MatrixRM& forward(ConstMatRef x, int batch);
  const MatrixRM& output() const { return out_; }  // of the last forward
  // x: the last forward's input; gy = dLoss/d(output). Accumulates weight
  // gradients; writes dLoss/dx into gx when given.
  void backward(ConstMatRef x, ConstMatRef gy, int batch, MatrixRM* gx);

  int vertices() const { return n_; }
  int in() const { return in_; }
  int out() const { return out_channels_; }
  bool learned() const { return !fixed_; }
  // Multiply-adds: n*in*out for W, nnz*min(in, out) for A.
  double flops_per_sample() const;

 private:
  bool aggregate_first() const { return in_ <= out_channels_; }
  Eigen::Index nonzeros() const { return fixed_ ? fixed_->nonzeros() : learned_.nonzeros(); }
  void aggregate(ConstMatRef x, int batch, MatRef y) const;
  // gu = A^T g (when given) and, when learned, the aggregation weights' gradient.
  void aggregate_backward(ConstMatRef u, ConstMatRef g, int batch, MatRef* gu);

  std::shared_ptr<const SparseOperator> fixed_;
  LearnedAggregation learned_;
  int n_ = 0, in_ = 0, out_channels_ = 0;
  Activation activation_;
  Weight* w_ = nullptr;
  Weight* b_ = nullptr;
  MatrixRM mid_;  // A x (aggregate first) or x W (transform first) of the last forward
  MatrixRM out_;  // the activated output of the last forward
};

}  // namespace drape::nn
