#pragma once
// First-order optimisers over a graph's weights (Graph::weights()), plus the
// learning-rate schedules of schedule.hpp. An optimiser only reads each
// weight's grad; zeroing gradients and choosing the rate stay with the caller:
//
//   Adam adam(graph.weights());
//   for (long epoch = 0; ...; ++epoch)
//     for (batch ...) { graph.zero_grad(); graph.forward(b); graph.backward();
//                       adam.step(schedule.at(epoch) * plateau.scale()); }
//
// state()/set_state() expose the moments so a checkpoint resumes exactly.
#include <drape/node.hpp>
#include <drape/training/schedule.hpp>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace drape {

using NamedWeights = std::vector<std::pair<std::string, Weight*>>;

// Everything an optimiser needs to continue: per-weight tensors named
// "<slot>/<weight name>" ("m/encoder/w") and scalars ("step").
struct OptimizerState {
  std::string type;  // "adam", "sgd"
  std::map<std::string, double> scalars;
  std::map<std::string, Tensor> tensors;
};

class Optimizer {
 public:
  explicit Optimizer(NamedWeights weights);
  virtual ~Optimizer() = default;

  // One update from the current gradients with the given learning rate.
  virtual void step(double learning_rate) = 0;
  long steps() const { return steps_; }
  const NamedWeights& weights() const { return weights_; }
  void zero_grad();

  virtual OptimizerState state() const = 0;
  // ConfigError naming what does not fit (another optimiser, a missing or
  // differently shaped tensor).
  virtual void set_state(const OptimizerState& state) = 0;

 protected:
  // Per-weight slot tensors, zero, shaped like the weights.
  std::vector<Tensor> zeros_like_weights() const;
  void save_slot(OptimizerState& state, const std::string& slot, const std::vector<Tensor>& tensors) const;
  void load_slot(const OptimizerState& state, const std::string& slot, std::vector<Tensor>& tensors) const;
  void check_type(const OptimizerState& state, const std::string& type) const;

  NamedWeights weights_;
  long steps_ = 0;
};

struct AdamOptions {
  double beta1 = 0.9;
  double beta2 = 0.999;
  double epsilon = 1e-8;
  double weight_decay = 0.0;
  bool decoupled_weight_decay = true;  // AdamW (decay applied to the weight), else L2 added to the gradient
  bool bias_correction = true;
};

class Adam final : public Optimizer {
 public:
  explicit Adam(NamedWeights weights, const AdamOptions& options = {});
  void step(double learning_rate) override;
  OptimizerState state() const override;
  void set_state(const OptimizerState& state) override;

 private:
  AdamOptions options_;
  std::vector<Tensor> m_, v_;  // first and second moments
};

struct SgdOptions {
  double momentum = 0.0;
  bool nesterov = false;
  double weight_decay = 0.0;  // L2, added to the gradient
};

class SGD final : public Optimizer {
 public:
  explicit SGD(NamedWeights weights, const SgdOptions& options = {});
  void step(double learning_rate) override;
  OptimizerState state() const override;
  void set_state(const OptimizerState& state) override;

 private:
  SgdOptions options_;
  std::vector<Tensor> velocity_;
};

// The L2 norm of all gradients together.
double grad_norm(const NamedWeights& weights);
// Scales all gradients so their joint norm is at most max_norm; returns the norm before.
double clip_grad_norm(const NamedWeights& weights, double max_norm);

}  // namespace drape
