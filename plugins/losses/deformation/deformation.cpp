// The seed's deformation-gradient loss L_d (eqs. 6.10-6.11):
//   L_d = mean_f | F_x(f) - F_y(f) |_1,   F_x(f) = x(f) X(f)^-1
// where x(f) = [x1 - x0, x2 - x0] (3x2) are face f's edge vectors in world space
// and X(f) = [X1 - X0, X2 - X0] (2x2) the same edges in material space, the UV
// coordinates of the garment template (meters, one chart per pattern panel).
// F (3x2) maps material directions to world directions: it tells stretch and
// shear apart, which edge lengths cannot. |.|_1 is the entry-wise L1 norm of the
// 3x2 difference; `reduction: sum` gives the seed's plain sum over faces.
// F is linear in the positions, so F_x - F_y = (x - y)(f) X^-1 and the
// gradients for pred and target are opposite.
#include <drape/errors.hpp>
#include <drape/nn/loss_inputs.hpp>
#include <drape/plugin.hpp>

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace {

using namespace drape;

class DeformationLoss final : public Node {
 public:
  explicit DeformationLoss(bool mean) : mean_(mean) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    const Mesh& mesh = bound_garment_mesh(context, "deformation", "the garment's material space");
    check_garment_pred_target(in, mesh.num_vertices());
    if (!mesh.has_uv()) throw ConfigError("the garment template has no material-space (UV) coordinates");
    if (mesh.num_faces() == 0) throw ConfigError("the garment template has no faces");
    faces_ = mesh.faces;
    inverse_rest_.resize(mesh.num_faces());
    for (int f = 0; f < mesh.num_faces(); ++f) {
      Eigen::Matrix2d X;
      for (int k = 0; k < 2; ++k) X.col(k) = (mesh.uv.row(mesh.uv_faces(f, k + 1)) - mesh.uv.row(mesh.uv_faces(f, 0))).transpose();
      const double det = X.determinant();
      const double scale = X.col(0).squaredNorm() * X.col(1).squaredNorm();
      if (!(std::abs(det) > 1e-12 * std::sqrt(scale)) || !std::isfinite(det))
        throw ConfigError("garment face " + std::to_string(f) + " has a degenerate material-space (UV) triangle");
      inverse_rest_[f] = X.inverse();
    }
    return {{"loss", {1, 1}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target");
    const int faces = static_cast<int>(faces_.rows());
    // Backward needs only the signs of F_x - F_y: kept here (6 bytes a face)
    // instead of computing every face's difference a second time.
    signs_.resize(static_cast<std::size_t>(x.batch()) * faces);
    for (int b = 0; b < x.batch(); ++b) {
      const auto xb = x.mat(b), yb = y.mat(b);
      Signs* signs = signs_.data() + static_cast<std::size_t>(b) * faces;
      double sum = 0.0;
#pragma omp parallel for reduction(+ : sum) schedule(static) if (faces > 20000)
      for (int f = 0; f < faces; ++f) {
        const Eigen::Matrix<double, 3, 2> D = difference(xb, yb, f);
        sum += D.lpNorm<1>();
        for (int k = 0; k < 6; ++k) signs[f][k] = static_cast<std::int8_t>((D(k) > 0) - (D(k) < 0));
      }
      (*out.at("loss"))(b, 0, 0) = static_cast<float>(mean_ ? sum / faces : sum);
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("pred");
    const int faces = static_cast<int>(faces_.rows());
    if (signs_.size() != static_cast<std::size_t>(x.batch()) * faces)
      throw Error("backward without a matching forward");
    for (int b = 0; b < x.batch(); ++b) {
      const double scale = (*gout.at("loss"))(b, 0, 0) / (mean_ ? double(faces) : 1.0);
      const Signs* signs = signs_.data() + static_cast<std::size_t>(b) * faces;
      // Row-major: a vertex's three coordinates are adjacent for the scatter.
      Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> g = decltype(g)::Zero(x.rows(), 3);
      for (int f = 0; f < faces; ++f) {
        Eigen::Matrix<double, 3, 2> S;
        for (int k = 0; k < 6; ++k) S(k) = signs[f][k];
        // dL/d[e1 e2] = sign(D) X^-T; e_k = v_k - v_0.
        const Eigen::Matrix<double, 3, 2> ge = scale * S * inverse_rest_[f].transpose();
        g.row(faces_(f, 1)) += ge.col(0).transpose();
        g.row(faces_(f, 2)) += ge.col(1).transpose();
        g.row(faces_(f, 0)) -= (ge.col(0) + ge.col(1)).transpose();
      }
      if (gin.count("pred")) gin.at("pred")->mat(b) = g.cast<float>();
      if (gin.count("target")) gin.at("target")->mat(b) = -g.cast<float>();
    }
  }

  double flops_per_sample() const override { return 24.0 * double(faces_.rows()); }

 private:
  // F_x(f) - F_y(f) = [(x - y)_1 - (x - y)_0, (x - y)_2 - (x - y)_0] X^-1.
  Eigen::Matrix<double, 3, 2> difference(const ConstMatrixMap& x, const ConstMatrixMap& y, int f) const {
    Eigen::Matrix<double, 3, 2> e;
    const Eigen::Vector3d d0 = (x.row(faces_(f, 0)) - y.row(faces_(f, 0))).transpose().cast<double>();
    for (int k = 0; k < 2; ++k)
      e.col(k) = (x.row(faces_(f, k + 1)) - y.row(faces_(f, k + 1))).transpose().cast<double>() - d0;
    return e * inverse_rest_[f];
  }

  bool mean_;
  Eigen::MatrixX3i faces_;
  std::vector<Eigen::Matrix2d> inverse_rest_;  // X(f)^-1 per face
  using Signs = std::array<std::int8_t, 6>;    // sign(F_x - F_y) of a face, column-major 3x2
  std::vector<Signs> signs_;                   // of the last forward, faces of sample b from b * F
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "deformation";
  d.doc = "The seed's L_d (eqs. 6.10-6.11): L1 difference of every face's deformation gradient (world per material-space "
          "UV), prediction vs ground truth.";
  d.inputs = {{"pred", "predicted garment vertices [N, 3]"}, {"target", "ground-truth garment vertices [N, 3]"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.params = {{.name = "reduction", .type = ParamType::String, .default_value = "mean",
               .doc = "mean over faces, or the seed's plain sum", .choices = {"mean", "sum"}}};
  d.create_node = [](const Params& p) { return std::make_unique<DeformationLoss>(p.get_string("reduction") == "mean"); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
