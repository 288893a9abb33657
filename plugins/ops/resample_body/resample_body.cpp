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
#include <drape/nn/sparse_ops.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class ResampleBody final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets) throw ConfigError("needs the template assets (their encoder body), but none are bound");
    const geometry::BodyResampling& r = context.assets->encoder_resampling;
    if (r.size() == 0)
      throw ConfigError("the template assets name no encoder body: give --encoder-body (e.g. parametric; drape train and graph check take it) so "
                        "that the assets resample the body onto that body model's vertices");
    const Shape x = in.at("x");
    if (x.cols != 3 || x.rows != r.source_vertices)
      throw ConfigError("input 'x' must be [" + std::to_string(r.source_vertices) + ", 3] (the body's vertices), got " +
                        x.str());
    map_ = nn::SparseOperator(r.matrix().cast<float>());
    mean_ = r.resampled_template.cast<float>();
    return {{"out", {r.size(), 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    Tensor& y = *out.at("out");
    map_.apply(x.flat(), x.batch(), y.flat());
    for (int b = 0; b < y.batch(); ++b) y.mat(b) -= mean_;
  }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const auto gx = gin.find("x");
    if (gx == gin.end()) return;
    const Tensor& gy = *gout.at("out");
    map_.apply_transpose(gy.flat(), gy.batch(), gx->second->flat());
  }

  double flops_per_sample() const override { return 3.0 * static_cast<double>(map_.nonzeros() + mean_.rows()); }

 private:
  nn::SparseOperator map_;  // R [encoder points, body vertices]: three barycentric weights a row
  MatrixRM mean_;           // [encoder points, 3] the mean body read at the points, subtracted
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
