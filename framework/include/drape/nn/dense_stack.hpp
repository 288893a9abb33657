#pragma once
// A stack of dense layers applied to every row of a [N, in] matrix (a shared
// per-vertex MLP, or an MLP over flattened samples). The weights live in the
// owning Node's weight map (so checkpoints and optimisers see them); the stack
// keeps pointers to them and the activations of its last forward for backward.
#include <drape/node.hpp>
#include <drape/nn/activation.hpp>
#include <drape/nn/refs.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace drape::nn {

class DenseStack {
 public:
  DenseStack() = default;
  // sizes = [in, h1, ..., out] (at least two entries); every layer but the last
  // is followed by `hidden`, the last by `last`.
  DenseStack(std::vector<int> sizes, Activation hidden, Activation last);

  // Creates (or re-creates) weights "<prefix>w<i>" [in_i, out_i] and "<prefix>b<i>"
  // [1, out_i] in `owner`: He-initialised matrices, zero biases. Call from setup().
  void create_weights(Node& owner, const std::string& prefix, std::uint64_t seed);

  // x [N, in] -> the output [N, out], valid until the next forward.
  const MatrixRM& forward(ConstMatRef x);
  // gy = dLoss/d(output) [N, out] of the last forward with this same x.
  // Accumulates weight gradients; writes dLoss/dx into gx when given.
  void backward(ConstMatRef x, ConstMatRef gy, MatrixRM* gx);
  // The same, dLoss/dx written into gx [N, in] in place (say, a graph tensor).
  void backward_into(ConstMatRef x, ConstMatRef gy, MatRef gx);

  int in() const { return sizes_.front(); }
  int out() const { return sizes_.back(); }
  int layers() const { return static_cast<int>(sizes_.size()) - 1; }
  double flops_per_row() const;  // multiply-adds

 private:
  const Activation& activation_of(int layer) const { return layer + 1 == layers() ? last_ : hidden_; }
  std::vector<int> sizes_;
  Activation hidden_, last_;
  std::vector<Weight*> w_, b_;
  std::vector<MatrixRM> out_;  // the activated output of each layer
  MatrixRM g_, gin_;           // backward's gradients of a layer's output and input (scratch)
  void backward_layers(ConstMatRef x, ConstMatRef gy, std::optional<MatRef> gx);
};

}  // namespace drape::nn
