// The original GCN (Kipf & Welling 2017) as a body encoder, the seed's "GCN
// [204]" row of Table 6.1: every layer is H' = f(A H W + b) with the fixed,
// isotropic propagation matrix A = D^-1/2 (A_body + I) D^-1/2 of the body
// mesh's vertex graph (Assets::body). No downsampling: every layer runs on all
// body vertices. Outputs follow cnn1d's convention so the encoders swap in a
// graph: `features` one row per body vertex, `global` the mean over vertices.
#include <drape/nn/body_graph_input.hpp>
#include <drape/nn/graph_conv_stack.hpp>
#include <drape/nn/layer_stack.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class GcnEncoder final : public Node {
 public:
  GcnEncoder(std::vector<long> channels, nn::Activation activation)
      : channels_(std::move(channels)), activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Mesh& mesh = nn::check_body_graph_input(in, context, "gcn");
    vertices_ = mesh.num_vertices();
    layers_ = nn::kipf_stack(mesh, 3, channels_, activation_);
    nn::create_stack_weights(*this, layers_, "conv", context.seed);
    const int width = layers_.back().out();
    return {{"features", {vertices_, width}}, {"global", {1, width}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& body = *in.at("body");
    const int batch = body.batch();
    const MatrixRM& last = nn::forward_graph_stack(layers_, body.flat(), batch);
    out.at("features")->flat() = last;
    Tensor& global = *out.at("global");
    for (int b = 0; b < batch; ++b) global.mat(b) = last.middleRows(Eigen::Index(b) * vertices_, vertices_).colwise().mean();
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& body = *in.at("body");
    const Tensor& gg = *gout.at("global");
    const int batch = body.batch();
    // features are the last map itself; global spreads its gradient evenly over the vertices.
    MatrixRM g = gout.at("features")->flat();
    for (int b = 0; b < batch; ++b)
      g.middleRows(Eigen::Index(b) * vertices_, vertices_).rowwise() += gg.mat(b).row(0) / float(vertices_);
    const auto gbody = gin.find("body");
    nn::backward_graph_stack(layers_, body.flat(), g, batch, gbody != gin.end());
    if (gbody != gin.end()) gbody->second->flat() = g;
  }

  double flops_per_sample() const override { return nn::stack_flops(layers_); }

 private:
  std::vector<long> channels_;
  nn::Activation activation_;
  std::vector<nn::GraphConvLayer> layers_;
  int vertices_ = 0;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "encoder";
  d.name = "gcn";
  d.doc = "The original GCN (Kipf & Welling) on the body mesh: fixed symmetric-normalised aggregation with self loops.";
  d.inputs = {{"body", "body vertices [Nb, 3] (the assets' body topology)"}};
  d.outputs = {{"features", "per-vertex features of the last layer [Nb, C_last]"},
               {"global", "mean of the last layer over the vertices [1, C_last]"}};
  d.params = {{.name = "channels", .type = ParamType::IntList, .default_value = "[32, 64, 128]",
               .doc = "output channels of each layer", .min = 1, .max = 4096},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    auto channels = p.get_int_list("channels");
    if (channels.empty()) throw ConfigError("parameter 'channels' needs at least one layer");
    return std::make_unique<GcnEncoder>(std::move(channels), nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
