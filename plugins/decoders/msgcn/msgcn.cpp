// The seed's multi-scale GCN decoder (Sec. 6.3.2). Graph convolutions whose
// aggregation weights are learned per vertex and per neighbour, independent of
// the features (eq. 6.4: A[i, j] = theta[i, j] on each vertex's 1-ring and
// itself), run on the garment hierarchy from the coarsest level to the garment,
// with barycentric up-sampling in UV space between levels
// (Assets::hierarchy, HierarchyLevel::upsample).
//
// Input. The chapter feeds "the encoded features to a coarsened mesh" so that
// global features spread over broad regions of the garment; the decoder then
// only up-samples. The garment features gathered from the body [Ng, C] are
// therefore pooled once to the coarsest level used, through the restrictions
// matched to the up-samplings (R = diag(1/colsum U) U^T per level, composed):
// each coarse vertex takes the average of the fine features that interpolate
// from it. There are no per-level skip inputs.
//
// Each level: `layers` graph convolutions to that level's `channels`
// (y = f(A_theta x W + b)); between levels x <- U x. After the garment level a
// dense head maps every vertex's features to 3 coordinates (no activation).
#include <drape/assets/assets.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/nn/dense_stack.hpp>
#include <drape/nn/graph_conv.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/mesh_graph.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class MultiScaleGcn final : public Node {
 public:
  MultiScaleGcn(std::vector<long> channels, std::vector<long> layers, nn::Activation activation)
      : channels_(std::move(channels)), layers_per_level_(std::move(layers)), activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape x = in.at("x");
    if (!context.assets || context.assets->hierarchy.levels.empty())
      throw ConfigError("msgcn needs the garment template's assets (its hierarchy); none are bound");
    const geometry::Hierarchy& h = context.assets->hierarchy;
    const int levels = static_cast<int>(channels_.size());
    if (levels > h.num_levels())
      throw ConfigError("parameter 'channels' has " + std::to_string(levels) +
                        " entries (one per level, coarsest first) but the hierarchy has " +
                        std::to_string(h.num_levels()) + " levels");
    if (layers_per_level_.size() != 1 && static_cast<int>(layers_per_level_.size()) != levels)
      throw ConfigError("parameter 'layers' needs one entry (every level) or one per level (" +
                        std::to_string(levels) + "), got " + std::to_string(layers_per_level_.size()));
    const int garment = h.levels[0].mesh.num_vertices();
    if (x.rows != garment || x.cols < 1)
      throw ConfigError("input 'x' must be [garment vertices = " + std::to_string(garment) + ", C], got " + x.str());
    in_channels_ = x.cols;

    // Stage i runs on hierarchy level levels-1-i (coarsest first).
    vertices_.assign(static_cast<std::size_t>(levels), 0);
    for (int i = 0; i < levels; ++i) vertices_[std::size_t(i)] = h.levels[std::size_t(levels - 1 - i)].mesh.num_vertices();
    upsample_.assign(static_cast<std::size_t>(levels), nn::SparseOperator());
    for (int i = 1; i < levels; ++i) upsample_[std::size_t(i)] = nn::SparseOperator(h.levels[std::size_t(levels - 1 - i)].upsample);
    if (levels > 1) {
      nn::SparseRM pool = nn::restriction_of(h.levels[0].upsample);
      for (int l = 1; l + 1 < levels; ++l) pool = nn::SparseRM(nn::restriction_of(h.levels[std::size_t(l)].upsample) * pool);
      pool_ = nn::SparseOperator(std::move(pool));
    }

    stages_.assign(static_cast<std::size_t>(levels), {});
    int channels_in = in_channels_;
    for (int i = 0; i < levels; ++i) {
      const int level = levels - 1 - i;
      const Mesh& mesh = h.levels[std::size_t(level)].mesh;
      const nn::SparseRM pattern = nn::ring_mean(geometry::vertex_neighbours(mesh.faces, mesh.num_vertices()));
      const int width = static_cast<int>(channels_[std::size_t(i)]);
      const long count = layers_per_level_.size() == 1 ? layers_per_level_[0] : layers_per_level_[std::size_t(i)];
      for (long k = 0; k < count; ++k) {
        stages_[std::size_t(i)].emplace_back(pattern, channels_in, width, activation_);
        channels_in = width;
      }
      for (long k = 0; k < count; ++k)
        stages_[std::size_t(i)][std::size_t(k)].create_weights(
            *this, "level" + std::to_string(level) + "_conv" + std::to_string(k) + "_",
            nn::mix_seed(context.seed, std::uint64_t(100 * level + k)));
    }
    head_ = nn::DenseStack({channels_in, 3}, nn::Activation{}, nn::Activation{});
    head_.create_weights(*this, "out_", nn::mix_seed(context.seed, 999));
    stage_input_.assign(static_cast<std::size_t>(levels), MatrixRM());
    return {{"out", {garment, 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    const int batch = x.batch();
    for (std::size_t i = 0; i < stages_.size(); ++i) {
      MatrixRM& input = stage_input_[i];
      if (i > 0) {
        const MatrixRM& coarser = stages_[i - 1].back().output();
        input.resize(Eigen::Index(batch) * vertices_[i], coarser.cols());
        upsample_[i].apply(coarser, batch, input);
      } else if (stages_.size() > 1) {
        input.resize(Eigen::Index(batch) * vertices_[0], in_channels_);
        pool_.apply(x.flat(), batch, input);
      }
      for (std::size_t k = 0; k < stages_[i].size(); ++k) stages_[i][k].forward(layer_input(i, k, x), batch);
    }
    out.at("out")->flat() = head_.forward(stages_.back().back().output());
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("x");
    const int batch = x.batch();
    const auto gx_port = gin.find("x");
    const bool wants_gx = gx_port != gin.end();
    MatrixRM g, gx;
    head_.backward(stages_.back().back().output(), gout.at("out")->flat(), &g);
    for (std::size_t i = stages_.size(); i-- > 0;) {
      for (std::size_t k = stages_[i].size(); k-- > 0;) {
        const bool first = i == 0 && k == 0;
        stages_[i][k].backward(layer_input(i, k, x), g, batch, first && !wants_gx ? nullptr : &gx);
        g.swap(gx);
      }
      if (i > 0) {
        gx.resize(Eigen::Index(batch) * vertices_[i - 1], g.cols());
        upsample_[i].apply_transpose(g, batch, gx);
        g.swap(gx);
      }
    }
    if (!wants_gx) return;
    if (stages_.size() > 1) pool_.apply_transpose(g, batch, gx_port->second->flat());
    else gx_port->second->flat() = g;
  }

  double flops_per_sample() const override {
    double f = 0.0;
    const int levels = static_cast<int>(stages_.size());
    for (int i = 0; i < levels; ++i) {
      const int width_in = i == 0 ? in_channels_ : stages_[std::size_t(i - 1)].back().out();
      if (i == 0 && levels > 1) f += double(pool_.nonzeros()) * width_in;
      if (i > 0) f += double(upsample_[std::size_t(i)].nonzeros()) * width_in;
      for (const auto& layer : stages_[std::size_t(i)]) f += layer.flops_per_sample();
    }
    return f + double(vertices_.back()) * head_.flops_per_row();
  }

 private:
  // What layer k of stage i multiplies: the previous layer's output, else the
  // stage's pooled or up-sampled input (x itself when one level is used).
  ConstMatrixMap layer_input(std::size_t i, std::size_t k, const Tensor& x) const {
    if (k > 0) {
      const MatrixRM& m = stages_[i][k - 1].output();
      return {m.data(), m.rows(), m.cols()};
    }
    if (stages_.size() == 1) return x.flat();
    return {stage_input_[i].data(), stage_input_[i].rows(), stage_input_[i].cols()};
  }

  std::vector<long> channels_, layers_per_level_;
  nn::Activation activation_;
  int in_channels_ = 0;
  std::vector<int> vertices_;                        // per stage, coarsest first
  nn::SparseOperator pool_;                          // garment -> coarsest stage
  std::vector<nn::SparseOperator> upsample_;         // [i]: stage i-1 -> stage i (empty for 0)
  std::vector<std::vector<nn::GraphConvLayer>> stages_;
  nn::DenseStack head_;
  std::vector<MatrixRM> stage_input_;                // pooled / up-sampled input of each stage
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "decoder";
  d.name = "msgcn";
  d.doc = "The seed's multi-scale GCN decoder: learned per-vertex aggregation (eq. 6.4) on the garment hierarchy, "
          "coarsest first, UV-barycentric up-sampling between levels.";
  d.inputs = {{"x", "garment features [Ng, C] (gathered from the body), pooled to the coarsest level"}};
  d.outputs = {{"out", "per garment vertex [Ng, 3] (a displacement or positions, as the graph uses it)"}};
  d.params = {{.name = "channels", .type = ParamType::IntList, .default_value = "[64, 64, 32, 32]",
               .doc = "channels of each level, coarsest first; its length is the number of levels used (at most the hierarchy's)",
               .min = 1, .max = 4096},
              {.name = "layers", .type = ParamType::IntList, .default_value = "[2]",
               .doc = "graph convolutions per level: one entry for all levels or one per level", .min = 1, .max = 16},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    auto channels = p.get_int_list("channels");
    auto layers = p.get_int_list("layers");
    if (channels.empty()) throw ConfigError("parameter 'channels' needs at least one level");
    if (layers.empty()) throw ConfigError("parameter 'layers' needs at least one entry");
    return std::make_unique<MultiScaleGcn>(std::move(channels), std::move(layers), nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
