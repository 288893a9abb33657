// `anchor_blend`: the high-frequency part of the TailorNet-style baseline
// with anchors (seed Table 6.6, "w/ anchor"). TailorNet predicts a garment's
// high frequencies at K anchor shapes and blends them by the inverse distance
// of the body to each anchor. With one pose per anchor (the seed's data) an
// anchor's prediction is one fixed displacement field, so the blend becomes
// a weighted sum of K learnt garments:
//   w_k = d_k^(-p/2) / sum_j d_j^(-p/2),  d_k = |x - c_k|^2 + 1e-6,
//   out = sum_k w_k A_k,
// with x the encoded body (flattened), c_k the anchors' codes in that space and
// A_k [Ng, 3] their displacements -- all learnt (TailorNet picks its anchor
// bodies from the data; here they move to where the data wants them). The
// weights are computed as a softmax of -(p/2) log d_k, stable for a body on an
// anchor. A starts at zero: an untrained blend adds nothing.
#include <drape/assets/assets.hpp>
#include <drape/nn/init.hpp>
#include <drape/plugin.hpp>

#include <cmath>

namespace {

using namespace drape;

class AnchorBlend final : public Node {
 public:
  AnchorBlend(int anchors, double power, double code_scale)
      : anchors_(anchors), power_(power), code_scale_(static_cast<float>(code_scale)) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets || !context.assets->garment)
      throw ConfigError("anchor_blend needs the garment template (its vertex count); none is bound");
    const Shape x = in.at("x");
    if (x.rows < 1 || x.cols < 1) throw ConfigError("input 'x' is empty: " + x.str());
    dims_ = x.rows * x.cols;
    vertices_ = context.assets->garment->mesh.num_vertices();
    Weight& codes = add_weight("codes", anchors_, dims_);
    nn::fill_normal(codes.value, code_scale_, context.seed);
    add_weight("anchors", anchors_, 3 * vertices_);
    return {{"out", {vertices_, 3}}, {"weights", {1, anchors_}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    const int batch = x.batch();
    const auto codes = weights().at("codes").value.mat(0);
    const auto anchors = weights().at("anchors").value.mat(0);
    distance_.resize(batch, anchors_);
    blend_.resize(batch, anchors_);
    for (int b = 0; b < batch; ++b) {
      const Eigen::Map<const Eigen::RowVectorXf> xb(x.mat(b).data(), dims_);
      for (int k = 0; k < anchors_; ++k) distance_(b, k) = (xb - codes.row(k)).squaredNorm() + 1e-6f;
      const Eigen::RowVectorXf logit = -0.5f * float(power_) * distance_.row(b).array().log().matrix();
      const Eigen::RowVectorXf e = (logit.array() - logit.maxCoeff()).exp().matrix();
      blend_.row(b) = e / e.sum();
      const Eigen::RowVectorXf field = blend_.row(b) * anchors;  // [3 Ng]
      out.at("out")->mat(b) = Eigen::Map<const MatrixRM>(field.data(), vertices_, 3);
      out.at("weights")->mat(b) = blend_.row(b);
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("x");
    const int batch = x.batch();
    const auto codes = weights().at("codes").value.mat(0);
    const auto anchors = weights().at("anchors").value.mat(0);
    auto gcodes = weights().at("codes").grad.mat(0);
    auto ganchors = weights().at("anchors").grad.mat(0);
    const auto gx = gin.find("x");
    for (int b = 0; b < batch; ++b) {
      const Eigen::Map<const Eigen::RowVectorXf> g(gout.at("out")->mat(b).data(), 3 * vertices_);
      const Eigen::RowVectorXf w = blend_.row(b);
      ganchors.noalias() += w.transpose() * g;
      // dL/dw_k: through the field, plus the weights output.
      Eigen::RowVectorXf s = (anchors * g.transpose()).transpose() + gout.at("weights")->mat(b);
      const float mean = w.dot(s);
      const Eigen::Map<const Eigen::RowVectorXf> xb(x.mat(b).data(), dims_);
      Eigen::RowVectorXf grad_x = Eigen::RowVectorXf::Zero(dims_);
      for (int k = 0; k < anchors_; ++k) {
        // w = softmax(-(p/2) log d): dL/dd_k = -(p/2) w_k (s_k - sum_j w_j s_j) / d_k, dd_k/dx = 2 (x - c_k).
        const float gd = -0.5f * float(power_) * w(k) * (s(k) - mean) / distance_(b, k);
        const Eigen::RowVectorXf dx = 2.0f * gd * (xb - codes.row(k));
        grad_x += dx;
        gcodes.row(k) -= dx;
      }
      if (gx != gin.end()) gx->second->mat(b) = Eigen::Map<const MatrixRM>(grad_x.data(), x.rows(), x.cols());
    }
  }

  double flops_per_sample() const override { return double(anchors_) * (dims_ + 3.0 * vertices_); }

 private:
  int anchors_;
  double power_;
  float code_scale_;
  int dims_ = 0, vertices_ = 0;
  MatrixRM distance_, blend_;  // [batch, K]
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "decoder";
  d.name = "anchor_blend";
  d.doc = "TailorNet-style anchors: K learnt displacement fields blended by the inverse distance of the encoded body to "
          "K learnt anchor codes.";
  d.inputs = {{"x", "the encoded body [R, C], flattened per sample (e.g. an encoder's global [1, C])"}};
  d.outputs = {{"out", "the blended displacement [Ng, 3]"}, {"weights", "each anchor's blend weight [1, K]"}};
  d.params = {{.name = "anchors", .type = ParamType::Int, .default_value = "8",
               .doc = "anchors K", .min = 1, .max = 4096},
              {.name = "power", .type = ParamType::Float, .default_value = "2",
               .doc = "p of the inverse distance d^-p", .min = 0.1, .max = 16.0},
              {.name = "code_scale", .type = ParamType::Float, .default_value = "1.0",
               .doc = "std of the anchor codes' initial values", .min = 0.0, .max = 100.0}};
  d.create_node = [](const Params& p) {
    return std::make_unique<AnchorBlend>(static_cast<int>(p.get_int("anchors")), p.get_float("power"), p.get_float("code_scale"));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
