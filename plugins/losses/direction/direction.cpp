// The seed's direction loss L_dir (eq. 6.7), per garment vertex i and averaged:
//   L_dir = mean_i [ R( -n' (c_x - c_y) / |c_x - c_y| )                  (1) correspondence outside
//                  + ( 1 - (x - c_y)' d_y / (|x - c_y| |d_y|) ) ]         (2) direction of the offset
// with c_x, c_y the closest points of the prediction x and the ground truth y on
// this sample's body, d_y = y - c_y (eq. 6.6), n the outward body normal at c_y
// and R the ReLU. n is the gradient of the signed distance at y (for y off the
// body, n = d_y / signed distance; on the body, the pseudo-normal there).
//
// Both terms are scale-free as the seed writes them: (1) is the sine of the
// angle by which c_x dips below the tangent plane at c_y, whatever |c_x - c_y|;
// (2) is one minus the cosine between x - c_y and d_y. Where a direction is
// undefined (c_x = c_y, x = c_y or d_y = 0, to 1e-9 m) that term is 0 and
// passes no gradient. Gradients reach pred, target and body through the closest
// points and n (geometry/closest_point_gradient.hpp), those of the three the
// graph wants (training: pred only). Computed in double; the closest points come
// from geometry::BodyPoints (the target's cached, shared with v2v).
#include <drape/assets/assets.hpp>
#include <drape/nn/body_loss_inputs.hpp>
#include <drape/geometry/body_points.hpp>
#include <drape/geometry/closest_point_gradient.hpp>
#include <drape/plugin.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace drape;
using geometry::SurfacePoint;

// Shorter vectors have no direction (float positions carry ~1e-7 m of rounding).
constexpr double kNoDirection = 1e-9;

Eigen::MatrixX3d to_double(const Tensor& t, int b) { return t.mat(b).cast<double>(); }

class DirectionLoss final : public Node {
 public:
  DirectionLoss(bool mean, double outside_weight, double offset_weight)
      : mean_(mean), outside_weight_(outside_weight), offset_weight_(offset_weight) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    rows_ = check_body_loss_inputs(in, context, "direction");
    const Mesh& mean_body = context.assets->body;
    faces_ = mean_body.faces;
    points_ = std::make_unique<geometry::BodyPoints>(mean_body, "direction");
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
      for (int i = 0; i < rows_; ++i)
        sum += vertex_term(xb.row(i).transpose().cast<double>(), yb.row(i).transpose().cast<double>(), hx[i], hy[i], nullptr);
      (*out.at("loss"))(b, 0, 0) = static_cast<float>(mean_ ? sum / rows_ : sum);
    }
  }

  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor &x = *in.at("pred"), &y = *in.at("target"), &body = *in.at("body");
    const int batch = x.batch();
    if (static_cast<int>(hits_x_.size()) != batch) throw Error("direction: backward without a matching forward");
    const auto gpred = gin.find("pred"), gtarget = gin.find("target"), gbody_port = gin.find("body");
    const bool want_y = gtarget != gin.end() || gbody_port != gin.end();  // the target's closest points move with both
    if (gpred == gin.end() && !want_y) return;
    for (int b = 0; b < batch; ++b) {
      const double scale = (*gout.at("loss"))(b, 0, 0) / (mean_ ? double(rows_) : 1.0);
      const Eigen::MatrixX3d xb = to_double(x, b), yb = to_double(y, b), vb = to_double(body, b);
      const auto &hx = *hits_x_[b], &hy = *hits_y_[b];
      Eigen::MatrixX3d gx(rows_, 3), gy(rows_, 3), gcx(rows_, 3), gcy(rows_, 3);
      for (int i = 0; i < rows_; ++i) {
        Grad g;
        vertex_term(xb.row(i).transpose(), yb.row(i).transpose(), hx[i], hy[i], &g);
        gx.row(i) = scale * g.x;
        gy.row(i) = scale * g.y;
        gcx.row(i) = scale * g.cx;
        gcy.row(i) = scale * g.cy;
      }
      Eigen::MatrixX3d gbody = Eigen::MatrixX3d::Zero(vb.rows(), 3);
      geometry::closest_points_backward(vb, faces_, xb, hx, gcx, gx, gbody);
      if (want_y) geometry::closest_points_backward(vb, faces_, yb, hy, gcy, gy, gbody);
      if (gpred != gin.end()) gpred->second->mat(b) = gx.cast<float>();
      if (gtarget != gin.end()) gtarget->second->mat(b) = gy.cast<float>();
      if (gbody_port != gin.end()) gbody_port->second->mat(b) = gbody.cast<float>();
    }
  }

  // An estimate: two closest-point queries (~40 box and triangle tests of ~30 flops) and the terms per vertex.
  double flops_per_sample() const override { return 2.0 * 40.0 * 30.0 * rows_ + 40.0 * rows_; }

 private:
  // dTerm/d(x, y, c_x, c_y), n's dependence on y and c_y folded in.
  struct Grad {
    Eigen::Vector3d x = Eigen::Vector3d::Zero(), y = Eigen::Vector3d::Zero();
    Eigen::Vector3d cx = Eigen::Vector3d::Zero(), cy = Eigen::Vector3d::Zero();
  };

  // One vertex's two terms; fills g when given.
  double vertex_term(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const SurfacePoint& hx, const SurfacePoint& hy,
                     Grad* g) const {
    const Eigen::Vector3d& n = hy.normal;
    double value = 0.0;
    Eigen::Vector3d gn = Eigen::Vector3d::Zero();  // dTerm/dn
    // (1) R(-n'e / |e|), e = c_x - c_y: d/de = -(I - ê ê') n / |e|, d/dn = -ê.
    const Eigen::Vector3d e = hx.point - hy.point;
    const double le = e.norm();
    if (outside_weight_ != 0.0 && le > kNoDirection) {
      const Eigen::Vector3d eh = e / le;
      const double r = -n.dot(eh);
      if (r > 0) {
        value += outside_weight_ * r;
        if (g) {
          const Eigen::Vector3d de = -outside_weight_ * (n - n.dot(eh) * eh) / le;
          g->cx += de;
          g->cy -= de;
          gn -= outside_weight_ * eh;
        }
      }
    }
    // (2) 1 - cos(u, d), u = x - c_y, d = y - c_y: dcos/du = (d̂ - cos û) / |u|, dcos/dd = (û - cos d̂) / |d|.
    const Eigen::Vector3d u = x - hy.point, d = y - hy.point;
    const double lu = u.norm(), ld = d.norm();
    if (offset_weight_ != 0.0 && lu > kNoDirection && ld > kNoDirection) {
      const Eigen::Vector3d uh = u / lu, dh = d / ld;
      const double cos = uh.dot(dh);
      value += offset_weight_ * (1.0 - cos);
      if (g) {
        const Eigen::Vector3d gu = -offset_weight_ * (dh - cos * uh) / lu;
        const Eigen::Vector3d gd = -offset_weight_ * (uh - cos * dh) / ld;
        g->x += gu;
        g->cy -= gu + gd;
        g->y += gd;
      }
    }
    // n = (y - c_y) / signed distance off the body: dn = (I - n n') d(y - c_y) / sd.
    if (g && std::abs(hy.signed_distance) > kNoDirection && !gn.isZero(0.0)) {
      const Eigen::Vector3d gd = (gn - n.dot(gn) * n) / hy.signed_distance;
      g->y += gd;
      g->cy -= gd;
    }
    return value;
  }

  bool mean_;
  double outside_weight_, offset_weight_;
  int rows_ = 0;
  Eigen::MatrixX3i faces_;
  std::unique_ptr<geometry::BodyPoints> points_;
  std::vector<std::shared_ptr<const geometry::BodyPoints::Hits>> hits_x_, hits_y_;  // of the last forward, per sample
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "loss";
  d.name = "direction";
  d.doc = "The seed's L_dir (eq. 6.7): closest body point of pred not below the ground truth's tangent plane, "
          "and pred's offset from the ground truth's body point along the ground truth's.";
  d.inputs = {{"pred", "predicted garment vertices [N, 3]"},
              {"target", "ground-truth garment vertices [N, 3]"},
              {"body", "this sample's body vertices [Nb, 3] (the assets' body topology)"}};
  d.outputs = {{"loss", "per-sample loss [1, 1]"}};
  d.params = {{"reduction", ParamType::String, "mean", "mean over vertices, or the seed's plain sum", {}, {}, {"mean", "sum"}},
              {"outside_weight", ParamType::Float, "1", "weight of term (1), the ReLU on the correspondence", 0.0, {}},
              {"offset_weight", ParamType::Float, "1", "weight of term (2), the offset direction", 0.0, {}}};
  d.create_node = [](const Params& p) {
    return std::make_unique<DirectionLoss>(p.get_string("reduction") == "mean", p.get_float("outside_weight"),
                                           p.get_float("offset_weight"));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
