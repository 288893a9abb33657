#pragma once
// Exposes an Energy as a graph loss node: input `x` [N, 3] garment positions
// (float), output `energy` [1, 1] per sample. The physics runs in double; the
// gradient flows back to the network in float.
#include <drape/energy.hpp>
#include <drape/node.hpp>

#include <memory>

namespace drape {

class EnergyNode final : public Node {
 public:
  explicit EnergyNode(std::unique_ptr<Energy> energy) : energy_(std::move(energy)) {}
  ShapeMap setup(const ShapeMap& inputs, const NodeContext& context) override;
  void forward(const TensorIn& in, const TensorOut& out) override;
  void backward(const TensorIn& in, const TensorIn& out, const TensorIn& grad_out, const TensorOut& grad_in) override;

 private:
  std::unique_ptr<Energy> energy_;
  int vertices_ = 0;
};

}  // namespace drape
