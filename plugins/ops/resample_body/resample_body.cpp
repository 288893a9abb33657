// resample_body: the body's offset from its mean, read at the vertices of the
// encoder's body (docs/bodies.md, "One encoder for both rigs").
//
// The human rig's 6,904 body vertices come in another order than the
// mannequin's 6,490, and a 1D encoder reads vertices in index order: the
// mannequin model's encoder means nothing on them. With the assets' encoder
// body (AssetsSpec::encoder_body), each of its template vertices sits at a
// fixed point of the body's surface (a face and barycentric weights,
// Assets::encoder_resampling); this node reads every input body there and
// subtracts the mean body read the same way, so the encoder sees the same
// kind of input as subtract_mean_body gives it on its own body model, in its
// own vertex order. Everything else of the graph (losses, the push-out) keeps
// the real body. Linear: backward scatters the weights.
#include <drape/assets/assets.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class ResampleBody final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets) throw ConfigError("needs the template assets (their encoder body), but none are bound");
    const Assets& a = *context.assets;
    if (a.encoder_resampling.size() == 0)
      throw ConfigError("the template assets name no encoder body: train with --encoder-body (e.g. parametric) so "
                        "that the assets resample the body onto that body model's vertices");
    const Shape x = in.at("x");
    if (x.cols != 3 || x.rows != a.body.num_vertices())
      throw ConfigError("input 'x' must be [" + std::to_string(a.body.num_vertices()) + ", 3] (the body's vertices), got " +
                        x.str());
    const int n = a.encoder_resampling.size();
    corners_.resize(n, 3);
    weights_.resize(n, 3);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        corners_(i, k) = a.body.faces(a.encoder_resampling.face[i], k);
        weights_(i, k) = static_cast<float>(a.encoder_resampling.barycentric(i, k));
      }
    mean_ = a.encoder_template.cast<float>();
    return {{"out", {n, 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    Tensor& y = *out.at("out");
    for (int b = 0; b < x.batch(); ++b) {
      const auto xb = x.mat(b);
      auto yb = y.mat(b);
      for (Eigen::Index i = 0; i < corners_.rows(); ++i)
        yb.row(i) = weights_(i, 0) * xb.row(corners_(i, 0)) + weights_(i, 1) * xb.row(corners_(i, 1)) +
                    weights_(i, 2) * xb.row(corners_(i, 2)) - mean_.row(i);
    }
  }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const auto gx = gin.find("x");
    if (gx == gin.end()) return;
    const Tensor& gy = *gout.at("out");
    Tensor& g = *gx->second;
    g.set_zero();
    for (int b = 0; b < g.batch(); ++b) {
      auto gb = g.mat(b);
      const auto gyb = gy.mat(b);
      for (Eigen::Index i = 0; i < corners_.rows(); ++i)
        for (int k = 0; k < 3; ++k) gb.row(corners_(i, k)) += weights_(i, k) * gyb.row(i);
    }
  }

  double flops_per_sample() const override { return 9.0 * static_cast<double>(corners_.rows()); }

 private:
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> corners_;  // [Ne, 3] body vertices of each point's face
  Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> weights_;  // [Ne, 3] their barycentric weights
  MatrixRM mean_;  // [Ne, 3] the mean body read at the points, subtracted
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "resample_body";
  d.doc = "Body vertices minus the mean body, read at the encoder body's vertices (the assets' encoder_body: another "
          "body model's template resampled on this body's surface), for an encoder trained on that body model";
  d.inputs = {{"x", "body vertices [body vertices, 3]"}};
  d.outputs = {{"out", "offsets from the mean body at the encoder body's vertices [encoder body vertices, 3]"}};
  d.create_node = [](const Params&) { return std::make_unique<ResampleBody>(); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
