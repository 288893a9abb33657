// `skin`: a garment predicted in the body's rest pose (canonical space) posed
// with the body, TailorNet's unposing run forwards (docs/poses.md):
//   y_i = sum_b w_ib (R_b x_i + t_b)
// with the garment's skinning weights w of the bound template
// (Assets::garment_skinning, from the body surface it lies on) and the
// sample's joint transforms (the graph input joint_transforms, R row by row
// then t). Losses and energies downstream see the posed garment; the
// gradient goes back to the canonical prediction through each vertex's
// blended rotation, and to the transforms as well (so a graph may learn them).
#include <drape/assets/assets.hpp>
#include <drape/bodies/garment_skinning.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class Skin final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets || context.assets->garment_skinning.size() == 0)
      throw ConfigError("skin needs the garment's skinning weights, and the bound template has none (its body model "
                        "has no skeleton, or no template assets are bound)");
    weights_ = context.assets->garment_skinning;
    const Shape x = in.at("x"), t = in.at("transforms");
    if (x.cols != 3 || x.rows != weights_.rows())
      throw ConfigError("input 'x' must be [" + std::to_string(weights_.rows()) + ", 3] (the garment's vertices), got " + x.str());
    if (t.cols != 12 || t.rows != weights_.cols())
      throw ConfigError("input 'transforms' must be [" + std::to_string(weights_.cols()) +
                        ", 12] (one rigid transform per joint: R row by row, then t), got " + t.str());
    joints_ = weighted_joints(weights_);
    return {{"out", x}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    const Tensor& t = *in.at("transforms");
    Tensor& y = *out.at("out");
    for (int s = 0; s < x.batch(); ++s)
      for (int i = 0; i < x.rows(); ++i) {
        const Eigen::Matrix<float, 3, 4> m = blended(t, s, i);
        const Eigen::Vector3f p(x(s, i, 0), x(s, i, 1), x(s, i, 2));
        const Eigen::Vector3f q = m.leftCols<3>() * p + m.col(3);
        for (int c = 0; c < 3; ++c) y(s, i, c) = q[c];
      }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("x");
    const Tensor& t = *in.at("transforms");
    const Tensor& g = *gout.at("out");
    Tensor* gx = gin.count("x") ? gin.at("x") : nullptr;
    Tensor* gt = gin.count("transforms") ? gin.at("transforms") : nullptr;
    if (gt) gt->vec().setZero();
    for (int s = 0; s < x.batch(); ++s)
      for (int i = 0; i < x.rows(); ++i) {
        const Eigen::Vector3f gi(g(s, i, 0), g(s, i, 1), g(s, i, 2));
        if (gx) {
          const Eigen::Matrix3f r = blended(t, s, i).leftCols<3>();
          const Eigen::Vector3f back = r.transpose() * gi;
          for (int c = 0; c < 3; ++c) (*gx)(s, i, c) = back[c];
        }
        if (gt) {
          const Eigen::Vector3f p(x(s, i, 0), x(s, i, 1), x(s, i, 2));
          for (int b : joints_[static_cast<std::size_t>(i)]) {
            const float w = weights_(i, b);
            for (int r = 0; r < 3; ++r) {
              for (int c = 0; c < 3; ++c) (*gt)(s, b, 3 * r + c) += w * gi[r] * p[c];
              (*gt)(s, b, 9 + r) += w * gi[r];
            }
          }
        }
      }
  }

  double flops_per_sample() const override {
    double n = 0;
    for (const auto& j : joints_) n += 24.0 * static_cast<double>(j.size()) + 18.0;
    return n;
  }

 private:
  Eigen::Matrix<float, 3, 4> blended(const Tensor& t, int s, int i) const {
    return blended_transform(weights_, joints_[static_cast<std::size_t>(i)], t, s, i);
  }

  Eigen::MatrixXf weights_;              // [garment vertices, joints]
  std::vector<std::vector<int>> joints_;  // per vertex, the joints with a weight
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "skin";
  d.doc = "Poses a garment predicted in the body's rest pose with the body's joints (linear blend skinning by the "
          "garment's weights from the body surface; TailorNet's unposing, docs/poses.md).";
  d.inputs = {{"x", "the garment in the rest pose [garment vertices, 3]"},
              {"transforms", "the sample's joint transforms [joints, 12] (graph input joint_transforms)"}};
  d.outputs = {{"out", "the garment posed [garment vertices, 3]"}};
  d.create_node = [](const Params&) { return std::make_unique<Skin>(); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
