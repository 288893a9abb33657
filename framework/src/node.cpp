#include <drape/node.hpp>

namespace drape {

void Node::zero_grad() {
  for (auto& [name, w] : weights_) w.grad.set_zero();
}

Weight& Node::add_weight(const std::string& name, int rows, int cols) {
  Weight& w = weights_[name];
  w.value = Tensor(1, rows, cols);
  w.grad = Tensor(1, rows, cols);
  return w;
}

}  // namespace drape
