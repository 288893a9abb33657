// The penetration loss L_pen: per predicted garment vertex i, how far it lies
// inside the body or within a margin eps of its surface, averaged:
//   L_pen = mean_i ( R(eps - s_i) / eps )^2
// with s_i the signed distance of x_i to this sample's body (negative inside),
// R the ReLU. A vertex eps outside costs nothing; one on the surface costs 1;
// one eps inside, 4.
//
// Not one of the seed's training losses: the seed puts its penetration term
// ([8] in the chapter) only into the potential its per-sample optimisation
// minimises (eq. 6.15). drape offers it to training as well (as learned
// garment models since Santesteban et al. 2019 do) for models over the whole
// body space, where the seed's losses alone leave p far above the seed's
// (docs/findings.md, "A model of the whole body space").
//
// Gradient: ds/dx = n, the unit outward normal at the closest point (the
// gradient of the signed distance; SurfacePoint::normal), so
// dL/dx_i = -2 R(eps - s_i) n_i / (eps^2 N). The closest points depend on the
// body too, but only pred's gradient is given: this is a training loss, and
// the graph asks for no other (setup refuses a body or target gradient).
#include <drape/assets/assets.hpp>
#include <drape/nn/body_loss_inputs.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/body_points.hpp>
#include <drape/plugin.hpp>

#include <algorithm>
#include <memory>
#include <string>

namespace {

using namespace drape;

class PenetrationLoss final : public Node {
 public:
  explicit PenetrationLoss(double margin) : margin_(margin) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    rows_ = check_body_loss_inputs(in, context, "penetration");
    points_ = std::make_unique<geometry::BodyPoints>(context.assets->body, "penetration");
    return {{"loss", {1, 1}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target"), &body = *in.at("body");
    const int batch = x.batch();
    depth_.assign(static_cast<std::size_t>(batch), {});
    normal_.assign(static_cast<std::size_t>(batch), {});
    for (int b = 0; b < batch; ++b) {
      const auto truth = points_->ground_truth(body, y, b);
      const geometry::BodyPoints::Hits hits = points_->signed_prediction(body, x, y, b, *truth);
      auto& depth = depth_[static_cast<std::size_t>(b)];
      auto& normal = normal_[static_cast<std::size_t>(b)];
      depth.resize(rows_);
      normal.resize(rows_, 3);
      double sum = 0.0;
      for (int i = 0; i < rows_; ++i) {
        // How far inside the margin: 0 for a vertex beyond it.
        depth[i] = std::max(0.0, margin_ - hits[static_cast<std::size_t>(i)].signed_distance);
        normal.row(i) = hits[static_cast<std::size_t>(i)].normal.transpose();
        sum += depth[i] * depth[i];
      }
      (*out.at("loss"))(b, 0, 0) = static_cast<float>(sum / (margin_ * margin_ * rows_));
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    if (gin.count("body") || gin.count("target"))
      throw Error("gradients reach pred only (a training loss); the graph asked for body or target");
    const auto gpred = gin.find("pred");
    if (gpred == gin.end()) return;
    const int batch = in.at("pred")->batch();
    if (static_cast<int>(depth_.size()) != batch) throw Error("backward without a matching forward");
    for (int b = 0; b < batch; ++b) {
      const double scale = -2.0 * (*gout.at("loss"))(b, 0, 0) / (margin_ * margin_ * rows_);
      const auto& depth = depth_[static_cast<std::size_t>(b)];
      const Eigen::MatrixX3d g = (scale * depth).asDiagonal() * normal_[static_cast<std::size_t>(b)];
      gpred->second->mat(b) = g.cast<float>();
    }
  }

  // An estimate: one closest-point query (~40 box and triangle tests of ~30 flops) per vertex.
  double flops_per_sample() const override { return 40.0 * 30.0 * rows_ + 20.0 * rows_; }

 private:
  double margin_;
  int rows_ = 0;
  std::unique_ptr<geometry::BodyPoints> points_;
  std::vector<Eigen::VectorXd> depth_;      // per sample: R(eps - s_i)
  std::vector<Eigen::MatrixX3d> normal_;    // per sample: ds_i/dx_i
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "penetration";
  d.doc = "mean over garment vertices of (R(eps - s) / eps)^2, s the signed distance to the body: vertices inside "
          "the body or within the margin eps of it (not a seed training loss; docs/losses.md)";
  d.inputs = {{"pred", "predicted garment vertices [N, 3]"},
              {"target", "ground-truth garment vertices [N, 3] (where the body search starts)"},
              {"body", "this sample's body vertices [Nb, 3] (the assets' body topology)"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.params = {{.name = "margin", .type = ParamType::Float, .default_value = "0.003",
               .doc = "eps, m: vertices nearer the body than this (or inside) cost", .min = 1e-5, .max = 0.1}};
  d.create_node = [](const Params& p) { return std::make_unique<PenetrationLoss>(p.get_float("margin")); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
