#pragma once
// The unit every learning plugin provides: named float32 ports, typed parameters,
// learnable weights with gradients, forward and reverse-mode backward.
// Shaped after Caffe's layers: a node keeps nothing between calls except its
// weights and the activations it saves in forward for backward.
#include <drape/params.hpp>
#include <drape/tensor.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace drape {

class GarmentSizes;  // a model's garment in each size, built lazily (garment_sizes.hpp)
class Assets;  // precomputed template data (garment, hierarchy, eigenbasis), see assets.hpp

using ShapeMap = std::map<std::string, Shape>;
using TensorIn = std::map<std::string, const Tensor*>;
using TensorOut = std::map<std::string, Tensor*>;

struct Weight {
  Tensor value;  // [1, rows, cols]
  Tensor grad;   // same shape; backward accumulates (+=) into it
};

// What a node may know about its surroundings when it is set up.
struct NodeContext {
  std::string name;               // the node's name in the graph
  std::uint64_t seed = 0;         // for weight initialisation; derived from the graph seed and name
  const Assets* assets = nullptr; // may be null when no template is bound
  // The bound garment's material space in each size of the model's size
  // chart, each built at its first use (garment_sizes.hpp): what the cloth
  // of a body's own size rests at (the push-out's strain limit). Null
  // without a chart: an untrained graph, a model of one size. A node may
  // keep it and ask for a size in forward.
  std::shared_ptr<const GarmentSizes> garment_sizes = {};
};

class Node {
 public:
  virtual ~Node() = default;

  // Called once before anything runs, with the per-sample shapes of every
  // connected input port. Returns the per-sample shapes of the output ports and
  // creates the weights. Throws ConfigError (plain message) on a shape mismatch;
  // the graph adds the file, line and node name.
  virtual ShapeMap setup(const ShapeMap& inputs, const NodeContext& context) = 0;

  // Output tensors arrive allocated to [batch, rows, cols] by the framework.
  virtual void forward(const TensorIn& in, const TensorOut& out) = 0;

  // Reverse mode. grad_out holds dLoss/dOutput for every output port; write
  // (overwrite) dLoss/dInput into every element of every grad_in tensor
  // (allocated, its contents unspecified: the graph reuses buffers unzeroed) and
  // accumulate (+=) weight gradients into weights()[..].grad. grad_in holds
  // only the ports whose gradient is wanted (Caffe's propagate_down): a graph
  // omits those fed by graph inputs or by nodes with no weights upstream, so
  // look ports up with find() and skip the work for the missing ones.
  virtual void backward(const TensorIn& in, const TensorIn& out, const TensorIn& grad_out,
                        const TensorOut& grad_in) = 0;

  // Multiply-adds per sample of one forward pass (for the FLOP report of `drape bench`).
  virtual double flops_per_sample() const { return 0.0; }

  std::map<std::string, Weight>& weights() { return weights_; }
  const std::map<std::string, Weight>& weights() const { return weights_; }
  void zero_grad();

 protected:
  // Creates (or re-creates) a weight of shape [1, rows, cols], zero-initialised.
  Weight& add_weight(const std::string& name, int rows, int cols);

 private:
  std::map<std::string, Weight> weights_;
};

}  // namespace drape
