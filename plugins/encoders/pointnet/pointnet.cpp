// PointNet (Qi et al. 2017) as the seed's encoder ablation (Table 6.1): a dense
// MLP shared by every vertex, then max pooling over the vertices, which makes the
// global feature independent of the vertex order. With `concat_global` (the
// default, as in PointNet's segmentation network) every vertex's feature is its
// own feature followed by the global one, so per-vertex outputs see the whole body.
#include <drape/nn/dense_stack.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class PointNet final : public Node {
 public:
  PointNet(std::vector<long> widths, nn::Activation activation, bool concat_global)
      : widths_(std::move(widths)), activation_(activation), concat_(concat_global) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape body = in.at("body");
    if (body.cols != 3) throw ConfigError("input 'body' must be [vertices, 3], got " + body.str());
    vertices_ = body.rows;
    std::vector<int> sizes{3};
    for (long w : widths_) sizes.push_back(static_cast<int>(w));
    mlp_ = nn::DenseStack(sizes, activation_, activation_);
    mlp_.create_weights(*this, "mlp_", context.seed);
    const int c = mlp_.out();
    return {{"features", {vertices_, concat_ ? 2 * c : c}}, {"global", {1, c}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& body = *in.at("body");
    const int batch = body.batch(), c = mlp_.out();
    const MatrixRM& h = mlp_.forward(body.flat());
    Tensor& features = *out.at("features");
    Tensor& global = *out.at("global");
    argmax_.resize(batch, c);
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) {
      const auto hb = h.middleRows(Eigen::Index(b) * vertices_, vertices_);
      for (int k = 0; k < c; ++k) {
        Eigen::Index best = 0;
        global(b, 0, k) = hb.col(k).maxCoeff(&best);
        argmax_(b, k) = static_cast<int>(best);
      }
      auto f = features.mat(b);
      f.leftCols(c) = hb;
      if (concat_) f.rightCols(c).rowwise() = global.mat(b).row(0);
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& body = *in.at("body");
    const Tensor& gf = *gout.at("features");
    const Tensor& gg = *gout.at("global");
    const int batch = body.batch(), c = mlp_.out();
    MatrixRM gh(Eigen::Index(batch) * vertices_, c);
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) {
      auto ghb = gh.middleRows(Eigen::Index(b) * vertices_, vertices_);
      const auto f = gf.mat(b);
      ghb = f.leftCols(c);
      // The pooled value flows back to the vertex that won the max.
      Eigen::RowVectorXf gpool = gg.mat(b).row(0);
      if (concat_) gpool += f.rightCols(c).colwise().sum();
      for (int k = 0; k < c; ++k) ghb(argmax_(b, k), k) += gpool(k);
    }
    const auto gbody = gin.find("body");
    if (gbody == gin.end()) {
      mlp_.backward(body.flat(), gh, nullptr);
      return;
    }
    MatrixRM gx;
    mlp_.backward(body.flat(), gh, &gx);
    gbody->second->flat() = gx;
  }

  double flops_per_sample() const override { return vertices_ * mlp_.flops_per_row(); }

 private:
  std::vector<long> widths_;
  nn::Activation activation_;
  bool concat_;
  nn::DenseStack mlp_;
  int vertices_ = 0;
  Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> argmax_;  // [batch, C] winning vertex
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "encoder";
  d.name = "pointnet";
  d.doc = "PointNet: a per-vertex MLP shared by all vertices, then max pooling (the seed's encoder ablation).";
  d.inputs = {{"body", "body vertices [Nb, 3]"}};
  d.outputs = {{"features", "per-vertex features [Nb, C], or [Nb, 2C] = [own, global] with concat_global"},
               {"global", "max over vertices of the per-vertex features [1, C]"}};
  d.params = {{.name = "widths", .type = ParamType::IntList, .default_value = "[64, 128]",
               .doc = "widths of the shared MLP's layers (C is the last)", .min = 1, .max = 4096},
              nn::activation_param("relu"),
              nn::negative_slope_param(),
              {.name = "concat_global", .type = ParamType::Bool, .default_value = "true",
               .doc = "append the global feature to every vertex's feature"}};
  d.create_node = [](const Params& p) {
    const auto widths = p.get_int_list("widths");
    if (widths.empty()) throw ConfigError("parameter 'widths' needs at least one layer");
    return std::make_unique<PointNet>(widths, nn::activation_from(p), p.get_bool("concat_global"));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
