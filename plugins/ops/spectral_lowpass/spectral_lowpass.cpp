// `spectral_lowpass`: a garment's low frequencies, x_lf = V_k V_k^T x, with V_k
// the first k eigenvectors of the template's Laplacian (orthonormal columns,
// Assets::eigenvectors). TailorNet's split of a garment into a smooth part that
// an MLP regresses with L2 and the high-frequency rest: here it makes the
// low-frequency target of the TailorNet-style baseline
// (graphs/baselines/tailornet_*.yaml). Linear, so its backward is itself.
#include <drape/assets/assets.hpp>
#include <drape/plugin.hpp>

#include <algorithm>

namespace {

using namespace drape;

class SpectralLowpass final : public Node {
 public:
  explicit SpectralLowpass(int k) : requested_k_(k) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets || context.assets->eigenvectors.size() == 0)
      throw ConfigError("spectral_lowpass needs the garment template's eigenvectors; none are bound");
    const MatrixRM& v = context.assets->eigenvectors;
    const Shape x = in.at("x");
    if (x.rows != v.rows() || x.cols != 3)
      throw ConfigError("input 'x' must be [" + std::to_string(v.rows()) + ", 3] (garment vertices), got " + x.str());
    k_ = std::min<int>(requested_k_, static_cast<int>(v.cols()));
    basis_ = v.leftCols(k_);
    return {{"out", x}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override { apply(*in.at("x"), *out.at("out")); }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    if (auto g = gin.find("x"); g != gin.end()) apply(*gout.at("out"), *g->second);  // V V^T is symmetric
  }

  double flops_per_sample() const override { return 2.0 * double(basis_.size()) * 3; }

 private:
  void apply(const Tensor& x, Tensor& y) const {
    for (int b = 0; b < x.batch(); ++b) {
      const Eigen::MatrixXf c = basis_.transpose() * x.mat(b);  // [k, 3]
      y.mat(b) = basis_ * c;
    }
  }

  int requested_k_, k_ = 0;
  MatrixRM basis_;  // [Ng, k]
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "spectral_lowpass";
  d.doc = "The low frequencies of a garment, V_k V_k^T x over the template's first k Laplacian eigenvectors.";
  d.inputs = {{"x", "garment vertices or displacements [Ng, 3]"}};
  d.outputs = {{"out", "their projection on the first k eigenvectors [Ng, 3]"}};
  d.params = {{.name = "k", .type = ParamType::Int, .default_value = "64",
               .doc = "eigenvectors kept (clamped to what the assets hold)", .min = 1, .max = 100000}};
  d.create_node = [](const Params& p) { return std::make_unique<SpectralLowpass>(static_cast<int>(p.get_int("k"))); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
