// Adam (Kingma & Ba 2015) with optional bias correction and weight decay,
// decoupled as in AdamW (Loshchilov & Hutter 2019) or as an L2 gradient term.
#include <drape/optimizer.hpp>

#include <cmath>

namespace drape {

Adam::Adam(NamedWeights weights, const AdamOptions& options)
    : Optimizer(std::move(weights)), options_(options), m_(zeros_like_weights()), v_(zeros_like_weights()) {}

void Adam::step(double learning_rate) {
  ++steps_;
  const double b1 = options_.beta1, b2 = options_.beta2;
  // Bias correction folded into the step size and epsilon (the paper's
  // "efficient version"): the same update with one multiply per element less.
  const double c1 = options_.bias_correction ? 1.0 - std::pow(b1, static_cast<double>(steps_)) : 1.0;
  const double c2 = options_.bias_correction ? 1.0 - std::pow(b2, static_cast<double>(steps_)) : 1.0;
  const float step_size = static_cast<float>(learning_rate * std::sqrt(c2) / c1);
  const float eps = static_cast<float>(options_.epsilon * std::sqrt(c2));
  const float decay = static_cast<float>(learning_rate * options_.weight_decay);
  const float l2 = static_cast<float>(options_.weight_decay);
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    auto w = weights_[i].second->value.vec();
    auto g = weights_[i].second->grad.vec();
    auto m = m_[i].vec();
    auto v = v_[i].vec();
    // Element-wise and independent: threads (OpenMP, as many as the caller
    // allows) change nothing in the result.
#pragma omp parallel for schedule(static) if (w.size() > (1 << 15))
    for (Eigen::Index k = 0; k < w.size(); ++k) {
      float gk = g[k];
      if (options_.weight_decay != 0.0) {
        if (options_.decoupled_weight_decay) w[k] -= decay * w[k];
        else gk += l2 * w[k];
      }
      m[k] = static_cast<float>(b1 * m[k] + (1.0 - b1) * gk);
      v[k] = static_cast<float>(b2 * v[k] + (1.0 - b2) * gk * gk);
      w[k] -= step_size * m[k] / (std::sqrt(v[k]) + eps);
    }
  }
}

OptimizerState Adam::state() const {
  OptimizerState s;
  s.type = "adam";
  s.scalars = {{"step", static_cast<double>(steps_)}, {"beta1", options_.beta1}, {"beta2", options_.beta2},
               {"epsilon", options_.epsilon}, {"weight_decay", options_.weight_decay}};
  save_slot(s, "m", m_);
  save_slot(s, "v", v_);
  return s;
}

void Adam::set_state(const OptimizerState& state) {
  check_type(state, "adam");
  std::vector<Tensor> m, v;
  load_slot(state, "m", m);
  load_slot(state, "v", v);
  m_ = std::move(m);
  v_ = std::move(v);
  steps_ = static_cast<long>(state.scalars.at("step"));
}

}  // namespace drape
