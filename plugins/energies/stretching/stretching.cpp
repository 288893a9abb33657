// The membrane (stretching) energy summed over the garment's faces: per face
// A psi(g) of the Green strain g against the material-space (UV) rest shape,
// psi from the face's material (drape/physics/arcsim_material.hpp):
//  * model arcsim: ArcSim's data-driven stiffness, k(g) from its sample table,
//    psi(g) the work of ArcSim's stress along the straight strain path
//    (drape/physics/arcsim_material.hpp);
//  * model linear: constant k, psi = (k_uu g0^2 + k_vv g1^2 + 2 k_uv g0 g1 + k_shear g2^2) / 2
//    (drape's model before ArcSim's tables, kept to reproduce old results).
//
// Degenerate material space: a face whose UV triangle has an area of at most
// 1e-10 times the mean face area (zero-area or collapsed UV triangles) carries
// no material; it is skipped (no energy, gradient or Hessian) and bind() prints
// one warning with the count. Thin but valid slivers above that are kept exactly:
// their energies are finite, only stiff.
//
// PSD projection (project_psd): a face whose d2psi/dg2 and stress matrix S are
// both PSD already has a PSD Hessian and is left alone (a face in tension both
// ways under a convex psi). Otherwise the exact nearest PSD matrix of the 9x9
// block is computed from far smaller problems: with F = X c and c = q t (q 3x2
// orthonormal), Y = X q, the block is (q (x) I3) H_Y (q (x) I3)^T with
// H_Y = d2E/dY2, and an orthonormal embedding commutes with clamping
// eigenvalues; H_Y splits further into an out-of-plane 2x2 block (closed form)
// and an in-plane 4x4 block (membrane.hpp, projected_hessian_in_Y). For model
// arcsim faces the in-plane block's negative eigenvalues are replaced by their
// magnitudes instead of clamped (absolute eigenvalue filtering): ArcSim's
// table makes the density non-convex over much of the strain space, and with
// clamping Newton's model predicted no curvature where the energy curves up
// (measured in docs/findings.md, "What settles the heavy drapes"). Linear faces
// keep the nearest PSD matrix, as before.
//
// Compression (`compressive_stiffness` s, default 1: ArcSim's tables as they
// are): psi is evaluated at G~, G with its compressive principal values
// scaled by sqrt(s) (compression.hpp), so a face shortens at s times the
// stiffness it stretches with; a face with no compressive principal strain is
// computed exactly as before. The derivatives of G~(G) come from Dual<3>
// (value, gradient, Hessian of the map), composed with psi's: dpsi~ = J^T dpsi,
// d2psi~ = J^T d2psi J + sum_k dpsi_k d2G~_k.
#include <drape/physics/arcsim_material.hpp>
#include <drape/element_energy.hpp>
#include <drape/plugin.hpp>
#include <drape/warnings.hpp>

#include <cmath>
#include <memory>

#include "compression.hpp"
#include "membrane.hpp"

namespace {

using namespace drape;
namespace mb = drape::membrane;

constexpr double kDegenerateAreaFraction = 1e-10;

// What a face needs at run time, precomputed from the rest state.
struct Face {
  mb::Mat32 c;  // F = X c
  mb::Mat32 q;  // c = q t with q^T q = I (thin QR): an orthonormal basis of c's columns
  Eigen::Matrix2d t;
  double area;  // material-space area times stiffness_scale
  int material;
};

class Stretching final : public ElementEnergy<3> {
 public:
  Stretching(double stiffness_scale, double compressive_stiffness)
      : scale_(stiffness_scale), compression_(compressive_stiffness) {}

  void bind(const EnergyContext& context) override {
    const Garment& garment = checked_garment(context);
    const Mesh& mesh = garment.mesh;
    materials_ = garment.materials;
    tables_.assign(materials_.size(), nullptr);
    for (std::size_t m = 0; m < materials_.size(); ++m)
      if (materials_[m].model == Material::Model::Arcsim)
        tables_[m] = std::make_shared<arcsim::StretchingTable>(materials_[m].arcsim);

    const int nf = mesh.num_faces();
    std::vector<double> area(static_cast<std::size_t>(nf));
    std::vector<Eigen::Matrix2d> dm(static_cast<std::size_t>(nf));
    double total = 0.0;
    for (int f = 0; f < nf; ++f) {
      const Eigen::Vector2d u0 = mesh.uv.row(mesh.uv_faces(f, 0)), u1 = mesh.uv.row(mesh.uv_faces(f, 1)),
                            u2 = mesh.uv.row(mesh.uv_faces(f, 2));
      dm[f].col(0) = u1 - u0;
      dm[f].col(1) = u2 - u0;
      area[f] = 0.5 * std::abs(dm[f].determinant());
      total += area[f];
    }
    const double threshold = nf > 0 ? kDegenerateAreaFraction * total / nf : 0.0;
    int skipped = 0;
    Eigen::Matrix<double, 3, 2> d;
    d << -1.0, -1.0, 1.0, 0.0, 0.0, 1.0;
    faces_.clear();
    std::vector<Element> elements;
    for (int f = 0; f < nf; ++f) {
      if (!(area[f] > threshold)) {
        ++skipped;
        continue;
      }
      Face face;
      face.c = d * dm[f].inverse();
      // Thin QR by Gram-Schmidt: c's two columns are independent because Dm is invertible.
      const double r00 = face.c.col(0).norm();
      face.q.col(0) = face.c.col(0) / r00;
      const double r01 = face.q.col(0).dot(face.c.col(1));
      const Eigen::Vector3d rest = face.c.col(1) - r01 * face.q.col(0);
      const double r11 = rest.norm();
      face.q.col(1) = rest / r11;
      face.t << r00, r01, 0.0, r11;
      face.area = area[f] * scale_;
      face.material = garment.material_of(f);
      faces_.push_back(face);
      elements.push_back({mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)});
    }
    if (skipped > 0)
      warn("skipped " + std::to_string(skipped) + " of " + std::to_string(nf) +
           " faces whose material-space (UV) area is (nearly) zero");
    set_elements(mesh.num_vertices(), std::move(elements));
  }

 private:
  // psi and its derivatives at strain g, scaled by the face's area. The
  // linear model scales its stiffness first, as drape did before the ArcSim
  // model, so that old drapes are reproduced bit for bit.
  arcsim::MembraneDensity density(const Face& f, const Eigen::Vector3d& g, bool hessian = true) const {
    if (!compression_.compressed(g)) return material_density(f, g, hessian);
    return hessian ? compressed_density<Dual<3, 2>>(f, g) : compressed_density<Dual<3, 1>>(f, g);
  }

  // psi at G~(g) with its derivatives in g (module comment).
  template <class D>
  arcsim::MembraneDensity compressed_density(const Face& f, const Eigen::Vector3d& g) const {
    const std::array<D, 3> out = compression_.apply(std::array<D, 3>{D::variable(g[0], 0), D::variable(g[1], 1), D::variable(g[2], 2)});
    Eigen::Matrix3d j;
    for (int k = 0; k < 3; ++k) j.row(k) = out[static_cast<std::size_t>(k)].g.transpose();
    constexpr bool kHessian = D::kHessianSize == 3;
    const arcsim::MembraneDensity d = material_density(f, Eigen::Vector3d(out[0].v, out[1].v, out[2].v), kHessian);
    arcsim::MembraneDensity r;
    r.psi = d.psi;
    r.dpsi = j.transpose() * d.dpsi;
    if constexpr (kHessian) {
      r.d2psi = j.transpose() * d.d2psi * j;
      for (int k = 0; k < 3; ++k) r.d2psi += d.dpsi[k] * out[static_cast<std::size_t>(k)].h;
    }
    return r;
  }

  arcsim::MembraneDensity material_density(const Face& f, const Eigen::Vector3d& g, bool hessian) const {
    const std::size_t m = static_cast<std::size_t>(f.material);
    if (!tables_[m]) return arcsim::linear_membrane_density(f.area * materials_[m].stretch, g);
    arcsim::MembraneDensity d = tables_[m]->density(g, hessian);
    d.psi *= f.area;
    d.dpsi *= f.area;
    d.d2psi *= f.area;
    return d;
  }

  // psi alone (what energy values and the line search need): the ArcSim
  // lookup without its derivatives.
  double energy(const Face& f, const Eigen::Vector3d& g_in) const {
    Eigen::Vector3d g = g_in;
    if (compression_.compressed(g_in)) {
      const std::array<double, 3> out = compression_.apply(std::array<double, 3>{g_in[0], g_in[1], g_in[2]});
      g = Eigen::Vector3d(out[0], out[1], out[2]);
    }
    const std::size_t m = static_cast<std::size_t>(f.material);
    return tables_[m] ? f.area * tables_[m]->energy_density(g) : material_density(f, g, false).psi;
  }

  double element_value(int e, const Stencil& x) const override {
    const Face& f = faces_[static_cast<std::size_t>(e)];
    return energy(f, mb::green_strain(mb::deformation_gradient(x, f.c)));
  }

  double element_gradient(int e, const Stencil& x, StencilGradient& grad) const override {
    const Face& f = faces_[static_cast<std::size_t>(e)];
    const mb::Mat32 F = mb::deformation_gradient(x, f.c);
    const arcsim::MembraneDensity d = density(f, mb::green_strain(F), false);
    // dE/dx_a = P c_a^T since F = sum_a x_a c_a.
    const mb::Mat32 P = mb::stress(F, d.dpsi);
    for (int a = 0; a < 3; ++a) grad.segment<3>(3 * a) = P * f.c.row(a).transpose();
    return d.psi;
  }

  void element_hessian(int e, const Stencil& x, bool project_psd, StencilHessian& h) const override {
    const Face& f = faces_[static_cast<std::size_t>(e)];
    const mb::Mat32 F = mb::deformation_gradient(x, f.c);
    const arcsim::MembraneDensity d = density(f, mb::green_strain(F));
    if (!project_psd || (mb::stress_is_psd(d.dpsi) && mb::stiffness_is_psd(d.d2psi))) {
      h = mb::lift(mb::hessian_in_F(F, d.d2psi, d.dpsi), f.c);
      return;
    }
    const bool arcsim_face = tables_[static_cast<std::size_t>(f.material)] != nullptr;  // absolute filtering
    h = mb::lift(mb::projected_hessian_in_Y(F, d.d2psi, d.dpsi, f.t, arcsim_face), f.q);
  }

  double scale_;
  mb::CompressionMap compression_;
  std::vector<Material> materials_;
  std::vector<std::shared_ptr<const arcsim::StretchingTable>> tables_;  // per material; null for linear
  std::vector<Face> faces_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "stretching";
  d.doc = "Membrane energy of the Green strain G against the material-space (UV) rest shape, per face A psi(G): "
          "ArcSim's data-driven stiffness for model arcsim materials (docs/materials.md), constant "
          "[k_uu, k_uv, k_vv, k_shear] for model linear.";
  d.params = {{.name = "stiffness_scale", .type = ParamType::Float, .default_value = "1.0",
               .doc = "multiplies every material's stretch stiffness (N/m)", .min = 0.0, .max = 1e6},
              {.name = "compressive_stiffness", .type = ParamType::Float, .default_value = "1.0",
               .doc = "the fraction of the material's stiffness left to compression: the Green strain's compressive "
                      "principal values are scaled by its square root before the material sees them (1: the "
                      "material as measured; docs/materials.md, \"Folds at the scale of knit\")",
               .min = 1e-4, .max = 1.0}};
  d.create_energy = [](const Params& p) {
    return std::make_unique<Stretching>(p.get_float("stiffness_scale"), p.get_float("compressive_stiffness"));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
