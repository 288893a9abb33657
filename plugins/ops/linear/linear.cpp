// A dense layer applied to every row: [R, Cin] -> [R, width], optionally followed
// by an activation. This is the seed's "1-layer MLP" that transforms the body
// features before they are distributed to the garment vertices.
#include <drape/nn/dense_stack.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class Linear final : public Node {
 public:
  Linear(int width, nn::Activation activation, bool zero) : width_(width), activation_(activation), zero_(zero) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape x = in.at("x");
    if (x.rows < 1 || x.cols < 1) throw ConfigError("input 'x' is empty: " + x.str());
    rows_ = x.rows;
    layer_ = nn::DenseStack({x.cols, width_}, activation_, activation_);
    layer_.create_weights(*this, "", context.seed);
    // A branch added to a trained model (drape train --init-widen) starts as
    // nothing: its last layer at zero, so the first prediction is the model's.
    if (zero_)
      for (auto& [name, w] : weights()) w.value.vec().setZero();
    return {{"out", {x.rows, width_}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    out.at("out")->flat() = layer_.forward(in.at("x")->flat());
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const auto gx = gin.find("x");
    if (gx == gin.end()) {
      layer_.backward(in.at("x")->flat(), gout.at("out")->flat(), nullptr);
      return;
    }
    layer_.backward_into(in.at("x")->flat(), gout.at("out")->flat(), gx->second->flat());
  }

  double flops_per_sample() const override { return rows_ * layer_.flops_per_row(); }

 private:
  int width_;
  nn::Activation activation_;
  bool zero_;
  nn::DenseStack layer_;
  int rows_ = 0;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "linear";
  d.doc = "Per-row dense layer [R, Cin] -> [R, width] with an optional activation (the seed's 1-layer MLP transfer).";
  d.inputs = {{"x", "features [R, Cin]"}};
  d.outputs = {{"out", "features [R, width]"}};
  d.params = {{.name = "width", .type = ParamType::Int, .default_value = "64",
               .doc = "output channels", .min = 1, .max = 65536},
              nn::activation_param("none"),
              nn::negative_slope_param(),
              {.name = "init", .type = ParamType::String, .default_value = "random",
               .doc = "random: He-initialised weights, zero bias; zero: every weight zero (a branch added to a trained "
                      "model that starts as nothing, its gradient still reaching the weights)",
               .choices = {"random", "zero"}}};
  d.create_node = [](const Params& p) {
    return std::make_unique<Linear>(static_cast<int>(p.get_int("width")), nn::activation_from(p), p.get_string("init") == "zero");
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
