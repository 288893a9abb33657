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
// prediction's among the faces listed near the target's vertex (the common
// part of the closest-point losses: nn/closest_point_loss.hpp).
#include <drape/nn/closest_point_loss.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;
using geometry::SurfacePoint;

Eigen::Vector3d l1_sign(const Eigen::Vector3d& v) {
  return v.unaryExpr([](double a) { return a > 0 ? 1.0 : (a < 0 ? -1.0 : 0.0); });
}

class V2vLoss final : public nn::ClosestPointLoss {
 public:
  explicit V2vLoss(bool mean) : ClosestPointLoss("v2v", mean) {}

  // An estimate: two closest-point queries (~40 box and triangle tests of ~30 flops) and the L1 terms per vertex.
  double flops_per_sample() const override { return 2.0 * 40.0 * 30.0 * rows() + 12.0 * rows(); }

 private:
  double vertex_loss(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const SurfacePoint& hx,
                     const SurfacePoint& hy) const override {
    const Eigen::Vector3d cx = hx.point, cy = hy.point;
    const Eigen::Vector3d dx = x - cx, dy = y - cy;
    return (cx - cy).lpNorm<1>() + (dx - dy).lpNorm<1>();
  }

  // With s_c = sign(c_x - c_y) and s_d = sign(d_x - d_y), d = p - c:
  // dL/dc_x = s_c - s_d, dL/dx (direct) = s_d; dL/dc_y = s_d - s_c, dL/dy (direct) = -s_d.
  VertexGradient vertex_gradient(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const SurfacePoint& hx,
                                 const SurfacePoint& hy) const override {
    const Eigen::Vector3d cx = hx.point, cy = hy.point;
    const Eigen::Vector3d sc = l1_sign(cx - cy);
    const Eigen::Vector3d sd = l1_sign((x - cx) - (y - cy));
    return {.x = sd, .y = -sd, .cx = sc - sd, .cy = sd - sc};
  }
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
  d.params = {{.name = "reduction", .type = ParamType::String, .default_value = "mean",
               .doc = "mean over vertices, or the seed's plain sum", .choices = {"mean", "sum"}}};
  d.create_node = [](const Params& p) { return std::make_unique<V2vLoss>(p.get_string("reduction") == "mean"); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
