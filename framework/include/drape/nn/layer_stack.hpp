#pragma once
// The loops a node runs over a stack of layers (nn::Conv1dLayer, a plugin's
// own 2D convolution, nn::GraphConvLayer), written once: every layer's weights
// under its own name and seed, the layers' flops, and, for layers that keep
// what their backward needs (forward(x, batch), backward(gy, batch, gx)), the
// forward and backward passes through the whole stack.
#include <drape/node.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/refs.hpp>

#include <cstdint>
#include <string>

namespace drape::nn {

// Layer l's weights as "<prefix><l>_...", seeded mix_seed(seed, l): one seed per node, a stream per layer.
template <class Layers>
void create_stack_weights(Node& owner, Layers& layers, const std::string& prefix, std::uint64_t seed) {
  for (std::size_t l = 0; l < layers.size(); ++l)
    layers[l].create_weights(owner, prefix + std::to_string(l) + "_", mix_seed(seed, l));
}

// start plus every layer's flops_per_sample, added in layer order.
template <class Layers>
double stack_flops(const Layers& layers, double start = 0.0) {
  for (const auto& layer : layers) start += layer.flops_per_sample();
  return start;
}

// x through every layer in turn; the last layer's output, valid until its next forward.
template <class Layers>
const MatrixRM& forward_stack(Layers& layers, ConstMatRef x, int batch) {
  const MatrixRM* h = nullptr;
  for (std::size_t l = 0; l < layers.size(); ++l) h = &layers[l].forward(l == 0 ? x : ConstMatRef(*h), batch);
  return *h;
}

// g = dLoss/d(the last output) back through the layers, last to first, each
// accumulating its weight gradients. Leaves dLoss/d(x) in g when want_input;
// otherwise the first layer skips it (nobody reads it) and g is left as it was.
template <class Layers>
void backward_stack(Layers& layers, MatrixRM& g, int batch, bool want_input) {
  for (int l = static_cast<int>(layers.size()) - 1; l >= 0; --l) {
    if (l == 0 && !want_input) {
      layers[0].backward(g, batch, nullptr);
      return;
    }
    MatrixRM gprev;
    layers[l].backward(g, batch, &gprev);
    g.swap(gprev);
  }
}

}  // namespace drape::nn
