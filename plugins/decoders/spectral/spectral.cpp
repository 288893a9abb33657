// The seed's spectral residual branch (Sec. 6.3.3): an MLP on the encoded body
// feature predicts coefficients Delta c [k, 3] of the k garment Laplacian
// eigenvectors with the smallest eigenvalues, and Delta x = V Delta c
// (V = Assets::eigenvectors [Ng, k], orthonormal columns) goes back to the
// vertices, to be added to the decoder's output. k is a parameter, clamped to
// the eigenvectors the assets hold.
//
// The MLP's last layer starts scaled by `init_scale` so that the residual is
// small at the start of training and does not swamp the main decoder.
//
// V is stored in bfloat16 (the top half of each float, rounded to nearest even):
// at one body the product is bound by reading V (1000 x 3505 floats are 14 MB,
// 45% of the whole model's inference time), and halving its bytes nearly halves
// that time. The rounding (relative 2^-9 per entry) is the basis's definition
// for training and inference alike, so every batch size and both directions use
// the same V and the gradients stay exact for it. Both products read the 16-bit
// V in place (nn::basis_times, nn::basis_transpose_times), at any batch size.
#include <drape/assets/assets.hpp>
#include <drape/nn/dense_stack.hpp>
#include <drape/nn/basis_products.hpp>
#include <drape/plugin.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace {

using namespace drape;

std::uint16_t to_bfloat16(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  u += 0x7FFFu + ((u >> 16) & 1u);  // round to nearest, ties to even (eigenvectors are finite)
  return static_cast<std::uint16_t>(u >> 16);
}

class SpectralDecoder final : public Node {
 public:
  SpectralDecoder(std::vector<long> widths, int k, int use_k, double init_scale, nn::Activation activation)
      : widths_(std::move(widths)), requested_k_(k), requested_use_k_(use_k), init_scale_(static_cast<float>(init_scale)),
        activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Shape x = in.at("x");
    if (x.rows < 1 || x.cols < 1) throw ConfigError("input 'x' is empty: " + x.str());
    if (!context.assets || context.assets->eigenvectors.size() == 0)
      throw ConfigError("spectral needs the garment template's assets (its eigenvectors); none are bound");
    const MatrixRM& v = context.assets->eigenvectors;
    if (context.assets->garment && v.rows() != context.assets->garment->mesh.num_vertices())
      throw ConfigError("the assets' eigenvectors have " + std::to_string(v.rows()) + " rows but the garment has " +
                        std::to_string(context.assets->garment->mesh.num_vertices()) + " vertices");
    vertices_ = static_cast<int>(v.rows());
    k_ = requested_k_ > 0 ? std::min<int>(requested_k_, static_cast<int>(v.cols())) : static_cast<int>(v.cols());
    use_k_ = requested_use_k_ > 0 ? std::min(requested_use_k_, k_) : k_;
    basis16_.resize(std::size_t(vertices_) * k_);
    for (int i = 0; i < vertices_; ++i)
      for (int j = 0; j < k_; ++j) basis16_[std::size_t(i) * k_ + j] = to_bfloat16(v(i, j));
    std::vector<int> sizes{x.rows * x.cols};
    for (long w : widths_) sizes.push_back(static_cast<int>(w));
    sizes.push_back(3 * k_);
    mlp_ = nn::DenseStack(sizes, activation_, nn::Activation{});
    mlp_.create_weights(*this, "mlp_", context.seed);
    weights().at("mlp_w" + std::to_string(mlp_.layers() - 1)).value.vec() *= init_scale_;
    return {{"out", {vertices_, 3}}, {"coefficients", {k_, 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    const int batch = x.batch();
    const MatrixRM& dc = mlp_.forward(ConstMatrixMap(x.data(), batch, Eigen::Index(x.rows()) * x.cols()));
    Tensor& coefficients = *out.at("coefficients");
    coefficients.vec() = Eigen::Map<const Eigen::VectorXf>(dc.data(), dc.size());
    // Row 3b + c of C [3*batch, k] is sample b's coefficient vector of axis c.
    coefficients_.resize(3 * batch, k_);
    for (int b = 0; b < batch; ++b) coefficients_.middleRows(3 * b, 3) = coefficients.mat(b).transpose();
    Tensor& dx = *out.at("out");
    // One pass over the 16-bit V (nn::basis_times reads it in place: half the
    // bytes of a float copy; the BLAS copied all of that before every product).
    product_.resize(vertices_, 3 * batch);
    nn::basis_times(basis(use_k_), coefficients_.leftCols(use_k_), product_);
    for (int b = 0; b < batch; ++b) dx.mat(b) = product_.middleCols(3 * b, 3);
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("x");
    const Tensor& gdx = *gout.at("out");
    const Tensor& gc = *gout.at("coefficients");
    const int batch = x.batch();
    // dLoss/dC = G^T V with G [Ng, 3*batch] the residual's gradient (V^T G, transposed).
    coefficients_.resize(3 * batch, k_);
    product_.resize(vertices_, 3 * batch);
    for (int b = 0; b < batch; ++b) product_.middleCols(3 * b, 3) = gdx.mat(b);
    coefficients_.setZero();
    nn::basis_transpose_times(product_, basis(use_k_), coefficients_.leftCols(use_k_));
    MatrixRM g(batch, 3 * k_);
    for (int b = 0; b < batch; ++b) {
      Eigen::Map<MatrixRM> gb(g.row(b).data(), k_, 3);
      gb = coefficients_.middleRows(3 * b, 3).transpose() + gc.mat(b);
    }
    const ConstMatrixMap flat(x.data(), batch, Eigen::Index(x.rows()) * x.cols());
    const auto gx = gin.find("x");
    if (gx == gin.end()) {
      mlp_.backward(flat, g, nullptr);
      return;
    }
    MatrixRM gflat;
    mlp_.backward(flat, g, &gflat);
    gx->second->vec() = Eigen::Map<const Eigen::VectorXf>(gflat.data(), gflat.size());
  }

  double flops_per_sample() const override { return mlp_.flops_per_row() + double(vertices_) * use_k_ * 3; }

 private:
  // The first `columns` eigenvectors as the bfloat16 matrix the products read.
  nn::Bfloat16Matrix basis(int columns) const { return {basis16_.data(), vertices_, columns, k_}; }

  std::vector<long> widths_;
  int requested_k_, requested_use_k_;
  float init_scale_;
  nn::Activation activation_;
  std::vector<std::uint16_t> basis16_;  // [Ng, k] row-major, bfloat16
  int vertices_ = 0, k_ = 0, use_k_ = 0;  // use_k_: the eigenvectors applied to Delta x
  nn::DenseStack mlp_;
  MatrixRM coefficients_;  // [3*batch, k]: row 3b + c is sample b's Delta c of axis c (or its gradient)
  MatrixRM product_;       // [Ng, 3*batch] for the matrix-product path
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "decoder";
  d.name = "spectral";
  d.doc = "The seed's spectral residual branch: an MLP predicts Delta c [k, 3], output Delta x = V Delta c (Sec. 6.3.3).";
  d.inputs = {{"x", "the encoded body [R, C], flattened per sample (e.g. an encoder's global [1, C])"}};
  d.outputs = {{"out", "the residual Delta x = V Delta c [Ng, 3]"},
               {"coefficients", "the predicted spectral coefficients Delta c [k, 3]"}};
  d.params = {{.name = "widths", .type = ParamType::IntList, .default_value = "[256]",
               .doc = "hidden layer widths of the MLP (may be empty: [])", .min = 1, .max = 65536},
              {.name = "k", .type = ParamType::Int, .default_value = "0",
               .doc = "eigenvectors used; 0 or more than the assets hold: all of them", .min = 0, .max = 100000},
              {.name = "use_k", .type = ParamType::Int, .default_value = "0",
               .doc = "eigenvectors applied to Delta x (0: all k): fewer trade accuracy for time at inference, same weights",
               .min = 0, .max = 100000},
              {.name = "init_scale", .type = ParamType::Float, .default_value = "0.01",
               .doc = "factor on the last layer's initial weights (a small initial residual)", .min = 0.0, .max = 1.0},
              nn::activation_param("relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    return std::make_unique<SpectralDecoder>(p.get_int_list("widths"), static_cast<int>(p.get_int("k")),
                                             static_cast<int>(p.get_int("use_k")),
                                             p.get_float("init_scale"), nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
