// The mean vertex distance: mean over vertices of the Euclidean distance to
// the ground truth, the ME every table of the seed reports (drape eval's ME).
// L_V2V (eq. 6.8) sums per-coordinate L1 norms of a closest-point part and a
// displacement part; its minimiser is a per-axis median, ME's the geometric
// one, so a model trained on L_V2V alone is not trained on the figure it is
// judged by. Not in the seed; the shipped posed model trains on it
// (docs/poses.md, "Training on the metric"). At a vertex that sits exactly
// on its target the distance has no gradient; the subgradient 0 is taken
// there.
#include <drape/nn/loss_inputs.hpp>
#include <drape/plugin.hpp>
#include <drape/training/metrics.hpp>

namespace {

using namespace drape;

class VertexDistanceLoss final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext&) override {
    const Shape s = check_pred_target(in);
    if (s.cols != 3) throw ConfigError("vertex_distance: pred must be vertices [N, 3], got " + s.str());
    rows_ = s.rows;
    return {{"loss", {1, 1}}};
  }

  // drape eval's ME itself, in double: a thousand distances of a centimetre
  // summed in float lose the digits the gradient check sees.
  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target");
    for (int b = 0; b < x.batch(); ++b)
      (*out.at("loss"))(b, 0, 0) =
          static_cast<float>(MetricsContext::mean_error(x.mat(b).cast<double>(), y.mat(b).cast<double>()));
  }

  // d/dx_i = (x_i - y_i) / (|x_i - y_i| N); 0 at a vertex on its target.
  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target");
    const auto gp = gin.find("pred"), gt = gin.find("target");
    for (int b = 0; b < x.batch(); ++b) {
      const Eigen::MatrixX3d d = (x.mat(b) - y.mat(b)).cast<double>();
      const Eigen::ArrayXd norms = d.rowwise().norm().array();
      const double s = static_cast<double>((*gout.at("loss"))(b, 0, 0)) / rows_;
      const Eigen::ArrayXd scale = (norms > 0).select(s / norms, 0.0);
      const Eigen::MatrixX3f g = (d.array().colwise() * scale).matrix().cast<float>();
      if (gp != gin.end()) gp->second->mat(b) = g;
      if (gt != gin.end()) gt->second->mat(b) = -g;
    }
  }

  double flops_per_sample() const override { return 9.0 * rows_; }

 private:
  int rows_ = 0;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "vertex_distance";
  d.doc = "Mean Euclidean per-vertex distance to the ground truth (the ME metric itself; not in the seed).";
  d.inputs = {{"pred", "predicted vertices [N, 3]"}, {"target", "ground-truth vertices [N, 3]"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.create_node = [](const Params&) { return std::make_unique<VertexDistanceLoss>(); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
