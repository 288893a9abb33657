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
    const Shape x = in.at("x");
    skinning_ = NodeSkinning(context.assets ? context.assets->garment_skinning : Eigen::MatrixXf(), in.at("transforms"), "skin");
    if (x.cols != 3 || x.rows != skinning_.weights.rows())
      throw ConfigError("input 'x' must be [" + std::to_string(skinning_.weights.rows()) + ", 3] (the garment's vertices), got " + x.str());
    return {{"out", x}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    const Tensor& t = *in.at("transforms");
    Tensor& y = *out.at("out");
    for (int s = 0; s < x.batch(); ++s)
      for (int i = 0; i < x.rows(); ++i) {
        const Eigen::Matrix<float, 3, 4> m = skinning_.blended(t, s, i);
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
          const Eigen::Matrix3f r = skinning_.blended(t, s, i).leftCols<3>();
          const Eigen::Vector3f back = r.transpose() * gi;
          for (int c = 0; c < 3; ++c) (*gx)(s, i, c) = back[c];
        }
        if (gt) {
          const Eigen::Vector3f p(x(s, i, 0), x(s, i, 1), x(s, i, 2));
          for (int b : skinning_.joints[static_cast<std::size_t>(i)]) {
            const float w = skinning_.weights(i, b);
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
    for (const auto& j : skinning_.joints) n += 24.0 * static_cast<double>(j.size()) + 18.0;
    return n;
  }

 private:
  NodeSkinning skinning_;
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
