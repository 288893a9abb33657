// The seed's vertex-to-vertex loss L_V2V (eq. 6.8): each garment vertex is split
// into its closest point on the body surface c and the displacement d from it
// (eq. 6.6, x = c_x + d_x, y = c_y + d_y), and the two parts are compared with
// per-vertex L1 norms:
//   L_V2V = mean_i ( |c_x,i - c_y,i|_1 + |d_x,i - d_y,i|_1 )     (reduction: mean)
// c_x and c_y are the exact closest points of the prediction and the ground truth
// on this sample's body (input `body`, with the faces of the assets' mean body),
// so the loss separates sliding along the body from lifting off it, which plain
// L1/L2 cannot. Gradients flow through the closest points to pred, target and
// body (geometry/closest_point_gradient.hpp), to those of the three the graph
// wants (training: pred only). Closest points in double, found by
// geometry::BodyPoints: the target's computed once per sample and cached, the
// prediction's among the faces listed near the target's vertex.
#include <drape/assets/assets.hpp>
#include <drape/nn/body_loss_inputs.hpp>
#include <drape/geometry/body_points.hpp>
#include <drape/geometry/closest_point_gradient.hpp>
#include <drape/plugin.hpp>

#include <memory>
#include <string>
#include <vector>

namespace {

using namespace drape;
using geometry::SurfacePoint;

Eigen::MatrixX3d to_double(const Tensor& t, int b) { return t.mat(b).cast<double>(); }

Eigen::Vector3d l1_sign(const Eigen::Vector3d& v) {
  return v.unaryExpr([](double a) { return a > 0 ? 1.0 : (a < 0 ? -1.0 : 0.0); });
}

class V2vLoss final : public Node {
 public:
  explicit V2vLoss(bool mean) : mean_(mean) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    rows_ = check_body_loss_inputs(in, context, "v2v");
    const Mesh& mean_body = context.assets->body;
    faces_ = mean_body.faces;
    points_ = std::make_unique<geometry::BodyPoints>(mean_body, "v2v");
    return {{"loss", {1, 1}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target"), &body = *in.at("body");
    const int batch = x.batch();
    hits_x_.assign(batch, {});
    hits_y_.assign(batch, {});
    for (int b = 0; b < batch; ++b) {
      hits_y_[b] = points_->ground_truth(body, y, b);
      hits_x_[b] = points_->prediction(body, x, y, b, *hits_y_[b]);
      const auto xb = x.mat(b), yb = y.mat(b);
      const auto &hx = *hits_x_[b], &hy = *hits_y_[b];
      double sum = 0.0;
      for (int i = 0; i < rows_; ++i) {
        const Eigen::Vector3d cx = hx[i].point, cy = hy[i].point;
        const Eigen::Vector3d dx = xb.row(i).transpose().cast<double>() - cx, dy = yb.row(i).transpose().cast<double>() - cy;
        sum += (cx - cy).lpNorm<1>() + (dx - dy).lpNorm<1>();
      }
      (*out.at("loss"))(b, 0, 0) = static_cast<float>(mean_ ? sum / rows_ : sum);
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target"), &body = *in.at("body");
    const int batch = x.batch();
    if (static_cast<int>(hits_x_.size()) != batch) throw Error("v2v: backward without a matching forward");
    const auto gpred = gin.find("pred"), gtarget = gin.find("target"), gbody_port = gin.find("body");
    const bool want_y = gtarget != gin.end() || gbody_port != gin.end();  // the target's closest points move with both
    if (gpred == gin.end() && !want_y) return;
    for (int b = 0; b < batch; ++b) {
      const double scale = (*gout.at("loss"))(b, 0, 0) / (mean_ ? double(rows_) : 1.0);
      const Eigen::MatrixX3d xb = to_double(x, b), yb = to_double(y, b), vb = to_double(body, b);
      const auto &hx = *hits_x_[b], &hy = *hits_y_[b];
      // With s_c = sign(c_x - c_y) and s_d = sign(d_x - d_y), d = p - c:
      // dL/dc_x = s_c - s_d, dL/dx (direct) = s_d; dL/dc_y = s_d - s_c, dL/dy (direct) = -s_d.
      Eigen::MatrixX3d gx(rows_, 3), gy(rows_, 3), gcx(rows_, 3), gcy(rows_, 3);
      for (int i = 0; i < rows_; ++i) {
        const Eigen::Vector3d cx = hx[i].point, cy = hy[i].point;
        const Eigen::Vector3d sc = l1_sign(cx - cy);
        const Eigen::Vector3d sd = l1_sign((xb.row(i).transpose() - cx) - (yb.row(i).transpose() - cy));
        gx.row(i) = scale * sd;
        gy.row(i) = -scale * sd;
        gcx.row(i) = scale * (sc - sd);
        gcy.row(i) = scale * (sd - sc);
      }
      Eigen::MatrixX3d gbody = Eigen::MatrixX3d::Zero(vb.rows(), 3);
      geometry::closest_points_backward(vb, faces_, xb, hx, gcx, gx, gbody);
      if (want_y) geometry::closest_points_backward(vb, faces_, yb, hy, gcy, gy, gbody);
      if (gpred != gin.end()) gpred->second->mat(b) = gx.cast<float>();
      if (gtarget != gin.end()) gtarget->second->mat(b) = gy.cast<float>();
      if (gbody_port != gin.end()) gbody_port->second->mat(b) = gbody.cast<float>();
    }
  }

  // An estimate: two closest-point queries (~40 box and triangle tests of ~30 flops) and the L1 terms per vertex.
  double flops_per_sample() const override { return 2.0 * 40.0 * 30.0 * rows_ + 12.0 * rows_; }

 private:
  bool mean_;
  int rows_ = 0;
  Eigen::MatrixX3i faces_;
  std::unique_ptr<geometry::BodyPoints> points_;
  std::vector<std::shared_ptr<const geometry::BodyPoints::Hits>> hits_x_, hits_y_;  // of the last forward, per sample
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "v2v";
  d.doc = "The seed's L_V2V (eq. 6.8): L1 of the closest-body-point and displacement parts of pred vs ground truth.";
  d.inputs = {{"pred", "predicted garment vertices [N, 3]"},
              {"target", "ground-truth garment vertices [N, 3]"},
              {"body", "this sample's body vertices [Nb, 3] (the assets' body topology)"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.params = {{"reduction", ParamType::String, "mean", "mean over vertices, or the seed's plain sum", {}, {}, {"mean", "sum"}}};
  d.create_node = [](const Params& p) { return std::make_unique<V2vLoss>(p.get_string("reduction") == "mean"); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
