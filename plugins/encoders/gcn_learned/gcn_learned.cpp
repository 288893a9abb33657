// The seed's GCN with learned per-vertex aggregation (eq. 6.4) used as a body
// encoder, the "GCN (mine)" row of Table 6.1: the decoder's up-sampling
// replaced by downsampling. The body has no UVs and no hierarchy, but its
// vertex order is spatially coherent (consecutive indices are mostly mesh
// neighbours, Sec. 6.3.1), so a coarser scale pools blocks of `stride`
// consecutive vertices (mean), and its graph joins two blocks when any of
// their vertices are adjacent.
//
// Layer l runs at scale l: y = f(A_theta x W + b) with A_theta learned on that
// scale's 1-ring + self pattern (initially the neighbourhood mean); the
// scales are pooled between layers, so the last map has ceil(Nb / stride^(L-1))
// rows. Outputs follow cnn1d's convention (swappable in a graph): `features`
// gives every body vertex the row of the block that contains it, `global` is
// the mean of the last map over its rows.
#include <drape/geometry/adjacency.hpp>
#include <drape/nn/body_graph_input.hpp>
#include <drape/nn/graph_conv.hpp>
#include <drape/nn/layer_stack.hpp>
#include <drape/nn/mesh_graph.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class LearnedGcnEncoder final : public Node {
 public:
  LearnedGcnEncoder(std::vector<long> channels, int stride, nn::Activation activation)
      : channels_(std::move(channels)), stride_(stride), activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Mesh& mesh = nn::check_body_graph_input(in, context, "gcn_learned");
    vertices_ = mesh.num_vertices();
    nn::Neighbours graph = geometry::vertex_neighbours(mesh.faces, mesh.num_vertices());
    layers_.clear();
    pools_.assign(channels_.size(), nn::SparseOperator());
    rows_.assign(channels_.size(), vertices_);
    int width_in = 3;
    for (std::size_t l = 0; l < channels_.size(); ++l) {
      if (l > 0) {
        nn::BlockPooling pooled = nn::pool_consecutive(graph, stride_);
        pools_[l] = nn::SparseOperator(std::move(pooled.pool));
        graph = std::move(pooled.neighbours);
        rows_[l] = pools_[l].rows();
      }
      layers_.emplace_back(nn::ring_mean(graph), width_in, static_cast<int>(channels_[l]), activation_);
      width_in = static_cast<int>(channels_[l]);
    }
    nn::create_stack_weights(*this, layers_, "conv", context.seed);
    // Block of the last scale that holds each body vertex: floor(v / stride^(L-1)).
    block_.resize(static_cast<std::size_t>(vertices_));
    for (int v = 0; v < vertices_; ++v) {
      int row = v;
      for (std::size_t l = 1; l < layers_.size(); ++l) row /= stride_;
      block_[std::size_t(v)] = row;
    }
    pooled_.assign(layers_.size(), MatrixRM());
    return {{"features", {vertices_, width_in}}, {"global", {1, width_in}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& body = *in.at("body");
    const int batch = body.batch();
    for (std::size_t l = 0; l < layers_.size(); ++l) {
      if (l > 0) {
        const MatrixRM& finer = layers_[l - 1].output();
        pooled_[l].resize(Eigen::Index(batch) * rows_[l], finer.cols());
        pools_[l].apply(finer, batch, pooled_[l]);
      }
      layers_[l].forward(input_of(l, body), batch);
    }
    const MatrixRM& last = layers_.back().output();
    const Eigen::Index rows = rows_.back();
    Tensor& features = *out.at("features");
    Tensor& global = *out.at("global");
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) {
      const auto map = last.middleRows(b * rows, rows);
      auto f = features.mat(b);
      for (int v = 0; v < vertices_; ++v) f.row(v) = map.row(block_[std::size_t(v)]);
      global.mat(b) = map.colwise().mean();
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& body = *in.at("body");
    const Tensor& gf = *gout.at("features");
    const Tensor& gg = *gout.at("global");
    const int batch = body.batch();
    const Eigen::Index rows = rows_.back();
    MatrixRM g = MatrixRM::Zero(batch * rows, layers_.back().out());
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) {
      auto map = g.middleRows(b * rows, rows);
      const auto f = gf.mat(b);
      for (int v = 0; v < vertices_; ++v) map.row(block_[std::size_t(v)]) += f.row(v);
      map.rowwise() += gg.mat(b).row(0) / float(rows);
    }
    const auto gbody = gin.find("body");
    MatrixRM gx;
    for (std::size_t l = layers_.size(); l-- > 0;) {
      layers_[l].backward(input_of(l, body), g, batch, l == 0 && gbody == gin.end() ? nullptr : &gx);
      g.swap(gx);
      if (l > 0) {
        gx.resize(Eigen::Index(batch) * rows_[l - 1], g.cols());
        pools_[l].apply_transpose(g, batch, gx);
        g.swap(gx);
      }
    }
    if (gbody != gin.end()) gbody->second->flat() = g;
  }

  double flops_per_sample() const override {
    double f = 0.0;
    for (std::size_t l = 0; l < layers_.size(); ++l) {
      f += layers_[l].flops_per_sample();
      if (l > 0) f += double(pools_[l].nonzeros()) * layers_[l].in();
    }
    return f;
  }

 private:
  // What layer l multiplies: the body, or the pooled output of layer l - 1.
  ConstMatrixMap input_of(std::size_t l, const Tensor& body) const {
    if (l == 0) return body.flat();
    return {pooled_[l].data(), pooled_[l].rows(), pooled_[l].cols()};
  }

  std::vector<long> channels_;
  int stride_;
  nn::Activation activation_;
  std::vector<nn::GraphConvLayer> layers_;
  std::vector<nn::SparseOperator> pools_;  // [l]: scale l-1 -> scale l (empty for 0)
  std::vector<int> rows_;                  // vertices of each scale
  std::vector<MatrixRM> pooled_;           // the pooled input of each layer (l > 0)
  std::vector<int> block_;                 // body vertex -> row of the last map
  int vertices_ = 0;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "encoder";
  d.name = "gcn_learned";
  d.doc = "The seed's learned-aggregation GCN (eq. 6.4) as a body encoder, pooling consecutive vertex blocks between layers.";
  d.inputs = {{"body", "body vertices [Nb, 3] (the assets' body topology)"}};
  d.outputs = {{"features", "per-vertex features [Nb, C_last] (the last map's row of the block holding the vertex)"},
               {"global", "mean of the last map over its rows [1, C_last]"}};
  d.params = {{.name = "channels", .type = ParamType::IntList, .default_value = "[32, 64, 128]",
               .doc = "output channels of each layer (one scale each)", .min = 1, .max = 4096},
              {.name = "stride", .type = ParamType::Int, .default_value = "2",
               .doc = "consecutive vertices pooled into one between layers", .min = 1, .max = 64},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    auto channels = p.get_int_list("channels");
    if (channels.empty()) throw ConfigError("parameter 'channels' needs at least one layer");
    return std::make_unique<LearnedGcnEncoder>(std::move(channels), static_cast<int>(p.get_int("stride")),
                                               nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
