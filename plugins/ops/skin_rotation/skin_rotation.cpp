// `skin_rotation`: the pose as each garment vertex feels it, a local feature
// for a posed model's decoder (docs/poses.md, "What holds the posed model's error"):
//   f_i = sum_b w_ib R_b - I, row by row [garment vertices, 9]
// with the garment's skinning weights w and the sample's joint rotations R
// (the graph input joint_transforms). The joint angles alone are global: the
// same 22 numbers reach every vertex, and the network must learn which
// vertices each angle moves. This is what the `skin` node will do at that
// vertex: a sleeve's vertices see their arm's rotation, the hem the hips', a
// vertex at the armpit a blend. Zero at rest (the identity taken away), so an
// A-pose sample feeds zeros, and the translations are left out (they depend on
// where the joint is, not on how it turned).
#include <drape/assets/assets.hpp>
#include <drape/bodies/garment_skinning.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class SkinRotation final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    skinning_ = NodeSkinning(context.assets ? context.assets->garment_skinning : Eigen::MatrixXf(), in.at("transforms"),
                             "skin_rotation");
    return {{"out", Shape{static_cast<int>(skinning_.weights.rows()), 9}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& t = *in.at("transforms");
    Tensor& f = *out.at("out");
    for (int s = 0; s < t.batch(); ++s)
      for (int i = 0; i < f.rows(); ++i) {
        const Eigen::Matrix<float, 3, 4> m = skinning_.blended(t, s, i);
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) f(s, i, 3 * r + c) = m(r, c) - (r == c ? 1.0f : 0.0f);
      }
  }

  // Linear in the rotations: d f_i[3r + c] / d t_b[3r + c] = w_ib.
  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    if (!gin.count("transforms")) return;
    const Tensor& g = *gout.at("out");
    Tensor& gt = *gin.at("transforms");
    gt.vec().setZero();
    for (int s = 0; s < g.batch(); ++s)
      for (int i = 0; i < g.rows(); ++i)
        for (int b : skinning_.joints[static_cast<std::size_t>(i)]) {
          const float w = skinning_.weights(i, b);
          for (int k = 0; k < 9; ++k) gt(s, b, k) += w * g(s, i, k);
        }
  }

  double flops_per_sample() const override {
    double n = 0;
    for (const auto& j : skinning_.joints) n += 18.0 * static_cast<double>(j.size()) + 9.0;
    return n;
  }

 private:
  NodeSkinning skinning_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "skin_rotation";
  d.doc = "Each garment vertex's blended joint rotation minus the identity (9 values, zero at rest): the pose as the "
          "vertex feels it through the garment's skinning weights, a local input for a posed model (docs/poses.md).";
  d.inputs = {{"transforms", "the sample's joint transforms [joints, 12] (graph input joint_transforms)"}};
  d.outputs = {{"out", "each garment vertex's blended rotation minus the identity, row by row [garment vertices, 9]"}};
  d.create_node = [](const Params&) { return std::make_unique<SkinRotation>(); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
