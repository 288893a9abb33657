// Adam (Kingma & Ba 2015) with optional bias correction and weight decay,
// decoupled as in AdamW (Loshchilov & Hutter 2019) or as an L2 gradient term.
#include <drape/training/optimizer.hpp>

#include <cmath>

#include <omp.h>

namespace drape {

Adam::Adam(NamedWeights weights, const AdamOptions& options)
    : Optimizer(std::move(weights)), options_(options), m_(zeros_like_weights()), v_(zeros_like_weights()) {}

namespace {

struct AdamConstants {
  float step_size, eps, decay, l2, b1, b2, a1, a2;
  bool coupled, decoupled;
};

// Elements [first, last) of one weight tensor. Compiled three times and the
// best for the CPU chosen when the library loads (GCC's target_clones): the
// build targets the baseline x86-64 (SSE2: four lanes, and a square root and
// a division per element that took ~2 ms a training step for 0.88 M weights);
// AVX-512 does sixteen lanes. Each element's update is independent of the
// others, so how the elements are split among threads changes no bit.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void adam_elements(float* w, const float* g, float* m, float* v, long first, long last, const AdamConstants& c) {
#pragma omp simd
  for (long k = first; k < last; ++k) {
    const float gk = c.coupled ? g[k] + c.l2 * w[k] : g[k];
    const float wk = c.decoupled ? w[k] - c.decay * w[k] : w[k];
    const float mk = c.b1 * m[k] + c.a1 * gk;
    const float vk = c.b2 * v[k] + c.a2 * gk * gk;
    m[k] = mk;
    v[k] = vk;
    w[k] = wk - c.step_size * mk / (std::sqrt(vk) + c.eps);
  }
}

}  // namespace

void Adam::step(double learning_rate) {
  ++steps_;
  const double b1 = options_.beta1, b2 = options_.beta2;
  // Bias correction folded into the step size and epsilon (the paper's
  // "efficient version"): the same update with one multiply per element less.
  const double c1 = options_.bias_correction ? 1.0 - std::pow(b1, static_cast<double>(steps_)) : 1.0;
  const double c2 = options_.bias_correction ? 1.0 - std::pow(b2, static_cast<double>(steps_)) : 1.0;
  // Single precision throughout, with the weight-decay choice hoisted out of
  // the loop, so the compiler vectorises it.
  AdamConstants c;
  c.step_size = static_cast<float>(learning_rate * std::sqrt(c2) / c1);
  c.eps = static_cast<float>(options_.epsilon * std::sqrt(c2));
  c.decay = static_cast<float>(learning_rate * options_.weight_decay);
  c.l2 = static_cast<float>(options_.weight_decay);
  c.b1 = static_cast<float>(b1);
  c.b2 = static_cast<float>(b2);
  c.a1 = 1.0f - c.b1;
  c.a2 = 1.0f - c.b2;
  c.decoupled = options_.weight_decay != 0.0 && options_.decoupled_weight_decay;
  c.coupled = options_.weight_decay != 0.0 && !options_.decoupled_weight_decay;
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    float* w = weights_[i].second->value.vec().data();
    const float* g = weights_[i].second->grad.vec().data();
    float* m = m_[i].vec().data();
    float* v = v_[i].vec().data();
    const long n = static_cast<long>(weights_[i].second->value.vec().size());
    if (n <= (1L << 15)) {
      adam_elements(w, g, m, v, 0, n, c);
      continue;
    }
    // Threads (OpenMP, as many as the caller allows) take contiguous slices.
#pragma omp parallel
    {
      const long threads = omp_get_num_threads(), t = omp_get_thread_num();
      adam_elements(w, g, m, v, n * t / threads, n * (t + 1) / threads, c);
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
