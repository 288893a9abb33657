// The seed's encoder (Sec. 6.3.1): a 1D CNN over the body's vertex order, which
// for a fixed-topology body keeps most mesh neighbours within a few indices.
// Each layer convolves along the vertex order and downsamples by `stride`.
// `features` brings the last map back to one row per body vertex (nearest
// strided row) so that later nodes can gather it by body vertex index;
// `global` is the mean of the last map over its rows.
#include <drape/nn/conv1d.hpp>
#include <drape/nn/layer_stack.hpp>
#include <drape/plugin.hpp>

#include <algorithm>
#include <cmath>

namespace {

using namespace drape;

class Cnn1d final : public Node {
 public:
  Cnn1d(std::vector<long> channels, int kernel, int stride, nn::Activation activation)
      : channels_(std::move(channels)), kernel_(kernel), stride_(stride), activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape body = in.at("body");
    if (body.cols != 3) throw ConfigError("input 'body' must be [vertices, 3], got " + body.str());
    vertices_ = body.rows;
    layers_.clear();
    nn::Conv1dGeometry g{body.rows, body.cols, kernel_, stride_};
    for (std::size_t l = 0; l < channels_.size(); ++l) {
      layers_.emplace_back(g, static_cast<int>(channels_[l]), activation_);
      g = {g.out_rows(), static_cast<int>(channels_[l]), kernel_, stride_};
    }
    nn::create_stack_weights(*this, layers_, "conv", context.seed);
    last_rows_ = g.in_rows;
    // Output row o of the last map is centred on body vertex o * stride^layers.
    const double span = std::pow(double(stride_), double(layers_.size()));
    nearest_.resize(vertices_);
    for (int v = 0; v < vertices_; ++v)
      nearest_[v] = std::min(last_rows_ - 1, static_cast<int>(std::floor(v / span + 0.5)));
    const int c = static_cast<int>(channels_.back());
    return {{"features", {vertices_, c}}, {"global", {1, c}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& body = *in.at("body");
    const int batch = body.batch();
    const MatrixRM* x = &nn::forward_stack(layers_, body.flat(), batch);
    Tensor& features = *out.at("features");
    Tensor& global = *out.at("global");
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) {
      const auto last = x->middleRows(Eigen::Index(b) * last_rows_, last_rows_);
      auto f = features.mat(b);
      for (int v = 0; v < vertices_; ++v) f.row(v) = last.row(nearest_[v]);
      global.mat(b) = last.colwise().mean();
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& gf = *gout.at("features");
    const Tensor& gg = *gout.at("global");
    const int batch = gf.batch();
    MatrixRM g = MatrixRM::Zero(Eigen::Index(batch) * last_rows_, channels_.back());
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) {
      auto last = g.middleRows(Eigen::Index(b) * last_rows_, last_rows_);
      const auto f = gf.mat(b);
      for (int v = 0; v < vertices_; ++v) last.row(nearest_[v]) += f.row(v);
      last.rowwise() += gg.mat(b).row(0) / float(last_rows_);
    }
    const auto gbody = gin.find("body");
    nn::backward_stack(layers_, g, batch, gbody != gin.end());
    if (gbody != gin.end()) gbody->second->flat() = g;
  }

  double flops_per_sample() const override { return nn::stack_flops(layers_); }

 private:
  std::vector<long> channels_;
  int kernel_, stride_;
  nn::Activation activation_;
  std::vector<nn::Conv1dLayer> layers_;
  int vertices_ = 0, last_rows_ = 0;
  std::vector<int> nearest_;  // body vertex -> row of the last map
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "encoder";
  d.name = "cnn1d";
  d.doc = "1D CNN along the body's vertex order (the seed's encoder); strided layers, per-vertex and mean-pooled features.";
  d.inputs = {{"body", "body vertices [Nb, 3]"}};
  d.outputs = {{"features", "per-vertex features [Nb, C_last] (last map, nearest row per vertex)"},
               {"global", "mean of the last map over its rows [1, C_last]"}};
  d.params = {{.name = "channels", .type = ParamType::IntList, .default_value = "[32, 64, 128]",
               .doc = "output channels of each layer", .min = 1, .max = 4096},
              {.name = "kernel", .type = ParamType::Int, .default_value = "5",
               .doc = "kernel size along the vertex order", .min = 1, .max = 101},
              {.name = "stride", .type = ParamType::Int, .default_value = "2",
               .doc = "downsampling factor of each layer", .min = 1, .max = 16},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    const auto channels = p.get_int_list("channels");
    if (channels.empty()) throw ConfigError("parameter 'channels' needs at least one layer");
    return std::make_unique<Cnn1d>(channels, static_cast<int>(p.get_int("kernel")),
                                   static_cast<int>(p.get_int("stride")), nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
