#include <drape/errors.hpp>
#include <drape/nn/activation.hpp>

namespace drape::nn {

const std::vector<std::string>& activation_names() {
  static const std::vector<std::string> names{"none", "relu", "leaky_relu", "tanh"};
  return names;
}

ActivationKind parse_activation(const std::string& name) {
  if (name == "none") return ActivationKind::None;
  if (name == "relu") return ActivationKind::Relu;
  if (name == "leaky_relu") return ActivationKind::LeakyRelu;
  if (name == "tanh") return ActivationKind::Tanh;
  throw ConfigError("unknown activation '" + name + "' (known: none, relu, leaky_relu, tanh)" +
                    did_you_mean(name, activation_names()));
}

const char* to_string(ActivationKind kind) {
  switch (kind) {
    case ActivationKind::None: return "none";
    case ActivationKind::Relu: return "relu";
    case ActivationKind::LeakyRelu: return "leaky_relu";
    case ActivationKind::Tanh: return "tanh";
  }
  return "?";
}

ParamSpec activation_param(const std::string& default_name) {
  return {"activation", ParamType::String, default_name, "point-wise activation", {}, {}, activation_names()};
}

ParamSpec negative_slope_param() {
  // The upper bound keeps leaky_relu monotonic with a sign-preserving output,
  // which activation_backward relies on.
  return {"negative_slope", ParamType::Float, "0.2", "slope of leaky_relu for negative inputs", 0.0, 0.99};
}

Activation activation_from(const Params& params) {
  return {parse_activation(params.get_string("activation")), static_cast<float>(params.get_float("negative_slope"))};
}

void activate(const Activation& f, MatRef y) {
  auto a = y.array();
  switch (f.kind) {
    case ActivationKind::None: return;
    case ActivationKind::Relu: a = a.max(0.0f); return;
    case ActivationKind::LeakyRelu: a = (a > 0.0f).select(a, f.negative_slope * a); return;
    case ActivationKind::Tanh: a = a.tanh(); return;
  }
}

void activation_backward(const Activation& f, ConstMatRef y, MatRef g) {
  auto ga = g.array();
  const auto ya = y.array();
  switch (f.kind) {
    case ActivationKind::None: return;
    case ActivationKind::Relu: ga = (ya > 0.0f).select(ga, 0.0f); return;
    case ActivationKind::LeakyRelu: ga = (ya > 0.0f).select(ga, f.negative_slope * ga); return;
    case ActivationKind::Tanh: ga *= 1.0f - ya.square(); return;
  }
}

}  // namespace drape::nn
