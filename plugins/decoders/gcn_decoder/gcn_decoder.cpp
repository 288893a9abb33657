// The original GCN (Kipf & Welling 2017) as a garment decoder, the seed's
// "GCN (original)" row of Table 6.2: layers H' = f(A H W + b) with the fixed,
// isotropic A = D^-1/2 (A_garment + I) D^-1/2 of the garment mesh's vertex
// graph (Assets::garment), all at the garment's resolution, then a dense head
// to 3 coordinates per vertex (no activation).
#include <drape/assets/assets.hpp>
#include <drape/nn/dense_stack.hpp>
#include <drape/nn/graph_conv_stack.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/layer_stack.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class GcnDecoder final : public Node {
 public:
  GcnDecoder(std::vector<long> channels, nn::Activation activation)
      : channels_(std::move(channels)), activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape x = in.at("x");
    if (!context.assets || !context.assets->garment)
      throw ConfigError("gcn_decoder needs the garment template's assets (the garment mesh's graph); none are bound");
    const Mesh& mesh = context.assets->garment->mesh;
    if (x.rows != mesh.num_vertices() || x.cols < 1)
      throw ConfigError("input 'x' must be [garment vertices = " + std::to_string(mesh.num_vertices()) + ", C], got " +
                        x.str());
    vertices_ = x.rows;
    layers_ = nn::kipf_stack(mesh, x.cols, channels_, activation_);
    nn::create_stack_weights(*this, layers_, "conv", context.seed);
    head_ = nn::DenseStack({layers_.back().out(), 3}, nn::Activation{}, nn::Activation{});
    head_.create_weights(*this, "out_", nn::mix_seed(context.seed, 999));
    return {{"out", {vertices_, 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    out.at("out")->flat() = head_.forward(nn::forward_graph_stack(layers_, x.flat(), x.batch()));
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("x");
    const auto gx_port = gin.find("x");
    MatrixRM g;
    head_.backward(layers_.back().output(), gout.at("out")->flat(), &g);
    nn::backward_graph_stack(layers_, x.flat(), g, x.batch(), gx_port != gin.end());
    if (gx_port != gin.end()) gx_port->second->flat() = g;
  }

  double flops_per_sample() const override {
    return nn::stack_flops(layers_, double(vertices_) * head_.flops_per_row());
  }

 private:
  std::vector<long> channels_;
  nn::Activation activation_;
  std::vector<nn::GraphConvLayer> layers_;
  nn::DenseStack head_;
  int vertices_ = 0;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "decoder";
  d.name = "gcn_decoder";
  d.doc = "The original GCN (Kipf & Welling) on the garment mesh, then a dense head to [Ng, 3].";
  d.inputs = {{"x", "garment features [Ng, C] (gathered from the body)"}};
  d.outputs = {{"out", "per garment vertex [Ng, 3] (a displacement or positions, as the graph uses it)"}};
  d.params = {{.name = "channels", .type = ParamType::IntList, .default_value = "[64, 64, 32, 32]",
               .doc = "output channels of each graph convolution", .min = 1, .max = 4096},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    auto channels = p.get_int_list("channels");
    if (channels.empty()) throw ConfigError("parameter 'channels' needs at least one layer");
    return std::make_unique<GcnDecoder>(std::move(channels), nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
