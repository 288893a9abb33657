// The per-vertex L2 loss (the baseline of the seed's Table 6.3):
// mean over vertices of the squared Euclidean distance to the ground truth.
#include <drape/nn/loss_inputs.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class L2Loss final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext&) override {
    rows_ = check_pred_target(in).rows;
    return {{"loss", {1, 1}}};
  }
  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target");
    for (int b = 0; b < x.batch(); ++b)
      (*out.at("loss"))(b, 0, 0) = (x.mat(b) - y.mat(b)).squaredNorm() / rows_;
  }
  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target");
    for (int b = 0; b < x.batch(); ++b) {
      const float s = 2.0f * (*gout.at("loss"))(b, 0, 0) / rows_;
      if (auto g = gin.find("pred"); g != gin.end()) g->second->mat(b) = s * (x.mat(b) - y.mat(b));
      if (auto g = gin.find("target"); g != gin.end()) g->second->mat(b) = -s * (x.mat(b) - y.mat(b));
    }
  }
  double flops_per_sample() const override { return 3.0 * rows_; }

 private:
  int rows_ = 0;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "l2";
  d.doc = "Mean squared per-vertex distance to the ground truth (the seed's L2 baseline).";
  d.inputs = {{"pred", "predicted vertices [N, 3]"}, {"target", "ground-truth vertices [N, 3]"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.create_node = [](const Params&) { return std::make_unique<L2Loss>(); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
