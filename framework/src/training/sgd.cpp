// Stochastic gradient descent with (Nesterov) momentum, PyTorch's convention:
// v = mu v + g; w -= lr v (or lr (g + mu v) with Nesterov).
#include <drape/training/optimizer.hpp>

namespace drape {

SGD::SGD(NamedWeights weights, const SgdOptions& options)
    : Optimizer(std::move(weights)), options_(options), velocity_(zeros_like_weights()) {}

void SGD::step(double learning_rate) {
  ++steps_;
  const float lr = static_cast<float>(learning_rate);
  const float mu = static_cast<float>(options_.momentum);
  const float l2 = static_cast<float>(options_.weight_decay);
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    auto w = weights_[i].second->value.vec();
    auto g = weights_[i].second->grad.vec();
    auto v = velocity_[i].vec();
    for (Eigen::Index k = 0; k < w.size(); ++k) {
      const float gk = g[k] + l2 * w[k];
      if (mu == 0.0f) {
        w[k] -= lr * gk;
        continue;
      }
      v[k] = mu * v[k] + gk;
      w[k] -= lr * (options_.nesterov ? gk + mu * v[k] : v[k]);
    }
  }
}

OptimizerState SGD::state() const {
  OptimizerState s;
  s.type = "sgd";
  s.scalars = {{"step", static_cast<double>(steps_)}, {"momentum", options_.momentum}};
  save_slot(s, "velocity", velocity_);
  return s;
}

void SGD::set_state(const OptimizerState& state) {
  check_type(state, "sgd");
  load_slot(state, "velocity", velocity_);
  steps_ = static_cast<long>(state.scalars.at("step"));
}

}  // namespace drape
