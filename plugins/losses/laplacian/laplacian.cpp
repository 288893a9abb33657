// The seed's multi-resolution Laplacian difference loss L_l (eq. 6.12):
//   L_l = sum_{k < levels} mean_i | (L_k (x_k - y_k))_i |_1
// L_k is the random-walk graph Laplacian I - D^-1 A of hierarchy level k
// (Assets::laplacians), so (L_k x)_i is vertex i minus the mean of its
// neighbours on that level: a length that sees folds about as wide as that
// level's edges. x_k, y_k restrict the garment to level k: the vertices of a
// coarse level are a subset of the garment's (Hierarchy::levels[k].fine_index),
// so restriction picks those rows. Level 0 is the garment itself.
// |.|_1 sums the three coordinates; each level is averaged over its vertices
// (`reduction: sum` gives the seed's plain sums).
#include <drape/assets.hpp>
#include <drape/plugin.hpp>

#include <string>
#include <vector>

namespace {

using namespace drape;

using SparseRM = Eigen::SparseMatrix<float, Eigen::RowMajor>;

class LaplacianLoss final : public Node {
 public:
  LaplacianLoss(bool mean, int levels) : mean_(mean), levels_(levels) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets || !context.assets->garment)
      throw ConfigError("the laplacian loss needs the garment's hierarchy, but no assets are bound to this graph");
    const Assets& assets = *context.assets;
    const Shape pred = in.at("pred"), target = in.at("target");
    if (!(pred == target)) throw ConfigError("pred " + pred.str() + " and target " + target.str() + " differ in shape");
    const int ng = assets.garment->mesh.num_vertices();
    if (pred.cols != 3 || pred.rows != ng)
      throw ConfigError("pred must be [" + std::to_string(ng) + ", 3] (the garment's vertices), got " + pred.str());
    const int available = std::min<int>(assets.hierarchy.num_levels(), static_cast<int>(assets.laplacians.size()));
    if (levels_ > available)
      throw ConfigError("levels is " + std::to_string(levels_) + " but the assets have " + std::to_string(available) +
                        " hierarchy levels with Laplacians");
    level_.clear();
    for (int k = 0; k < levels_; ++k) {
      const auto& h = assets.hierarchy.levels[k];
      const SparseRM& L = assets.laplacians[k];
      const int n = static_cast<int>(h.fine_index.size());
      if (L.rows() != n || L.cols() != n)
        throw ConfigError("the Laplacian of level " + std::to_string(k) + " is " + std::to_string(L.rows()) + "x" +
                          std::to_string(L.cols()) + " but the level has " + std::to_string(n) + " vertices");
      for (int i = 0; i < n; ++i)
        if (h.fine_index[i] < 0 || h.fine_index[i] >= ng)
          throw ConfigError("hierarchy level " + std::to_string(k) + " names garment vertex " +
                            std::to_string(h.fine_index[i]) + ", outside [0, " + std::to_string(ng) + ")");
      level_.push_back({L, SparseRM(L.transpose()), h.fine_index});
    }
    return {{"loss", {1, 1}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target");
    residual_.assign(x.batch(), {});
    for (int b = 0; b < x.batch(); ++b) {
      const MatrixRM delta = x.mat(b) - y.mat(b);
      double sum = 0.0;
      residual_[b].resize(level_.size());
      for (std::size_t k = 0; k < level_.size(); ++k) {
        const Level& l = level_[k];
        restricted_.resize(l.fine_index.size(), 3);
        for (Eigen::Index i = 0; i < l.fine_index.size(); ++i) restricted_.row(i) = delta.row(l.fine_index[i]);
        MatrixRM& r = residual_[b][k];
        r.noalias() = l.L * restricted_;
        const double s = r.cast<double>().lpNorm<1>();
        sum += mean_ ? s / double(r.rows()) : s;
      }
      (*out.at("loss"))(b, 0, 0) = static_cast<float>(sum);
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("pred");
    if (static_cast<int>(residual_.size()) != x.batch()) throw Error("laplacian: backward without a matching forward");
    for (int b = 0; b < x.batch(); ++b) {
      MatrixRM g = MatrixRM::Zero(x.rows(), 3);
      for (std::size_t k = 0; k < level_.size(); ++k) {
        const Level& l = level_[k];
        const MatrixRM& r = residual_[b][k];
        const float scale = (*gout.at("loss"))(b, 0, 0) / (mean_ ? float(r.rows()) : 1.0f);
        const MatrixRM s = r.unaryExpr([scale](float v) { return v > 0 ? scale : (v < 0 ? -scale : 0.0f); });
        const MatrixRM gk = l.LT * s;  // dL/dx_k = L_k' sign(L_k (x_k - y_k))
        for (Eigen::Index i = 0; i < gk.rows(); ++i) g.row(l.fine_index[i]) += gk.row(i);
      }
      if (gin.count("pred")) gin.at("pred")->mat(b) = g;
      if (gin.count("target")) gin.at("target")->mat(b) = -g;
    }
  }

  double flops_per_sample() const override {
    double f = 0.0;
    for (const auto& l : level_) f += 3.0 * double(l.L.nonZeros()) + 3.0 * double(l.L.rows());
    return f;
  }

 private:
  struct Level {
    SparseRM L;                 // I - D^-1 A of the level
    SparseRM LT;                // its transpose, row-major for the backward product
    Eigen::VectorXi fine_index;  // level vertex -> garment vertex
  };

  bool mean_;
  int levels_;
  std::vector<Level> level_;
  std::vector<std::vector<MatrixRM>> residual_;  // [batch][level] L_k (x_k - y_k) of the last forward
  MatrixRM restricted_;                          // x_k - y_k (scratch)
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "laplacian";
  d.doc = "The seed's L_l (eq. 6.12): L1 of the random-walk Laplacian of pred - ground truth on each hierarchy level.";
  d.inputs = {{"pred", "predicted garment vertices [N, 3]"}, {"target", "ground-truth garment vertices [N, 3]"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.params = {{"reduction", ParamType::String, "mean", "mean over each level's vertices, or the seed's plain sum", {}, {}, {"mean", "sum"}},
              {"levels", ParamType::Int, "4", "resolutions summed, finest first (the seed uses 4)", 1, 16}};
  d.create_node = [](const Params& p) {
    return std::make_unique<LaplacianLoss>(p.get_string("reduction") == "mean", static_cast<int>(p.get_int("levels")));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
