// The original GCN (Kipf & Welling 2017) as a garment decoder, the seed's
// "GCN (original)" row of Table 6.2: layers H' = f(A H W + b) with the fixed,
// isotropic A = D^-1/2 (A_garment + I) D^-1/2 of the garment mesh's vertex
// graph (Assets::garment), all at the garment's resolution, then a dense head
// to 3 coordinates per vertex (no activation).
#include <drape/assets/assets.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/nn/dense_stack.hpp>
#include <drape/nn/graph_conv.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/mesh_graph.hpp>
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
    const auto propagation = std::make_shared<const nn::SparseOperator>(
        nn::kipf_adjacency(geometry::vertex_neighbours(mesh.faces, mesh.num_vertices())));
    layers_.clear();
    int width_in = x.cols;
    for (std::size_t l = 0; l < channels_.size(); ++l) {
      layers_.emplace_back(propagation, width_in, static_cast<int>(channels_[l]), activation_);
      width_in = static_cast<int>(channels_[l]);
    }
    for (std::size_t l = 0; l < layers_.size(); ++l)
      layers_[l].create_weights(*this, "conv" + std::to_string(l) + "_", nn::mix_seed(context.seed, l));
    head_ = nn::DenseStack({width_in, 3}, nn::Activation{}, nn::Activation{});
    head_.create_weights(*this, "out_", nn::mix_seed(context.seed, 999));
    return {{"out", {vertices_, 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    for (std::size_t l = 0; l < layers_.size(); ++l) layers_[l].forward(input_of(l, x), x.batch());
    out.at("out")->flat() = head_.forward(layers_.back().output());
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("x");
    const auto gx_port = gin.find("x");
    MatrixRM g, gx;
    head_.backward(layers_.back().output(), gout.at("out")->flat(), &g);
    for (std::size_t l = layers_.size(); l-- > 0;) {
      layers_[l].backward(input_of(l, x), g, x.batch(), l == 0 && gx_port == gin.end() ? nullptr : &gx);
      g.swap(gx);
    }
    if (gx_port != gin.end()) gx_port->second->flat() = g;
  }

  double flops_per_sample() const override {
    double f = double(vertices_) * head_.flops_per_row();
    for (const auto& l : layers_) f += l.flops_per_sample();
    return f;
  }

 private:
  ConstMatrixMap input_of(std::size_t l, const Tensor& x) const {
    if (l == 0) return x.flat();
    const MatrixRM& m = layers_[l - 1].output();
    return {m.data(), m.rows(), m.cols()};
  }

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
  d.params = {{"channels", ParamType::IntList, "[64, 64, 32, 32]", "output channels of each graph convolution", 1, 4096},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    auto channels = p.get_int_list("channels");
    if (channels.empty()) throw ConfigError("gcn_decoder: parameter 'channels' needs at least one layer");
    return std::make_unique<GcnDecoder>(std::move(channels), nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
