// Input and output normalisation inside a graph, relative to the bound
// template (NodeContext::assets):
//   subtract_mean_body  body vertices -> offsets from the mean body, so an
//                       encoder sees the shape change rather than the whole body;
//   add_template        predicted offsets -> garment vertices, template + offset,
//                       so a decoder starts from the garment dressed on the
//                       mean body and learns displacements (TailorNet's and the
//                       seed's "garment = template + displacement" view).
// Both are constant shifts, so the gradient passes through unchanged, and the
// losses still see absolute positions (edge lengths, the body surface).
#include <drape/assets/assets.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class TemplateOffset final : public Node {
 public:
  enum class Of { MeanBody, Garment };
  explicit TemplateOffset(Of of) : of_(of) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const char* what = of_ == Of::Garment ? "garment template" : "mean body";
    if (!context.assets || (of_ == Of::Garment && !context.assets->garment))
      throw ConfigError(std::string("needs the ") + what + ", but no template assets are bound to this graph");
    const Eigen::MatrixX3d& v =
        of_ == Of::Garment ? context.assets->garment->mesh.vertices : context.assets->body.vertices;
    const Shape x = in.at("x");
    if (x.cols != 3 || x.rows != v.rows())
      throw ConfigError(std::string("input 'x' must be [") + std::to_string(v.rows()) + ", 3] (the " + what +
                        "'s vertices), got " + x.str());
    offset_ = (of_ == Of::Garment ? 1.0 : -1.0) * v.cast<float>();
    return {{"out", x}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    Tensor& y = *out.at("out");
    for (int b = 0; b < x.batch(); ++b) y.mat(b) = x.mat(b) + offset_;
  }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    if (auto g = gin.find("x"); g != gin.end()) g->second->vec() = gout.at("out")->vec();
  }

  double flops_per_sample() const override { return double(offset_.size()); }

 private:
  Of of_;
  MatrixRM offset_;  // [vertices, 3], added
};

PluginList plugins() {
  PluginDescriptor body;
  body.kind = "op";
  body.name = "subtract_mean_body";
  body.doc = "Body vertices minus the mean body of the bound template (input normalisation).";
  body.inputs = {{"x", "body vertices [body vertices, 3]"}};
  body.outputs = {{"out", "offsets from the mean body [body vertices, 3]"}};
  body.create_node = [](const Params&) { return std::make_unique<TemplateOffset>(TemplateOffset::Of::MeanBody); };

  PluginDescriptor garment;
  garment.kind = "op";
  garment.name = "add_template";
  garment.doc = "Offsets plus the garment template dressed on the mean body (output normalisation).";
  garment.inputs = {{"x", "offsets [garment vertices, 3]"}};
  garment.outputs = {{"out", "garment vertices [garment vertices, 3]"}};
  garment.create_node = [](const Params&) { return std::make_unique<TemplateOffset>(TemplateOffset::Of::Garment); };
  return {body, garment};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
