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
  // Single precision throughout, with the weight-decay choice hoisted out of
  // the loop, so the compiler vectorises it: the per-sample optimisation runs
  // Adam over 0.88 M weights every iteration, where the mixed double/float
  // loop took 4.5 ms (drape bench optimize) and this one about a quarter.
  const float b1f = static_cast<float>(b1), b2f = static_cast<float>(b2);
  const float a1 = 1.0f - b1f, a2 = 1.0f - b2f;
  const bool decoupled = options_.weight_decay != 0.0 && options_.decoupled_weight_decay;
  const bool coupled = options_.weight_decay != 0.0 && !options_.decoupled_weight_decay;
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    float* w = weights_[i].second->value.vec().data();
    const float* g = weights_[i].second->grad.vec().data();
    float* m = m_[i].vec().data();
    float* v = v_[i].vec().data();
    const Eigen::Index n = weights_[i].second->value.vec().size();
    // Element-wise and independent: threads (OpenMP, as many as the caller
    // allows) change nothing in the result.
#pragma omp parallel for simd schedule(static) if (n > (1 << 15))
    for (Eigen::Index k = 0; k < n; ++k) {
      const float gk = coupled ? g[k] + l2 * w[k] : g[k];
      const float wk = decoupled ? w[k] - decay * w[k] : w[k];
      const float mk = b1f * m[k] + a1 * gk;
      const float vk = b2f * v[k] + a2 * gk * gk;
      m[k] = mk;
      v[k] = vk;
      w[k] = wk - step_size * mk / (std::sqrt(vk) + eps);
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
