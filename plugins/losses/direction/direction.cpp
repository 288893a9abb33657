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
// from geometry::BodyPoints (the target's cached, shared with v2v), found and
// differentiated through by nn::ClosestPointLoss.
#include <drape/nn/closest_point_loss.hpp>
#include <drape/plugin.hpp>

#include <cmath>

namespace {

using namespace drape;
using geometry::SurfacePoint;

// Shorter vectors have no direction (float positions carry ~1e-7 m of rounding).
constexpr double kNoDirection = 1e-9;

class DirectionLoss final : public nn::ClosestPointLoss {
 public:
  DirectionLoss(bool mean, double outside_weight, double offset_weight)
      : ClosestPointLoss("direction", mean), outside_weight_(outside_weight), offset_weight_(offset_weight) {}

  // An estimate: two closest-point queries (~40 box and triangle tests of ~30 flops) and the terms per vertex.
  double flops_per_sample() const override { return 2.0 * 40.0 * 30.0 * rows() + 40.0 * rows(); }

 private:
  double vertex_loss(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const SurfacePoint& hx,
                     const SurfacePoint& hy) const override {
    return vertex_term(x, y, hx, hy, nullptr);
  }
  // n's dependence on y and c_y folded in.
  VertexGradient vertex_gradient(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const SurfacePoint& hx,
                                 const SurfacePoint& hy) const override {
    VertexGradient g;
    vertex_term(x, y, hx, hy, &g);
    return g;
  }

  // One vertex's two terms; fills g when given.
  double vertex_term(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const SurfacePoint& hx, const SurfacePoint& hy,
                     VertexGradient* g) const {
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

  double outside_weight_, offset_weight_;
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
  d.params = {{.name = "reduction", .type = ParamType::String, .default_value = "mean",
               .doc = "mean over vertices, or the seed's plain sum", .choices = {"mean", "sum"}},
              {.name = "outside_weight", .type = ParamType::Float, .default_value = "1",
               .doc = "weight of term (1), the ReLU on the correspondence", .min = 0.0},
              {.name = "offset_weight", .type = ParamType::Float, .default_value = "1",
               .doc = "weight of term (2), the offset direction", .min = 0.0}};
  d.create_node = [](const Params& p) {
    return std::make_unique<DirectionLoss>(p.get_string("reduction") == "mean", p.get_float("outside_weight"),
                                           p.get_float("offset_weight"));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
