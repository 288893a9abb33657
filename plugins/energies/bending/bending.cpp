// The bending energy summed over the garment's hinges (interior edges), in
// ArcSim's form (physics.cpp, bending_energy):
//   E_e = k_b * l^2 / (2 (A0 + A1)) * (theta - theta_rest)^2 / 4,
// with theta the signed dihedral angle of the current positions
// (dihedral_angle.hpp), l the edge's material-space (UV) length and A0, A1 the
// material-space areas of its two faces, times `stiffness_scale`. On a UV
// seam the edge has a different UV segment in each face; l is the mean of the
// two lengths. theta - theta_rest is wrapped to [-pi, pi], so a hinge folded
// shut (theta near +-pi) has a finite, continuous energy.
//
// k_b, the smaller of the two faces' materials' stiffness:
//  * model arcsim: ArcSim's table at the edge's UV direction and the curvature
//    |theta| l / (A0 + A1) (drape/physics/arcsim_material.hpp), so k_b depends on
//    theta; E is differentiated exactly, dk_b/dtheta included;
//  * model linear: the material's constant `bending`.
// ArcSim measures l in world space at each step; drape uses the rest (UV)
// length, so that bending does not also resist stretching (the same on an
// unstretched hinge; docs/materials.md).
//
// Potential (`potential`, model arcsim hinges): ArcSim's bending_force is
// k_b(theta) l^2 / (4 (A0 + A1)) (theta - rest) dtheta with k_b frozen at the
// current angle, which no energy has as its gradient once k_b varies with
// curvature (as for stretching, docs/materials.md). `product` is the energy
// above, ArcSim's bending_energy as written; its moment c (2 k_b d + k_b' d^2)
// departs from ArcSim's force wherever the table slopes, and where k_b falls
// (columns 3-4 of the knit's 0 and 45 degree rows) the moment turns negative
// and a hinge has a second rest angle at 40 1/m. `work` is the work of
// ArcSim's force along the fold from rest,
//   W = 2 c int_rest^{rest + d} k_b(|t| l / A) (t - rest) dt,  c = l^2 / (8 A),
// integrated exactly (a cubic on each polynomial piece of the rounded lookup,
// arcsim::bending_breakpoints, by 3-point Gauss); W' = 2 c k_b d is ArcSim's
// force and W'' = 2 c (k_b + k_b' d). The two agree where k_b is constant.
//
// Rest angle (`rest`): `flat` (0, panels cut flat) or `initial` (the angles of
// the garment's rest positions mesh.vertices at bind time).
//
// Hessian: exact, E'' dtheta dtheta^T + E' d2theta with E' = dE/dtheta (E the
// potential chosen).
// Projected (`projection`): `gauss_newton` keeps max(E'', 0) dtheta dtheta^T,
// rank one and PSD by construction (ArcSim's choice), dropping the curvature
// term; `eigen` clamps the negative eigenvalues of the exact 12x12 block, the
// nearest PSD matrix, at several times the cost.
//
// Collapsing wings: E_e is multiplied by a weight w that fades from 1 to 0 as
// a wing's 3D height over the edge falls below kFadeFraction (10 %) of its rest
// (UV) height (wing_fade.hpp), because theta's derivatives grow like 1/h and
// 1/h^2 there. Derivatives are exact: w E' dtheta + E dw, and w H_e + E' (dtheta
// dw^T + dw dtheta^T) + E d2w. A faded hinge's block is made PSD by clamping its
// eigenvalues under either projection (the product has no rank-one
// Gauss-Newton form); hinges outside the fade are computed exactly as before.
//
// Degenerate input: hinges whose two faces have (nearly) zero total UV area
// (at most 1e-10 times the mean) are skipped with one warning from bind().
// A wing of (near) zero area in the current 3D state has no normal: its hinge
// contributes nothing (w = 0), or, for a wing below 1e-10 of the edge length
// but not at 0, a tiny energy w E whose dtheta terms are dropped (dihedral_angle.hpp).
#include <drape/physics/arcsim_material.hpp>
#include <drape/element_energy.hpp>
#include <drape/plugin.hpp>
#include <drape/physics/psd_projection.hpp>
#include <drape/warnings.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "dihedral_angle.hpp"
#include "hinges.hpp"
#include "wing_fade.hpp"

namespace {

using namespace drape;
namespace dh = drape::dihedral;

constexpr double kDegenerateAreaFraction = 1e-10;

struct HingeElement {
  double shape;          // stiffness_scale * l^2 / (8 (A0 + A1)): E = k_b shape (theta - rest)^2
  double c_linear;       // both faces linear: stiffness_scale * k_b l^2 / (8 (A0 + A1)), E = c (theta - rest)^2
  double curvature;      // l / (A0 + A1): ArcSim's curvature is |theta| times this
  double rest_angle;
  double fade_height[2];  // kFadeFraction times each wing's UV height over the edge (0: never faded)
  double k_linear;       // both faces linear: the smaller constant stiffness
  bool tabulated;        // some face is arcsim: k_b from the curves
  int softer;            // the side whose curve is nowhere above the other's (0 or 1), or -1: the curves cross
  arcsim::BendingCurve side[2];  // per face; a linear face's curve is its constant
};

// ArcSim's min over a hinge's two sides, rounded where they differ by less
// than kSideBand times their mean: min's kink where the two curves cross
// (a seam between the knit and a print) would be a kink of the energy, which
// stalls Newton as the table's columns did (arcsim_material.hpp). C1; at most
// kSideBand / 4 of the mean below the plain min, where the two are equal.
constexpr double kSideBand = 0.02;

arcsim::BendingStiffness softer_side(const arcsim::BendingStiffness& a, const arcsim::BendingStiffness& b) {
  const double sum = a.k + b.k, gap = a.k - b.k;
  if (!(std::abs(gap) < 0.5 * kSideBand * sum)) return a.k <= b.k ? a : b;
  // In s = a + b and g = a - b: m = s / 2 - kSideBand s / 8 - g^2 / (2 kSideBand s).
  const double c = kSideBand;
  const double m_s = 0.5 - c / 8 + gap * gap / (2 * c * sum * sum), m_g = -gap / (c * sum);
  const double m_ss = -gap * gap / (c * sum * sum * sum), m_sg = gap / (c * sum * sum), m_gg = -1.0 / (c * sum);
  const double ds = a.dk_dcurvature + b.dk_dcurvature, dg = a.dk_dcurvature - b.dk_dcurvature;
  const double d2s = a.d2k_dcurvature2 + b.d2k_dcurvature2, d2g = a.d2k_dcurvature2 - b.d2k_dcurvature2;
  return {0.5 * sum - c * sum / 8 - gap * gap / (2 * c * sum), m_s * ds + m_g * dg,
          m_ss * ds * ds + 2 * m_sg * ds * dg + m_gg * dg * dg + m_s * d2s + m_g * d2g};
}

// Which side is the softer at every curvature: the curves are linear between
// the same columns, so comparing the columns decides (the corner rounding
// moves each by under 0.5 %). Most hinges have one material and one edge
// direction on both sides, so one curve is taken and ArcSim's min is exact;
// only curves that cross (a seam between the knit and a print, a UV seam)
// need softer_side.
int softer_everywhere(const arcsim::BendingCurve& a, const arcsim::BendingCurve& b) {
  // Equal to rounding counts as below: an edge's direction, reversed on the
  // other face, can interpolate the table's rows in the last bit.
  bool a_below = true, b_below = true;
  for (std::size_t j = 0; j < a.samples.size(); ++j) {
    const double tie = 1e-9 * std::max(std::abs(a.samples[j]), std::abs(b.samples[j]));
    a_below = a_below && a.samples[j] <= b.samples[j] + tie;
    b_below = b_below && b.samples[j] <= a.samples[j] + tie;
  }
  return a_below ? 0 : b_below ? 1 : -1;
}

// theta - rest wrapped to [-pi, pi].
double angle_offset(double theta, double rest) { return std::remainder(theta - rest, 2.0 * std::numbers::pi); }

dh::Hinge hinge_at(const Eigen::Matrix<double, 3, 4>& x) { return dh::Hinge(x.col(0), x.col(1), x.col(2), x.col(3)); }

Eigen::Vector2d uv_edge(const Mesh& mesh, int face, int corner) {
  return mesh.uv.row(mesh.uv_faces(face, (corner + 1) % 3)) - mesh.uv.row(mesh.uv_faces(face, corner));
}

double uv_area(const Mesh& mesh, int face) {
  const Eigen::Vector2d u0 = mesh.uv.row(mesh.uv_faces(face, 0)), u1 = mesh.uv.row(mesh.uv_faces(face, 1)),
                        u2 = mesh.uv.row(mesh.uv_faces(face, 2));
  const Eigen::Vector2d e1 = u1 - u0, e2 = u2 - u0;
  return 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
}

enum class Projection { GaussNewton, Eigen };

// What a tabulated hinge's energy is (module comment): the work of ArcSim's
// bending force, or k_b(theta) l^2 / (8 (A0 + A1)) (theta - rest)^2.
enum class Potential { Work, Product };

// Gauss-Legendre, 3 points on [-1, 1]: exact for the cubic that the work
// integrand k(|s|) (s - from) is on each polynomial piece of the lookup.
constexpr double kGaussNode = 0.77459666924148337704;
constexpr double kGaussOuter = 5.0 / 9.0, kGaussCentre = 8.0 / 9.0;

// E(theta) and its first two derivatives in theta.
struct AngleEnergy {
  double e, de, d2e;
};

class Bending final : public ElementEnergy<4> {
 public:
  Bending(double stiffness_scale, bool initial_rest, Projection projection, Potential potential)
      : scale_(stiffness_scale), initial_rest_(initial_rest), projection_(projection), potential_(potential) {}

  void bind(const EnergyContext& context) override {
    const Garment& garment = checked_garment(context);
    const Mesh& mesh = garment.mesh;
    if (initial_rest_ && !mesh.vertices.allFinite())
      throw ConfigError("rest: initial needs finite rest positions, the garment's are not");
    const auto topology = bending::find_hinges(mesh);
    const int nf = mesh.num_faces();
    double mean_area = 0.0;
    for (int f = 0; f < nf; ++f) mean_area += uv_area(mesh, f);
    if (nf > 0) mean_area /= nf;

    hinges_.clear();
    hinges_.reserve(topology.size());
    std::vector<Element> elements;
    int skipped = 0;
    for (const auto& t : topology) {
      const double face_area[2] = {uv_area(mesh, t.face[0]), uv_area(mesh, t.face[1])};
      const double area = face_area[0] + face_area[1];
      if (!(area > 2.0 * kDegenerateAreaFraction * mean_area)) {
        ++skipped;
        continue;
      }
      const Eigen::Vector2d du[2] = {uv_edge(mesh, t.face[0], t.corner[0]), uv_edge(mesh, t.face[1], t.corner[1])};
      const double l = 0.5 * (du[0].norm() + du[1].norm());
      HingeElement h;
      h.shape = scale_ * l * l / (8.0 * area);
      h.curvature = l / area;
      h.tabulated = false;
      h.k_linear = std::numeric_limits<double>::infinity();
      for (int s = 0; s < 2; ++s) {
        const Material& m = garment.materials[static_cast<std::size_t>(garment.material_of(t.face[s]))];
        if (m.model == Material::Model::Arcsim) {
          h.side[s] = arcsim::bending_curve(m.arcsim, du[s]);
          h.tabulated = true;
        } else {
          h.side[s].samples.fill(m.bending);
          h.k_linear = std::min(h.k_linear, m.bending);
        }
      }
      h.c_linear = scale_ * h.k_linear * l * l / (8.0 * area);
      h.softer = softer_everywhere(h.side[0], h.side[1]);
      Element v;
      std::copy(std::begin(t.vertex), std::end(t.vertex), v.begin());
      for (int s = 0; s < 2; ++s) {
        const double len = du[s].norm();  // a zero-length UV edge has zero area: no fade
        h.fade_height[s] = len > 0.0 ? bending::kFadeFraction * 2.0 * face_area[s] / len : 0.0;
      }
      h.rest_angle = 0.0;
      if (initial_rest_) {
        Eigen::Matrix<double, 3, 4> rest;
        for (int k = 0; k < 4; ++k) rest.col(k) = mesh.vertices.row(v[static_cast<std::size_t>(k)]).transpose();
        h.rest_angle = hinge_at(rest).angle();
      }
      hinges_.push_back(h);
      elements.push_back(v);
    }
    if (skipped > 0)
      warn("skipped " + std::to_string(skipped) + " of " + std::to_string(topology.size()) +
           " hinges whose faces have (nearly) zero material-space (UV) area");
    set_elements(mesh.num_vertices(), std::move(elements));
  }

 private:
  // The softer side's stiffness at a (signed) curvature: ArcSim's min over the two faces.
  static arcsim::BendingStiffness stiffness_at(const HingeElement& h, double curvature) {
    return h.softer >= 0 ? arcsim::bending_stiffness(h.side[h.softer], curvature)
                         : softer_side(arcsim::bending_stiffness(h.side[0], curvature),
                                       arcsim::bending_stiffness(h.side[1], curvature));
  }

  // int_from^to k(|s|) (s - from) ds over curvature s (1/m): the work of the
  // moment k s per unit of the hinge's area / 4. Split where the lookup
  // changes polynomial (either side's breakpoints, mirrored, and 0), each
  // piece by 3-point Gauss: exact on one side's curve (a cubic per piece), and
  // to rounding on the smooth rounded min of two curves that cross.
  static double moment_work(const HingeElement& h, double from, double to) {
    if (from == to) return 0.0;
    const double lo = std::min(from, to), hi = std::max(from, to);
    std::array<double, 44> cut{};
    std::size_t n = 0;
    cut[n++] = lo;
    auto add = [&](double c) {
      if (c > lo && c < hi) cut[n++] = c;
    };
    add(0.0);
    for (int s = 0; s < 2; ++s) {
      if (h.softer >= 0 && s != h.softer) continue;
      for (double b : arcsim::bending_breakpoints(h.side[s])) {
        add(b);
        add(-b);
      }
    }
    std::sort(cut.begin() + 1, cut.begin() + static_cast<std::ptrdiff_t>(n));
    cut[n++] = hi;
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const double mid = 0.5 * (cut[i] + cut[i + 1]), half = 0.5 * (cut[i + 1] - cut[i]);
      if (!(half > 0.0)) continue;
      auto f = [&](double s) { return stiffness_at(h, s).k * (s - from); };
      sum += half * (kGaussOuter * (f(mid - kGaussNode * half) + f(mid + kGaussNode * half)) + kGaussCentre * f(mid));
    }
    return to >= from ? sum : -sum;
  }

  AngleEnergy angle_energy(const HingeElement& h, double theta) const {
    const double d = angle_offset(theta, h.rest_angle);
    // Linear: drape's constant model, in its old order of operations.
    if (!h.tabulated) return {h.c_linear * d * d, 2.0 * h.c_linear * d, 2.0 * h.c_linear};
    if (potential_ == Potential::Work) {
      // W = 2 shape int_rest^{rest + d} k(|t| c) (t - rest) dt, c = h.curvature:
      // W' = 2 shape k d (ArcSim's bending force), W'' = 2 shape (k + dk/dtheta d).
      const double c = h.curvature, end = (h.rest_angle + d) * c;
      const arcsim::BendingStiffness s = stiffness_at(h, end);
      const double work = 2.0 * h.shape / (c * c) * moment_work(h, h.rest_angle * c, end);
      return {work, 2.0 * h.shape * s.k * d, 2.0 * h.shape * (s.k + s.dk_dcurvature * c * d)};
    }
    double k = 0.0, dk = 0.0, d2k = 0.0;
    {
      const double curvature = theta * h.curvature;
      const arcsim::BendingStiffness s = stiffness_at(h, curvature);
      k = s.k;
      dk = s.dk_dcurvature * h.curvature;
      d2k = s.d2k_dcurvature2 * h.curvature * h.curvature;
    }
    // E = k(theta) c d^2: E' = c (k' d^2 + 2 k d), E'' = c (k'' d^2 + 4 k' d + 2 k).
    return {k * h.shape * d * d, h.shape * (dk * d * d + 2.0 * k * d), h.shape * (d2k * d * d + 4.0 * dk * d + 2.0 * k)};
  }

  double element_value(int e, const Stencil& x) const override {
    const HingeElement& h = hinges_[static_cast<std::size_t>(e)];
    const dh::Hinge hinge = hinge_at(x);
    const double energy = angle_energy(h, hinge.angle()).e;
    if (!bending::faded(hinge, h.fade_height)) return energy;
    const bending::Fade fade(hinge, h.fade_height, 0);
    return fade.w > 0.0 ? fade.w * energy : 0.0;
  }

  double element_gradient(int e, const Stencil& x, StencilGradient& g) const override {
    const HingeElement& h = hinges_[static_cast<std::size_t>(e)];
    const dh::Hinge hinge = hinge_at(x);
    const AngleEnergy a = angle_energy(h, hinge.angle());
    if (hinge.degenerate())
      g.setZero();
    else
      g = a.de * dh::gradient(wing0(hinge), wing1(hinge));
    if (!bending::faded(hinge, h.fade_height)) return a.e;
    const bending::Fade fade(hinge, h.fade_height, 1);
    if (!(fade.w > 0.0)) {
      g.setZero();
      return 0.0;
    }
    g = fade.w * g + a.e * fade.dw;
    return fade.w * a.e;
  }

  void element_hessian(int e, const Stencil& x, bool project_psd, StencilHessian& block) const override {
    const HingeElement& h = hinges_[static_cast<std::size_t>(e)];
    const dh::Hinge hinge = hinge_at(x);
    if (bending::faded(hinge, h.fade_height)) {
      faded_hessian(h, hinge, project_psd, block);
      return;
    }
    if (hinge.degenerate()) {
      block.setZero();
      return;
    }
    const AngleEnergy a = angle_energy(h, hinge.angle());
    const dh::Wing w0 = wing0(hinge), w1 = wing1(hinge);
    const dh::Vec12 grad = dh::gradient(w0, w1);
    if (project_psd && projection_ == Projection::GaussNewton) {
      block = std::max(a.d2e, 0.0) * grad * grad.transpose();
      return;
    }
    block = a.d2e * grad * grad.transpose() + a.de * angle_hessian(hinge, w0, w1);
    if (project_psd) project_to_psd(block);
  }

  // w E's exact Hessian, eigen-projected when asked (module comment).
  void faded_hessian(const HingeElement& h, const dh::Hinge& hinge, bool project_psd, StencilHessian& block) const {
    const bending::Fade fade(hinge, h.fade_height, 2);
    if (!(fade.w > 0.0)) {
      block.setZero();
      return;
    }
    const AngleEnergy a = angle_energy(h, hinge.angle());
    block = a.e * fade.d2w;
    if (!hinge.degenerate()) {
      const dh::Wing w0 = wing0(hinge), w1 = wing1(hinge);
      const dh::Vec12 dtheta = dh::gradient(w0, w1), de = a.de * dtheta;
      block += fade.w * (a.d2e * dtheta * dtheta.transpose() + a.de * angle_hessian(hinge, w0, w1)) +
               de * fade.dw.transpose() + fade.dw * de.transpose();
    }
    if (project_psd) project_to_psd(block);
  }

  static dh::Mat12 angle_hessian(const dh::Hinge& hinge, const dh::Wing& w0, const dh::Wing& w1) {
    const dh::WingDerivatives d0(w0, hinge.e, hinge.a0, hinge.n0, hinge.q0, hinge.e2, 1.0);
    const dh::WingDerivatives d1(w1, hinge.e, hinge.a1, hinge.n1, hinge.q1, hinge.e2, -1.0);
    return dh::hessian(w0, d0, w1, d1);
  }

  static dh::Wing wing0(const dh::Hinge& h) { return dh::Wing(h.e, h.a0, h.n0, h.q0, h.e2); }
  static dh::Wing wing1(const dh::Hinge& h) { return dh::Wing(h.e, h.a1, h.n1, h.q1, h.e2); }

  double scale_;
  bool initial_rest_;
  Projection projection_;
  Potential potential_;
  std::vector<HingeElement> hinges_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "bending";
  d.doc = "ArcSim's bending energy: per interior edge k_b l^2 / (2 (A0 + A1)) (theta - theta_rest)^2 / 4 of the signed "
          "dihedral angle, l and A from the material-space (UV) rest shape; k_b from ArcSim's table over curvature and "
          "edge direction (model arcsim) or constant (model linear); faded out smoothly on a wing crushed below 10 % of "
          "its rest height.";
  d.params = {
      {.name = "stiffness_scale", .type = ParamType::Float, .default_value = "1.0",
       .doc = "multiplies every material's bending stiffness (N*m)", .min = 0.0, .max = 1e6},
      {.name = "rest", .type = ParamType::String, .default_value = "flat",
       .doc = "rest dihedral angles: flat (0, panels cut flat) or initial (the garment's rest positions)",
       .choices = {"flat", "initial"}},
      {.name = "projection", .type = ParamType::String, .default_value = "gauss_newton",
       .doc = "PSD Hessian for Newton: gauss_newton (2c dtheta dtheta^T, cheap) or eigen (exact block with negative eigenvalues clamped)",
       .choices = {"gauss_newton", "eigen"}},
      {.name = "potential", .type = ParamType::String, .default_value = "product",
       .doc = "a tabulated (model arcsim) hinge's energy: work (the work of ArcSim's bending force k_b(theta) l^2 / (4 (A0 + A1)) "
              "(theta - rest) along the fold from rest, whose gradient is that force) or product (k_b(theta) l^2 / (8 (A0 + A1)) "
              "(theta - rest)^2, ArcSim's bending_energy as written)",
       .choices = {"work", "product"}}};
  d.create_energy = [](const Params& p) {
    return std::make_unique<Bending>(p.get_float("stiffness_scale"), p.get_string("rest") == "initial",
                                     p.get_string("projection") == "eigen" ? Projection::Eigen : Projection::GaussNewton,
                                     p.get_string("potential") == "work" ? Potential::Work : Potential::Product);
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
