// The seed's spectral loss L_s (eq. 6.13):
//   L_s = mean_j | (V' (x - y))_j |_1
// V [N, k] holds the garment's eigenvectors with the k smallest eigenvalues
// (Assets::eigenvectors, orthonormal columns), so V' (x - y) [k, 3] are the
// spectral coefficients of the error: the loss weighs every frequency up to k
// alike, where a per-vertex loss is dominated by the low ones. |.|_1 sums the
// three coordinates; mean over the k coefficients (`reduction: sum` gives the
// seed's plain sum).
// Reading V (N x k floats, 14 MB at the default resolution) is the cost here:
// once per batch forward, once backward.
#include <drape/assets/assets.hpp>
#include <drape/nn/basis_products.hpp>
#include <drape/nn/loss_inputs.hpp>
#include <drape/plugin.hpp>

#include <string>

namespace {

using namespace drape;

class SpectralLoss final : public Node {
 public:
  SpectralLoss(bool mean, int k) : mean_(mean), k_(k) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets || context.assets->eigenvectors.size() == 0)
      throw ConfigError("the spectral loss needs the garment's eigenvectors, but no assets with an eigenbasis are bound "
                        "to this graph");
    const MatrixRM& V = context.assets->eigenvectors;
    check_garment_pred_target(in, static_cast<int>(V.rows()));
    if (k_ > V.cols())
      throw ConfigError("k is " + std::to_string(k_) + " but the assets hold " + std::to_string(V.cols()) + " eigenvectors");
    const int k = k_ > 0 ? k_ : static_cast<int>(V.cols());
    basis_ = V.leftCols(k);
    return {{"loss", {1, 1}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target");
    const int batch = x.batch(), n = x.rows();
    // C = D' V [3B, k] for the whole batch, D [N, 3B] the samples' x - y side
    // by side: one pass over V (nn::basis_transpose_times; the BLAS copied all
    // of V before every product).
    difference_.resize(n, 3 * batch);
    for (int b = 0; b < batch; ++b) difference_.middleCols(3 * b, 3) = x.mat(b) - y.mat(b);
    coefficients_.resize(3 * batch, basis_.cols());
    nn::basis_transpose_times(difference_, basis_, coefficients_);
    for (int b = 0; b < batch; ++b) {
      const double s = coefficients_.middleRows(3 * b, 3).cast<double>().lpNorm<1>();
      (*out.at("loss"))(b, 0, 0) = static_cast<float>(mean_ ? s / double(basis_.cols()) : s);
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("pred");
    const int batch = x.batch();
    if (coefficients_.rows() != 3 * batch) throw Error("backward without a matching forward");
    // dL/dx = V sign(V' (x - y)), all samples in one product: [N, k] x [k, 3B]
    // (the signs held as rows, [3B, k], as basis_times takes them).
    MatrixRM signs(3 * batch, basis_.cols());
    for (int b = 0; b < batch; ++b) {
      const float scale = (*gout.at("loss"))(b, 0, 0) / (mean_ ? float(basis_.cols()) : 1.0f);
      signs.middleRows(3 * b, 3) = coefficients_.middleRows(3 * b, 3).unaryExpr(
          [scale](float v) { return v > 0 ? scale : (v < 0 ? -scale : 0.0f); });
    }
    const auto gpred = gin.find("pred"), gtarget = gin.find("target");
    if (gpred == gin.end() && gtarget == gin.end()) return;
    MatrixRM g(basis_.rows(), 3 * batch);
    nn::basis_times(basis_, signs, g);
    for (int b = 0; b < batch; ++b) {
      if (gpred != gin.end()) gpred->second->mat(b) = g.middleCols(3 * b, 3);
      if (gtarget != gin.end()) gtarget->second->mat(b) = -g.middleCols(3 * b, 3);
    }
  }

  double flops_per_sample() const override { return 3.0 * double(basis_.rows()) * double(basis_.cols()); }

 private:
  bool mean_;
  int k_;
  MatrixRM basis_;         // [N, k] the first k eigenvectors
  MatrixRM difference_;    // [N, 3B] x - y of the last forward, sample b in columns 3b..3b+2
  MatrixRM coefficients_;  // [3B, k] (V' (x - y))' of the last forward, three rows per sample
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "spectral_loss";
  d.doc = "The seed's L_s (eq. 6.13): L1 of the spectral coefficients V'(pred - ground truth) on the garment's eigenbasis.";
  d.inputs = {{"pred", "predicted garment vertices [N, 3]"}, {"target", "ground-truth garment vertices [N, 3]"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.params = {{.name = "reduction", .type = ParamType::String, .default_value = "mean",
               .doc = "mean over the k coefficients, or the seed's plain sum",
               .choices = {"mean", "sum"}},
              {.name = "k", .type = ParamType::Int, .default_value = "0",
               .doc = "eigenvectors used, smallest eigenvalues first; 0: all the assets hold", .min = 0, .max = 100000}};
  d.create_node = [](const Params& p) {
    return std::make_unique<SpectralLoss>(p.get_string("reduction") == "mean", static_cast<int>(p.get_int("k")));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
