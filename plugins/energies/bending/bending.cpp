// ArcSim's bending energy (Narain, Samii & O'Brien 2012; physics.cpp,
// bending_energy) summed over the garment's hinges (interior edges):
//   E_e = k_b * l^2 / (2 (A0 + A1)) * (theta - theta_rest)^2 / 4,
// with theta the signed dihedral angle of the current positions
// (dihedral_angle.hpp), l the edge's material-space (UV) length and A0, A1 the
// material-space areas of its two faces, k_b the smaller bending stiffness of
// the two faces' materials (N*m) times `stiffness_scale`. On a UV seam the edge
// has a different UV segment in each face; like ArcSim, l is the mean of the
// two lengths. theta - theta_rest is wrapped to [-pi, pi], so a hinge folded
// shut (theta near +-pi) has a finite, continuous energy.
//
// Rest angle (`rest`): `flat` (0, panels cut flat) or `initial` (the angles of
// the garment's rest positions mesh.vertices at bind time).
//
// Hessian: exact, 2c (dtheta dtheta^T + (theta - theta_rest) d2theta) with
// c = k_b l^2 / (8 (A0 + A1)). Projected (`projection`): `gauss_newton` keeps
// 2c dtheta dtheta^T, rank one and PSD by construction (ArcSim's choice),
// dropping the curvature term; `eigen` clamps the negative eigenvalues of the
// exact 12x12 block, the nearest PSD matrix, at several times the cost.
//
// Degenerate input: hinges whose two faces have (nearly) zero total UV area
// (at most 1e-10 times the mean) are skipped with one warning from bind().
// A wing of (near) zero area in the current 3D state has no normal: its hinge
// keeps a finite energy but contributes no gradient or Hessian (dihedral_angle.hpp).
#include <drape/element_assembly.hpp>
#include <drape/plugin.hpp>
#include <drape/psd_projection.hpp>

#include <cmath>
#include <iostream>
#include <numbers>

#include "dihedral_angle.hpp"
#include "hinges.hpp"

namespace {

using namespace drape;
namespace dh = drape::dihedral;

constexpr double kDegenerateAreaFraction = 1e-10;

struct HingeElement {
  int vertex[4];
  double c;           // k_b l^2 / (8 (A0 + A1)): E = c (theta - rest)^2
  double rest_angle;
};

// theta - rest wrapped to [-pi, pi].
double angle_offset(double theta, double rest) { return std::remainder(theta - rest, 2.0 * std::numbers::pi); }

dh::Hinge hinge_at(const Eigen::MatrixX3d& x, const HingeElement& h) {
  return dh::Hinge(x.row(h.vertex[0]).transpose(), x.row(h.vertex[1]).transpose(), x.row(h.vertex[2]).transpose(),
                   x.row(h.vertex[3]).transpose());
}

double uv_length(const Mesh& mesh, int face, int corner) {
  return (mesh.uv.row(mesh.uv_faces(face, corner)) - mesh.uv.row(mesh.uv_faces(face, (corner + 1) % 3))).norm();
}

double uv_area(const Mesh& mesh, int face) {
  const Eigen::Vector2d u0 = mesh.uv.row(mesh.uv_faces(face, 0)), u1 = mesh.uv.row(mesh.uv_faces(face, 1)),
                        u2 = mesh.uv.row(mesh.uv_faces(face, 2));
  const Eigen::Vector2d e1 = u1 - u0, e2 = u2 - u0;
  return 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
}

enum class Projection { GaussNewton, Eigen };

class Bending final : public Energy {
 public:
  Bending(double stiffness_scale, bool initial_rest, Projection projection)
      : scale_(stiffness_scale), initial_rest_(initial_rest), projection_(projection) {}

  void bind(const EnergyContext& context) override {
    if (!context.garment) throw ConfigError("bending: no garment is bound");
    const Garment& garment = *context.garment;
    const Mesh& mesh = garment.mesh;
    if (!mesh.has_uv())
      throw ConfigError("bending: the garment has no material-space UVs (uv and uv_faces), so its rest lengths are unknown");
    if (garment.materials.empty()) throw ConfigError("bending: the garment has no materials");
    if (garment.face_material.size() && garment.face_material.size() != mesh.num_faces())
      throw ConfigError("bending: the garment has " + std::to_string(garment.face_material.size()) +
                        " face materials for " + std::to_string(mesh.num_faces()) + " faces");
    if (!mesh.uv.allFinite()) throw ConfigError("bending: the garment's UVs are not all finite");
    if (initial_rest_ && !mesh.vertices.allFinite())
      throw ConfigError("bending: rest: initial needs finite rest positions, the garment's are not");
    const int nf = mesh.num_faces();
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k)
        if (mesh.uv_faces(f, k) < 0 || mesh.uv_faces(f, k) >= mesh.uv.rows())
          throw ConfigError("bending: face " + std::to_string(f) + " has a UV index out of range");
    const auto topology = bending::find_hinges(mesh);

    auto stiffness = [&](int face) {
      const int m = garment.material_of(face);
      if (m < 0 || m >= static_cast<int>(garment.materials.size()))
        throw ConfigError("bending: face " + std::to_string(face) + " names material " + std::to_string(m) + " of " +
                          std::to_string(garment.materials.size()));
      const double kb = garment.materials[m].bending;
      if (!std::isfinite(kb)) throw ConfigError("bending: material '" + garment.materials[m].name + "' has a non-finite bending stiffness");
      return kb;
    };
    double mean_area = 0.0;
    for (int f = 0; f < nf; ++f) mean_area += uv_area(mesh, f);
    if (nf > 0) mean_area /= nf;

    vertices_ = mesh.num_vertices();
    hinges_.clear();
    hinges_.reserve(topology.size());
    skipped_ = 0;
    for (const auto& t : topology) {
      const double area = uv_area(mesh, t.face[0]) + uv_area(mesh, t.face[1]);
      const double kb = std::min(stiffness(t.face[0]), stiffness(t.face[1]));
      if (!(area > 2.0 * kDegenerateAreaFraction * mean_area)) {
        ++skipped_;
        continue;
      }
      const double l = 0.5 * (uv_length(mesh, t.face[0], t.corner[0]) + uv_length(mesh, t.face[1], t.corner[1]));
      HingeElement h;
      std::copy(std::begin(t.vertex), std::end(t.vertex), std::begin(h.vertex));
      h.c = scale_ * kb * l * l / (8.0 * area);
      h.rest_angle = initial_rest_ ? hinge_at(mesh.vertices, h).angle() : 0.0;
      hinges_.push_back(h);
    }
    if (skipped_ > 0)
      std::cerr << "drape: warning: bending: skipped " << skipped_ << " of " << topology.size()
                << " hinges whose faces have (nearly) zero material-space (UV) area\n";
    gather_.build(vertices_, num_hinges(), 4, [&](int e, int k) { return hinges_[e].vertex[k]; });
  }

  double value(const Eigen::MatrixX3d& x) const override {
    check(x);
    return deterministic_sum(num_hinges(), [&](int i) {
      const HingeElement& h = hinges_[static_cast<std::size_t>(i)];
      const double d = angle_offset(hinge_at(x, h).angle(), h.rest_angle);
      return h.c * d * d;
    });
  }

  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    check(x);
    std::vector<Eigen::Vector3d> corner(gather_.num_slots());
    const double e = deterministic_sum(num_hinges(), [&](int i) {
      const HingeElement& h = hinges_[static_cast<std::size_t>(i)];
      const dh::Hinge hinge = hinge_at(x, h);
      const double d = angle_offset(hinge.angle(), h.rest_angle);
      Eigen::Vector3d* out = corner.data() + 4 * static_cast<std::size_t>(i);
      if (hinge.degenerate()) {
        for (int k = 0; k < 4; ++k) out[k].setZero();
      } else {
        const dh::Vec12 grad = 2.0 * h.c * d * dh::gradient(wing0(hinge), wing1(hinge));
        for (int k = 0; k < 4; ++k) out[k] = grad.segment<3>(3 * k);
      }
      return h.c * d * d;
    });
    gather_.add_to(corner, g);
    return e;
  }

  void add_hessian(const Eigen::MatrixX3d& x, Triplets& t, bool project_psd) const override {
    hessian(x, t, project_psd, false);
  }
  void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& t, bool project_psd) const override {
    hessian(x, t, project_psd, true);
  }

 private:
  void hessian(const Eigen::MatrixX3d& x, Triplets& t, bool project_psd, bool lower) const {
    check(x);
    const std::size_t offset = t.size();
    const int n = num_hinges();
    const std::size_t per_hinge = hessian_entries<4>(lower);
    t.resize(offset + per_hinge * static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n >= kParallelHessianMinimum)
    for (int i = 0; i < n; ++i) {
      const HingeElement& h = hinges_[static_cast<std::size_t>(i)];
      const dh::Hinge hinge = hinge_at(x, h);
      dh::Mat12 block;
      if (hinge.degenerate()) {
        block.setZero();
      } else {
        const dh::Wing w0 = wing0(hinge), w1 = wing1(hinge);
        const dh::Vec12 grad = dh::gradient(w0, w1);
        block = (2.0 * h.c) * grad * grad.transpose();
        if (!project_psd || projection_ == Projection::Eigen) {
          const dh::WingDerivatives d0(w0, hinge.e, hinge.a0, hinge.n0, hinge.q0, hinge.e2, 1.0);
          const dh::WingDerivatives d1(w1, hinge.e, hinge.a1, hinge.n1, hinge.q1, hinge.e2, -1.0);
          block += (2.0 * h.c * angle_offset(hinge.angle(), h.rest_angle)) * dh::hessian(w0, d0, w1, d1);
          if (project_psd) project_to_psd(block);
        }
      }
      write_element_hessian<4>(block, h.vertex, lower, t.data() + offset + per_hinge * static_cast<std::size_t>(i));
    }
  }

  static dh::Wing wing0(const dh::Hinge& h) { return dh::Wing(h.e, h.a0, h.n0, h.q0, h.e2); }
  static dh::Wing wing1(const dh::Hinge& h) { return dh::Wing(h.e, h.a1, h.n1, h.q1, h.e2); }
  int num_hinges() const { return static_cast<int>(hinges_.size()); }
  void check(const Eigen::MatrixX3d& x) const {
    if (x.rows() != vertices_)
      throw Error("bending: " + std::to_string(x.rows()) + " vertices given, the bound garment has " +
                  std::to_string(vertices_) + (vertices_ == 0 ? " (bind() was not called)" : ""));
  }

  double scale_;
  bool initial_rest_;
  Projection projection_;
  int vertices_ = 0;
  int skipped_ = 0;
  std::vector<HingeElement> hinges_;
  CornerGather gather_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "bending";
  d.doc = "ArcSim's bending energy: per interior edge k_b l^2 / (2 (A0 + A1)) (theta - theta_rest)^2 / 4 of the signed "
          "dihedral angle, l and A from the material-space (UV) rest shape.";
  d.params = {
      {"stiffness_scale", ParamType::Float, "1.0", "multiplies every material's bending stiffness (N*m)", 0.0, 1e6},
      {"rest", ParamType::String, "flat", "rest dihedral angles: flat (0, panels cut flat) or initial (the garment's rest positions)",
       std::nullopt, std::nullopt, {"flat", "initial"}},
      {"projection", ParamType::String, "gauss_newton",
       "PSD Hessian for Newton: gauss_newton (2c dtheta dtheta^T, cheap) or eigen (exact block with negative eigenvalues clamped)",
       std::nullopt, std::nullopt, {"gauss_newton", "eigen"}}};
  d.create_energy = [](const Params& p) {
    return std::make_unique<Bending>(p.get_float("stiffness_scale"), p.get_string("rest") == "initial",
                                     p.get_string("projection") == "eigen" ? Projection::Eigen : Projection::GaussNewton);
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
