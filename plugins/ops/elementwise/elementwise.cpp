// Small element-wise graph operations: `add` sums same-shaped tensors (the
// decoder output plus the spectral residual), `scale` multiplies by a constant.
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class Add final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext&) override {
    const Shape a = in.at("a");
    for (const auto& [port, s] : in)
      if (!(s == a)) throw ConfigError("cannot add " + a.str() + " and " + s.str() + " (input '" + port + "')");
    return {{"out", a}};
  }
  void forward(const TensorIn& in, const TensorOut& out) override {
    Tensor& o = *out.at("out");
    o.vec() = in.at("a")->vec();
    for (const auto& [port, t] : in)
      if (port != "a") o.vec() += t->vec();
  }
  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    for (const auto& [port, g] : gin) g->vec() = gout.at("out")->vec();
  }
};

class Scale final : public Node {
 public:
  explicit Scale(double factor) : factor_(static_cast<float>(factor)) {}
  ShapeMap setup(const ShapeMap& in, const NodeContext&) override { return {{"out", in.at("x")}}; }
  void forward(const TensorIn& in, const TensorOut& out) override { out.at("out")->vec() = factor_ * in.at("x")->vec(); }
  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    if (auto g = gin.find("x"); g != gin.end()) g->second->vec() = factor_ * gout.at("out")->vec();
  }

 private:
  float factor_;
};

PluginList plugins() {
  PluginDescriptor add;
  add.kind = "op";
  add.name = "add";
  add.doc = "Element-wise sum of two to four tensors of one shape.";
  add.inputs = {{"a", "first term"}, {"b", "second term"}, {"c", "third term", true}, {"d", "fourth term", true}};
  add.outputs = {{"out", "the sum"}};
  add.create_node = [](const Params&) { return std::make_unique<Add>(); };

  PluginDescriptor scale;
  scale.kind = "op";
  scale.name = "scale";
  scale.doc = "Multiplies a tensor by a constant.";
  scale.inputs = {{"x", "input"}};
  scale.outputs = {{"out", "factor * x"}};
  scale.params = {{.name = "factor", .type = ParamType::Float, .default_value = "1.0",
                   .doc = "the constant"}};
  scale.create_node = [](const Params& p) { return std::make_unique<Scale>(p.get_float("factor")); };
  return {add, scale};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
