// Picks rows of the input by index: out.row(i) = x.row(indices[i]). This is how
// body features are distributed to garment vertices through fixed
// correspondences. The indices come from the `indices` parameter for now;
// correspondences computed from the template assets will feed the same node.
// Backward scatter-adds, so a row picked twice receives both gradients.
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class Gather final : public Node {
 public:
  explicit Gather(std::vector<long> indices) : indices_(std::move(indices)) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext&) override {
    const Shape x = in.at("x");
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
  std::vector<long> indices_;
  int cols_ = 0;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "gather";
  d.doc = "Rows of the input picked by index (body-to-garment correspondences); backward scatter-adds.";
  d.inputs = {{"x", "features [R, C]"}};
  d.outputs = {{"out", "the picked rows [len(indices), C]"}};
  d.params = {{"indices", ParamType::IntList, "[]", "row of x for each output row (0-based)", 0, {}}};
  d.create_node = [](const Params& p) {
    auto indices = p.get_int_list("indices");
    if (indices.empty()) throw ConfigError("gather: parameter 'indices' is empty; list the input row of each output row");
    return std::make_unique<Gather>(std::move(indices));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
