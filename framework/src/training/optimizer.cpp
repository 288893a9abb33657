// The optimiser base: slots shaped like the weights and their (re)storing.
#include <drape/errors.hpp>
#include <drape/training/optimizer.hpp>

#include <cmath>

namespace drape {

Optimizer::Optimizer(NamedWeights weights) : weights_(std::move(weights)) {
  for (const auto& [name, w] : weights_)
    if (!w) throw Error("optimizer: weight '" + name + "' is null");
}

void Optimizer::zero_grad() {
  for (auto& [name, w] : weights_) w->grad.set_zero();
}

std::vector<Tensor> Optimizer::zeros_like_weights() const {
  std::vector<Tensor> out;
  for (const auto& [name, w] : weights_) out.emplace_back(w->value.batch(), w->value.rows(), w->value.cols());
  return out;
}

void Optimizer::save_slot(OptimizerState& state, const std::string& slot, const std::vector<Tensor>& tensors) const {
  for (std::size_t i = 0; i < weights_.size(); ++i) state.tensors[slot + "/" + weights_[i].first] = tensors[i];
}

void Optimizer::load_slot(const OptimizerState& state, const std::string& slot, std::vector<Tensor>& tensors) const {
  std::vector<Tensor> loaded;
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    const std::string key = slot + "/" + weights_[i].first;
    const auto it = state.tensors.find(key);
    if (it == state.tensors.end()) throw ConfigError("optimizer state: missing '" + key + "'");
    const Tensor& w = weights_[i].second->value;
    if (it->second.shape() != w.shape() || it->second.batch() != w.batch())
      throw ConfigError("optimizer state: '" + key + "' is " + it->second.shape_str() + ", the weight is " + w.shape_str());
    loaded.push_back(it->second);
  }
  tensors = std::move(loaded);  // all or nothing
}

void Optimizer::check_type(const OptimizerState& state, const std::string& type) const {
  if (state.type != type) throw ConfigError("optimizer state is for '" + state.type + "', not '" + type + "'");
  if (!state.scalars.count("step")) throw ConfigError("optimizer state: missing 'step'");
}

double grad_norm(const NamedWeights& weights) {
  double sum = 0.0;
  for (const auto& [name, w] : weights) sum += w->grad.vec().cast<double>().squaredNorm();
  return std::sqrt(sum);
}

double clip_grad_norm(const NamedWeights& weights, double max_norm) {
  const double norm = grad_norm(weights);
  if (norm > max_norm && norm > 0.0) {
    const float scale = static_cast<float>(max_norm / norm);
    for (const auto& [name, w] : weights) w->grad.vec() *= scale;
  }
  return norm;
}

}  // namespace drape
