// The MLP decoder: each sample's input [R, C] is flattened to one vector and
// mapped by dense layers to `rows` x 3 coordinates. It is the seed's MLP decoder
// ablation (Table 6.2) and TailorNet's low-frequency MLP. Every output vertex
// depends on every input entry, so the parameter count grows with R*C*width.
#include <drape/assets/assets.hpp>
#include <drape/nn/dense_stack.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class MlpDecoder final : public Node {
 public:
  MlpDecoder(std::vector<long> widths, nn::Activation activation, int rows)
      : widths_(std::move(widths)), activation_(activation), rows_(rows) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape x = in.at("x");
    if (x.rows < 1 || x.cols < 1) throw ConfigError("input 'x' is empty: " + x.str());
    // 0: the garment template's vertex count when assets are bound (decoding a
    // global feature into the garment), else the input's row count.
    const bool garment_bound = context.assets && context.assets->garment;
    out_rows_ = rows_ > 0 ? rows_ : garment_bound ? context.assets->garment->mesh.num_vertices() : x.rows;
    std::vector<int> sizes{x.rows * x.cols};
    for (long w : widths_) sizes.push_back(static_cast<int>(w));
    sizes.push_back(3 * out_rows_);
    mlp_ = nn::DenseStack(sizes, activation_, nn::Activation{});
    mlp_.create_weights(*this, "mlp_", context.seed);
    return {{"out", {out_rows_, 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    out.at("out")->vec() = Eigen::Map<const Eigen::VectorXf>(mlp_.forward(flat(x)).data(), out.at("out")->size());
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("x");
    const Tensor& g = *gout.at("out");
    const ConstMatrixMap gy(g.data(), g.batch(), 3 * out_rows_);
    const auto gx = gin.find("x");
    if (gx == gin.end()) {
      mlp_.backward(flat(x), gy, nullptr);
      return;
    }
    MatrixRM gflat;
    mlp_.backward(flat(x), gy, &gflat);
    gx->second->vec() = Eigen::Map<const Eigen::VectorXf>(gflat.data(), gflat.size());
  }

  double flops_per_sample() const override { return mlp_.flops_per_row(); }

 private:
  // One sample per row: a sample's [R, C] block is contiguous.
  static ConstMatrixMap flat(const Tensor& t) { return {t.data(), t.batch(), Eigen::Index(t.rows()) * t.cols()}; }

  std::vector<long> widths_;
  nn::Activation activation_;
  int rows_, out_rows_ = 0;
  nn::DenseStack mlp_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "decoder";
  d.name = "mlp";
  d.doc = "Dense decoder from a flattened [R, C] input to [rows, 3] vertices (the seed's MLP ablation, TailorNet's LF net).";
  d.inputs = {{"x", "features [R, C], flattened per sample (e.g. an encoder's global [1, C])"}};
  d.outputs = {{"out", "vertices [rows, 3]"}};
  d.params = {{.name = "widths", .type = ParamType::IntList, .default_value = "[256, 256]",
               .doc = "hidden layer widths (may be empty: [])", .min = 1, .max = 65536},
              {.name = "rows", .type = ParamType::Int, .default_value = "0",
               .doc = "output vertices; 0: the garment's vertex count (assets bound) or the input's row count",
               .min = 0, .max = 10000000},
              nn::activation_param("relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    return std::make_unique<MlpDecoder>(p.get_int_list("widths"), nn::activation_from(p),
                                        static_cast<int>(p.get_int("rows")));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
