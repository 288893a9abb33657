// The seed's 1D CNN decoder ablation (Table 6.2): convolutions along the
// garment's vertex order. The template's vertices are ordered by lattice rows,
// panel by panel (docs/garments.md), so index neighbours are mostly mesh
// neighbours and a kernel of k taps sees a strip of about k vertices of one
// row; neighbours in the next row are ~a row length away and unseen, which is
// why this decoder is a weak baseline. Stride 1 and "same" padding keep one
// output row per vertex: hidden layers with `channels`, then a linear
// convolution to 3 coordinates.
#include <drape/assets/assets.hpp>
#include <drape/nn/conv1d.hpp>
#include <drape/nn/layer_stack.hpp>
#include <drape/plugin.hpp>

#include <string>
#include <vector>

namespace {

using namespace drape;

class Cnn1dDecoder final : public Node {
 public:
  Cnn1dDecoder(std::vector<long> channels, int kernel, nn::Activation activation)
      : channels_(std::move(channels)), kernel_(kernel), activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape x = in.at("x");
    if (x.rows < 1 || x.cols < 1) throw ConfigError("input 'x' is empty: " + x.str());
    if (context.assets && context.assets->garment && x.rows != context.assets->garment->mesh.num_vertices())
      throw ConfigError("input 'x' must have one row per garment vertex (" +
                        std::to_string(context.assets->garment->mesh.num_vertices()) + "), got " + x.str());
    rows_ = x.rows;
    layers_.clear();
    int in_channels = x.cols;
    for (long c : channels_) {
      layers_.emplace_back(nn::Conv1dGeometry{rows_, in_channels, kernel_, 1}, static_cast<int>(c), activation_);
      in_channels = static_cast<int>(c);
    }
    layers_.emplace_back(nn::Conv1dGeometry{rows_, in_channels, kernel_, 1}, 3, nn::Activation{});
    nn::create_stack_weights(*this, layers_, "conv", context.seed);
    return {{"out", {rows_, 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    out.at("out")->flat() = nn::forward_stack(layers_, x.flat(), x.batch());
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const int batch = in.at("x")->batch();
    MatrixRM g = gout.at("out")->flat();
    const auto gx = gin.find("x");
    nn::backward_stack(layers_, g, batch, gx != gin.end());
    if (gx != gin.end()) gx->second->flat() = g;
  }

  double flops_per_sample() const override { return nn::stack_flops(layers_); }

 private:
  std::vector<long> channels_;
  int kernel_;
  nn::Activation activation_;
  int rows_ = 0;
  std::vector<nn::Conv1dLayer> layers_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "decoder";
  d.name = "cnn1d_decoder";
  d.doc = "1D CNN along the garment's vertex order (the seed's 1D CNN decoder ablation): stride 1, one output row per vertex.";
  d.inputs = {{"x", "per-garment-vertex features [Ng, C] (e.g. body features gathered through the correspondences)"}};
  d.outputs = {{"out", "garment vertices or offsets [Ng, 3]"}};
  d.params = {{.name = "channels", .type = ParamType::IntList, .default_value = "[32, 32]",
               .doc = "output channels of the hidden layers (may be empty: [])", .min = 1, .max = 4096},
              {.name = "kernel", .type = ParamType::Int, .default_value = "5",
               .doc = "kernel size along the vertex order (odd keeps it centred)", .min = 1, .max = 101},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    return std::make_unique<Cnn1dDecoder>(p.get_int_list("channels"), static_cast<int>(p.get_int("kernel")),
                                          nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
