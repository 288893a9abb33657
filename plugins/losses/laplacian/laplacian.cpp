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
#include <drape/assets/assets.hpp>
#include <drape/nn/loss_inputs.hpp>
#include <drape/plugin.hpp>

#include <algorithm>
#include <cmath>
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
    const int ng = assets.garment->mesh.num_vertices();
    check_garment_pred_target(in, ng);
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
      level_.push_back(fold_restriction(L, h.fine_index));
    }
    return {{"loss", {1, 1}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target");
    const int batch = x.batch(), n = x.rows();
    std::size_t per_sample = 0;
    for (const Level& l : level_) per_sample += 3 * static_cast<std::size_t>(l.rows());
    residual_.resize(static_cast<std::size_t>(batch) * per_sample);
    delta_.resize(3 * static_cast<std::size_t>(n));
    for (int b = 0; b < batch; ++b) {
      const float *xb = x.data() + static_cast<std::size_t>(b) * 3 * n, *yb = y.data() + static_cast<std::size_t>(b) * 3 * n;
      for (std::size_t j = 0; j < delta_.size(); ++j) delta_[j] = xb[j] - yb[j];
      float* r = residual_.data() + static_cast<std::size_t>(b) * per_sample;
      double sum = 0.0;
      for (const Level& l : level_) {
        // r_i = sum_j L_ij (x - y)_fine(j), in the order of the row's entries
        // (as the sparse product summed them).
        double level_sum = 0.0;
        for (int i = 0; i < l.rows(); ++i, r += 3) {
          float r0 = 0.0f, r1 = 0.0f, r2 = 0.0f;
          for (int e = l.start[i]; e < l.start[i + 1]; ++e) {
            const float w = l.weight[e];
            const float* d = delta_.data() + 3 * static_cast<std::size_t>(l.vertex[e]);
            r0 += w * d[0];
            r1 += w * d[1];
            r2 += w * d[2];
          }
          r[0] = r0;
          r[1] = r1;
          r[2] = r2;
          level_sum += double(std::abs(r0)) + double(std::abs(r1)) + double(std::abs(r2));
        }
        sum += mean_ ? level_sum / double(l.rows()) : level_sum;
      }
      (*out.at("loss"))(b, 0, 0) = static_cast<float>(sum);
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("pred");
    const int batch = x.batch(), n = x.rows();
    std::size_t per_sample = 0;
    for (const Level& l : level_) per_sample += 3 * static_cast<std::size_t>(l.rows());
    if (residual_.size() != static_cast<std::size_t>(batch) * per_sample)
      throw Error("backward without a matching forward");
    const auto gpred = gin.find("pred"), gtarget = gin.find("target");
    if (gpred == gin.end() && gtarget == gin.end()) return;
    g_.resize(3 * static_cast<std::size_t>(n));
    for (int b = 0; b < batch; ++b) {
      std::fill(g_.begin(), g_.end(), 0.0f);
      const float* r = residual_.data() + static_cast<std::size_t>(b) * per_sample;
      for (const Level& l : level_) {
        // dL/dx_k = L_k' sign(L_k (x_k - y_k)), scattered to the garment vertices.
        const float scale = (*gout.at("loss"))(b, 0, 0) / (mean_ ? float(l.rows()) : 1.0f);
        for (int i = 0; i < l.rows(); ++i, r += 3) {
          const float s0 = sign(r[0], scale), s1 = sign(r[1], scale), s2 = sign(r[2], scale);
          for (int e = l.start[i]; e < l.start[i + 1]; ++e) {
            const float w = l.weight[e];
            float* g = g_.data() + 3 * static_cast<std::size_t>(l.vertex[e]);
            g[0] += w * s0;
            g[1] += w * s1;
            g[2] += w * s2;
          }
        }
      }
      const std::size_t offset = static_cast<std::size_t>(b) * 3 * n;
      if (gpred != gin.end()) std::copy(g_.begin(), g_.end(), gpred->second->data() + offset);
      if (gtarget != gin.end())
        for (std::size_t j = 0; j < g_.size(); ++j) gtarget->second->data()[offset + j] = -g_[j];
    }
  }

  double flops_per_sample() const override {
    double f = 0.0;
    for (const auto& l : level_) f += 6.0 * double(l.weight.size()) + 3.0 * double(l.rows());
    return f;
  }

 private:
  // L_k with the restriction folded in: row i of the level, its entries naming
  // garment vertices (compressed rows).
  struct Level {
    std::vector<int> start;    // row i's entries are [start[i], start[i + 1])
    std::vector<int> vertex;   // garment vertex of each entry
    std::vector<float> weight;  // L_k's value
    int rows() const { return static_cast<int>(start.size()) - 1; }
  };

  static Level fold_restriction(const SparseRM& L, const Eigen::VectorXi& fine_index) {
    Level l;
    l.start.reserve(static_cast<std::size_t>(L.rows()) + 1);
    l.start.push_back(0);
    for (int i = 0; i < L.rows(); ++i) {
      for (SparseRM::InnerIterator it(L, i); it; ++it) {
        l.vertex.push_back(fine_index[it.col()]);
        l.weight.push_back(it.value());
      }
      l.start.push_back(static_cast<int>(l.vertex.size()));
    }
    return l;
  }

  static float sign(float v, float scale) { return v > 0 ? scale : (v < 0 ? -scale : 0.0f); }

  bool mean_;
  int levels_;
  std::vector<Level> level_;
  std::vector<float> residual_;  // L_k (x_k - y_k) of the last forward: per sample, the levels' rows in turn
  std::vector<float> delta_;     // x - y of one sample (scratch)
  std::vector<float> g_;         // one sample's gradient (scratch)
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "laplacian";
  d.doc = "The seed's L_l (eq. 6.12): L1 of the random-walk Laplacian of pred - ground truth on each hierarchy level.";
  d.inputs = {{"pred", "predicted garment vertices [N, 3]"}, {"target", "ground-truth garment vertices [N, 3]"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.params = {{.name = "reduction", .type = ParamType::String, .default_value = "mean",
               .doc = "mean over each level's vertices, or the seed's plain sum",
               .choices = {"mean", "sum"}},
              {.name = "levels", .type = ParamType::Int, .default_value = "4",
               .doc = "resolutions summed, finest first (the seed uses 4)", .min = 1, .max = 16}};
  d.create_node = [](const Params& p) {
    return std::make_unique<LaplacianLoss>(p.get_string("reduction") == "mean", static_cast<int>(p.get_int("levels")));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
