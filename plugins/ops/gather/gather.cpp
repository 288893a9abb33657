// Picks rows of the input by index: out.row(i) = x.row(indices[i]). This is how
// body features are distributed to garment vertices through fixed
// correspondences. By default the indices are the template assets'
// correspondences (garment vertex -> closest body vertex on the mean body,
// Assets::correspondence); the `indices` parameter overrides them for graphs
// that pick rows of something else. Backward scatter-adds, so a row picked
// twice receives both gradients.
#include <drape/assets/assets.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class Gather final : public Node {
 public:
  // Empty `indices`: take them from the assets at every setup.
  explicit Gather(std::vector<long> indices) : from_assets_(indices.empty()), indices_(std::move(indices)) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape x = in.at("x");
    if (from_assets_) {
      if (!context.assets)
        throw ConfigError("no `indices` given and no template assets bound: the correspondences come from the assets "
                          "(drape graph check, train and predict bind them), or list the rows in `indices`");
      const auto& c = context.assets->correspondence;
      if (c.empty()) throw ConfigError("the template assets hold no body->garment correspondences");
      indices_.assign(c.begin(), c.end());
      // The correspondences index the body's vertices, or the encoder body's
      // points when the assets have one: rows of anything else would be read
      // silently wrong wherever its indices happen to fall inside. (Assets
      // made by hand without a body say nothing: only the indices are checked.)
      const int rows = context.assets->correspondence_rows();
      if (rows > 0 && x.rows != rows)
        throw ConfigError("the assets' correspondences index " +
                          (context.assets->encoder_resampling.size() > 0
                               ? "the encoder body's " + std::to_string(rows) +
                                     " points (drape train --encoder-body: gather rows of resample_body's output or the "
                                     "encoder's)"
                               : "the body's " + std::to_string(rows) + " vertices") +
                          ", but input 'x' has " + std::to_string(x.rows) + " rows");
    }
    for (std::size_t i = 0; i < indices_.size(); ++i)
      if (indices_[i] >= x.rows)
        throw ConfigError("parameter 'indices' entry " + std::to_string(i) + " is " + std::to_string(indices_[i]) +
                          " but input 'x' has only " + std::to_string(x.rows) + " rows");
    cols_ = x.cols;
    return {{"out", {static_cast<int>(indices_.size()), x.cols}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    Tensor& y = *out.at("out");
    const int n = static_cast<int>(indices_.size());
#pragma omp parallel for schedule(static) if (x.batch() > 1)
    for (int b = 0; b < x.batch(); ++b) {
      const auto xb = x.mat(b);
      auto yb = y.mat(b);
      for (int i = 0; i < n; ++i) yb.row(i) = xb.row(indices_[i]);
    }
  }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const auto gx = gin.find("x");
    if (gx == gin.end()) return;
    const Tensor& gy = *gout.at("out");
    Tensor& g = *gx->second;
    g.set_zero();
    const int n = static_cast<int>(indices_.size());
#pragma omp parallel for schedule(static) if (g.batch() > 1)
    for (int b = 0; b < g.batch(); ++b) {
      auto gb = g.mat(b);
      const auto gyb = gy.mat(b);
      for (int i = 0; i < n; ++i) gb.row(indices_[i]) += gyb.row(i);
    }
  }

  double flops_per_sample() const override { return double(indices_.size()) * cols_; }

 private:
  bool from_assets_;
  std::vector<long> indices_;
  int cols_ = 0;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "gather";
  d.doc = "Rows of the input picked by index (body-to-garment correspondences); backward scatter-adds.";
  d.inputs = {{"x", "features [R, C] (body features [Nb, C] for the correspondences)"}};
  d.outputs = {{"out", "the picked rows [len(indices), C] (garment vertices [Ng, C] for the correspondences)"}};
  d.params = {{.name = "indices", .type = ParamType::IntList, .default_value = "[]",
               .doc = "row of x for each output row (0-based); empty: the assets' body->garment correspondences",
               .min = 0}};
  d.create_node = [](const Params& p) { return std::make_unique<Gather>(p.get_int_list("indices")); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
