// ArcSim's anisotropic membrane energy summed over the garment's faces (see
// membrane.hpp for the per-face model), stiffness from each face's material.
//
// Degenerate material space: a face whose UV triangle has an area of at most
// 1e-10 times the mean face area (zero-area or collapsed UV triangles) carries
// no material; it is skipped (no energy, gradient or Hessian) and bind() prints
// one warning with the count. Thin but valid slivers above that are kept exactly:
// their energies are finite, only stiff. UVs that are not finite are a
// ConfigError.
//
// PSD projection (project_psd): a face whose K and stress matrix S are both PSD
// already has a PSD Hessian and is left alone (a face in tension both ways).
// Near rest S is small but of mixed sign, so on a dressed garment nearly every
// face takes the projection path, and about half need the 4x4 eigen-solve below.
// Otherwise the exact nearest PSD matrix of the 9x9 block is computed from far
// smaller problems: with F = X c and c = q t (q 3x2 orthonormal), Y = X q, the
// block is (q (x) I3) H_Y (q (x) I3)^T with H_Y = d2E/dY2, and an orthonormal
// embedding commutes with clamping eigenvalues; H_Y splits further into an
// out-of-plane 2x2 block (closed form) and an in-plane 4x4 block
// (membrane.hpp, projected_hessian_in_Y).
#include <drape/element_assembly.hpp>
#include <drape/plugin.hpp>

#include <cmath>
#include <iostream>

#include "membrane.hpp"

namespace {

using namespace drape;
namespace mb = drape::membrane;

constexpr double kDegenerateAreaFraction = 1e-10;

class Stretching final : public Energy {
 public:
  explicit Stretching(double stiffness_scale) : scale_(stiffness_scale) {}

  void bind(const EnergyContext& context) override {
    if (!context.garment) throw ConfigError("stretching: no garment is bound");
    const Garment& garment = *context.garment;
    const Mesh& mesh = garment.mesh;
    if (!mesh.has_uv())
      throw ConfigError("stretching: the garment has no material-space UVs (uv and uv_faces), so its rest shape is unknown");
    if (garment.materials.empty()) throw ConfigError("stretching: the garment has no materials");
    if (garment.face_material.size() && garment.face_material.size() != mesh.num_faces())
      throw ConfigError("stretching: the garment has " + std::to_string(garment.face_material.size()) +
                        " face materials for " + std::to_string(mesh.num_faces()) + " faces");
    if (!mesh.uv.allFinite()) throw ConfigError("stretching: the garment's UVs are not all finite");
    for (const Material& m : garment.materials)
      if (!m.stretch.allFinite()) throw ConfigError("stretching: material '" + m.name + "' has a non-finite stretch stiffness");
    const int nf = mesh.num_faces();
    vertices_ = mesh.num_vertices();
    faces_.clear();
    faces_.reserve(static_cast<std::size_t>(nf));

    std::vector<double> area(static_cast<std::size_t>(nf));
    std::vector<Eigen::Matrix2d> dm(static_cast<std::size_t>(nf));
    double total = 0.0;
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) {
        if (mesh.faces(f, k) < 0 || mesh.faces(f, k) >= vertices_ || mesh.uv_faces(f, k) < 0 || mesh.uv_faces(f, k) >= mesh.uv.rows())
          throw ConfigError("stretching: face " + std::to_string(f) + " has a vertex or UV index out of range");
      }
      const Eigen::Vector2d u0 = mesh.uv.row(mesh.uv_faces(f, 0)), u1 = mesh.uv.row(mesh.uv_faces(f, 1)),
                            u2 = mesh.uv.row(mesh.uv_faces(f, 2));
      dm[f].col(0) = u1 - u0;
      dm[f].col(1) = u2 - u0;
      area[f] = 0.5 * std::abs(dm[f].determinant());
      total += area[f];
    }
    const double threshold = nf > 0 ? kDegenerateAreaFraction * total / nf : 0.0;
    skipped_ = 0;
    Eigen::Matrix<double, 3, 2> d;
    d << -1.0, -1.0, 1.0, 0.0, 0.0, 1.0;
    for (int f = 0; f < nf; ++f) {
      const int m = garment.material_of(f);
      if (m < 0 || m >= static_cast<int>(garment.materials.size()))
        throw ConfigError("stretching: face " + std::to_string(f) + " names material " + std::to_string(m) + " of " +
                          std::to_string(garment.materials.size()));
      if (!(area[f] > threshold)) {
        ++skipped_;
        continue;
      }
      mb::Face face;
      for (int k = 0; k < 3; ++k) face.vertex[k] = mesh.faces(f, k);
      face.c = d * dm[f].inverse();
      // Thin QR by Gram-Schmidt: c's two columns are independent because Dm is invertible.
      const double r00 = face.c.col(0).norm();
      face.q.col(0) = face.c.col(0) / r00;
      const double r01 = face.q.col(0).dot(face.c.col(1));
      const Eigen::Vector3d rest = face.c.col(1) - r01 * face.q.col(0);
      const double r11 = rest.norm();
      face.q.col(1) = rest / r11;
      face.t << r00, r01, 0.0, r11;
      face.k = area[f] * scale_ * garment.materials[m].stretch;
      face.k_psd = mb::stiffness_is_psd(face.k);
      faces_.push_back(face);
    }
    if (skipped_ > 0)
      std::cerr << "drape: warning: stretching: skipped " << skipped_ << " of " << nf
                << " faces whose material-space (UV) area is (nearly) zero\n";
    gather_.build(vertices_, static_cast<int>(faces_.size()), 3, [&](int e, int k) { return faces_[e].vertex[k]; });
  }

  double value(const Eigen::MatrixX3d& x) const override {
    check(x);
    return deterministic_sum(num_faces(), [&](int i) {
      const mb::Face& f = faces_[static_cast<std::size_t>(i)];
      return mb::energy(f.k, mb::green_strain(mb::deformation_gradient(x, f)));
    });
  }

  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    check(x);
    std::vector<Eigen::Vector3d> corner(gather_.num_slots());
    const double e = deterministic_sum(num_faces(), [&](int i) {
      const mb::Face& f = faces_[static_cast<std::size_t>(i)];
      const mb::Mat32 F = mb::deformation_gradient(x, f);
      const Eigen::Vector3d strain = mb::green_strain(F);
      const mb::Mat32 P = mb::stress(F, mb::strain_stress(f.k, strain));
      // dE/dx_a = P c_a^T since F = sum_a x_a c_a.
      for (int a = 0; a < 3; ++a) corner[static_cast<std::size_t>(3 * i + a)] = P * f.c.row(a).transpose();
      return mb::energy(f.k, strain);
    });
    gather_.add_to(corner, g);
    return e;
  }

  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const override {
    hessian(x, h, project_psd, false);
  }
  void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd) const override {
    hessian(x, h, project_psd, true);
  }

 private:
  void hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd, bool lower) const {
    check(x);
    const std::size_t offset = h.size();
    const int n = num_faces();
    const std::size_t per_face = hessian_entries<3>(lower);
    h.resize(offset + per_face * static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n >= kParallelHessianMinimum)
    for (int i = 0; i < n; ++i) {
      const mb::Face& f = faces_[static_cast<std::size_t>(i)];
      const mb::Mat32 F = mb::deformation_gradient(x, f);
      const Eigen::Vector3d s = mb::strain_stress(f.k, mb::green_strain(F));
      mb::Mat9 block;
      if (!project_psd || (f.k_psd && mb::stress_is_psd(s)))
        block = mb::lift(mb::hessian_in_F(F, f.k, s), f.c);
      else
        block = mb::lift(mb::projected_hessian_in_Y(F, f.k, s, f.t), f.q);
      write_element_hessian<3>(block, f.vertex, lower, h.data() + offset + per_face * static_cast<std::size_t>(i));
    }
  }

  int num_faces() const { return static_cast<int>(faces_.size()); }
  void check(const Eigen::MatrixX3d& x) const {
    if (x.rows() != vertices_)
      throw Error("stretching: " + std::to_string(x.rows()) + " vertices given, the bound garment has " +
                  std::to_string(vertices_) + (vertices_ == 0 ? " (bind() was not called)" : ""));
  }

  double scale_;
  int vertices_ = 0;
  int skipped_ = 0;
  std::vector<mb::Face> faces_;
  CornerGather gather_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "stretching";
  d.doc = "ArcSim's anisotropic membrane energy: per face A (k_uu G00^2 + k_vv G11^2 + 2 k_uv G00 G11 + k_shear G01^2) / 2 "
          "of the Green strain G against the material-space (UV) rest shape.";
  d.params = {{"stiffness_scale", ParamType::Float, "1.0",
               "multiplies every material's stretch stiffness [k_uu, k_uv, k_vv, k_shear] (N/m)", 0.0, 1e6}};
  d.create_energy = [](const Params& p) { return std::make_unique<Stretching>(p.get_float("stiffness_scale")); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
