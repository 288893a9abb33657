// The original GCN (Kipf & Welling 2017) as a body encoder, the seed's "GCN
// [204]" row of Table 6.1: every layer is H' = f(A H W + b) with the fixed,
// isotropic propagation matrix A = D^-1/2 (A_body + I) D^-1/2 of the body
// mesh's vertex graph (Assets::body). No downsampling: every layer runs on all
// body vertices. Outputs follow cnn1d's convention so the encoders swap in a
// graph: `features` one row per body vertex, `global` the mean over vertices.
#include <drape/assets/assets.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/nn/graph_conv.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/mesh_graph.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class GcnEncoder final : public Node {
 public:
  GcnEncoder(std::vector<long> channels, nn::Activation activation)
      : channels_(std::move(channels)), activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape body = in.at("body");
    if (body.cols != 3) throw ConfigError("input 'body' must be [vertices, 3], got " + body.str());
    if (!context.assets || context.assets->body.num_vertices() == 0)
      throw ConfigError("gcn needs the template's assets (the body mesh's graph); none are bound");
    const Mesh& mesh = context.assets->body;
    if (body.rows != mesh.num_vertices())
      throw ConfigError("input 'body' has " + std::to_string(body.rows) + " vertices but the assets' body has " +
                        std::to_string(mesh.num_vertices()));
    vertices_ = body.rows;
    const auto propagation = std::make_shared<const nn::SparseOperator>(
        nn::kipf_adjacency(geometry::vertex_neighbours(mesh.faces, mesh.num_vertices())));
    layers_.clear();
    int width_in = 3;
    for (std::size_t l = 0; l < channels_.size(); ++l) {
      layers_.emplace_back(propagation, width_in, static_cast<int>(channels_[l]), activation_);
      width_in = static_cast<int>(channels_[l]);
    }
    for (std::size_t l = 0; l < layers_.size(); ++l)
      layers_[l].create_weights(*this, "conv" + std::to_string(l) + "_", nn::mix_seed(context.seed, l));
    return {{"features", {vertices_, width_in}}, {"global", {1, width_in}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& body = *in.at("body");
    const int batch = body.batch();
    for (std::size_t l = 0; l < layers_.size(); ++l)
      layers_[l].forward(l == 0 ? nn::ConstMatRef(body.flat()) : nn::ConstMatRef(layers_[l - 1].output()), batch);
    const MatrixRM& last = layers_.back().output();
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
    MatrixRM gx;
    for (std::size_t l = layers_.size(); l-- > 0;) {
      const nn::ConstMatRef input = l == 0 ? nn::ConstMatRef(body.flat()) : nn::ConstMatRef(layers_[l - 1].output());
      layers_[l].backward(input, g, batch, l == 0 && gbody == gin.end() ? nullptr : &gx);
      g.swap(gx);
    }
    if (gbody != gin.end()) gbody->second->flat() = g;
  }

  double flops_per_sample() const override {
    double f = 0.0;
    for (const auto& l : layers_) f += l.flops_per_sample();
    return f;
  }

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
  d.params = {{"channels", ParamType::IntList, "[32, 64, 128]", "output channels of each layer", 1, 4096},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    auto channels = p.get_int_list("channels");
    if (channels.empty()) throw ConfigError("gcn: parameter 'channels' needs at least one layer");
    return std::make_unique<GcnEncoder>(std::move(channels), nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
