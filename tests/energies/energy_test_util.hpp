#pragma once
// Helpers for the energy tests: energies built through the build tree's
// registry and bound to a garment, garments of one or two triangles with
// hand-placed UVs, deterministic perturbations and rotations, the dense
// Hessian, and capturing what a plugin prints to std::cerr.
#include <drape/energy.hpp>
#include <drape/materials/materials.hpp>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <iostream>
#include <random>
#include <sstream>

#include "../plugins/plugin_test_util.hpp"

namespace drape::test {

// ArcSim's gray-interlock knit (materials/gray-interlock.json) as the region "knit".
inline Material arcsim_knit() {
  Material m = MaterialTable::builtin().get("gray-interlock");
  m.name = "knit";
  return m;
}

inline std::unique_ptr<Energy> bound_energy(const std::string& name, const std::string& yaml, const Garment& garment) {
  auto e = plugins().create_energy(name, params_for(name, yaml));
  EnergyContext ctx;
  ctx.garment = &garment;
  e->bind(ctx);
  return e;
}

// A garment of the given faces, positions and per-corner UVs (uv_faces = faces
// unless given), one knit material.
inline Garment small_garment(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, const Eigen::MatrixX2d& uv,
                             const Eigen::MatrixX3i& uv_faces = Eigen::MatrixX3i()) {
  Garment g;
  g.mesh.vertices = vertices;
  g.mesh.faces = faces;
  g.mesh.uv = uv;
  g.mesh.uv_faces = uv_faces.rows() ? uv_faces : faces;
  g.materials.push_back(Material{});
  g.materials[0].name = "knit";
  return g;
}

// grid_garment with a second material that differs in every stiffness (the
// T-shirt's print: 5x the stretch, 10x the bending of the knit).
inline std::shared_ptr<Garment> two_material_grid(int n, double spacing) {
  auto g = grid_garment(n, spacing, true);
  g->materials[1].stretch *= 5.0;
  g->materials[1].bending *= 10.0;
  return g;
}

inline Eigen::MatrixX3d perturbed(const Eigen::MatrixX3d& x, double scale, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::MatrixX3d y = x;
  for (Eigen::Index i = 0; i < y.size(); ++i) y.data()[i] += u(rng);
  return y;
}

// x rotated about an arbitrary axis and translated.
inline Eigen::MatrixX3d rigidly_moved(const Eigen::MatrixX3d& x) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, -1.0, 0.5).normalized()).toRotationMatrix();
  Eigen::MatrixX3d y = x * r.transpose();
  y.rowwise() += Eigen::RowVector3d(0.4, -2.0, 1.5);
  return y;
}

inline Eigen::MatrixXd dense_hessian(const Energy& e, const Eigen::MatrixX3d& x, bool project) {
  Triplets t;
  e.add_hessian(x, t, project);
  Eigen::SparseMatrix<double> h(3 * x.rows(), 3 * x.rows());
  h.setFromTriplets(t.begin(), t.end());
  return Eigen::MatrixXd(h);
}

inline Eigen::MatrixX3d gradient_of(const Energy& e, const Eigen::MatrixX3d& x) {
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
  e.add_gradient(x, g);
  return g;
}

// Everything written to std::cerr while it lives.
class CerrCapture {
 public:
  CerrCapture() : old_(std::cerr.rdbuf(buffer_.rdbuf())) {}
  ~CerrCapture() { std::cerr.rdbuf(old_); }
  std::string str() const { return buffer_.str(); }

 private:
  std::ostringstream buffer_;
  std::streambuf* old_;
};

}  // namespace drape::test
