#pragma once
// Point-wise activations. Derivatives are taken from the activated output, so
// a layer only keeps its output for backward (valid because every activation
// here is monotonic with a sign-preserving or invertible output).
#include <drape/nn/refs.hpp>
#include <drape/params.hpp>

#include <string>
#include <vector>

namespace drape::nn {

enum class ActivationKind { None, Relu, LeakyRelu, Tanh };

struct Activation {
  ActivationKind kind = ActivationKind::None;
  float negative_slope = 0.2f;  // leaky_relu only, in [0, 1)
};

// "none", "relu", "leaky_relu", "tanh".
const std::vector<std::string>& activation_names();
// Throws ConfigError listing the known names.
ActivationKind parse_activation(const std::string& name);
const char* to_string(ActivationKind kind);

// The two parameters every plugin with an activation declares, and how to read them.
ParamSpec activation_param(const std::string& default_name);
ParamSpec negative_slope_param();
Activation activation_from(const Params& params);

// y = f(y), in place.
void activate(const Activation& f, MatRef y);
// g *= f'(z) where y = f(z) is the stored output of activate().
void activation_backward(const Activation& f, ConstMatRef y, MatRef g);

}  // namespace drape::nn
