#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>
#include <drape/materials/materials.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>

#include "energy_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// One unit right triangle in material space, (0,0), (1,0), (0,1), A = 1/2,
// placed at `x` (three rows).
Garment unit_triangle(const Eigen::Matrix3d& x = Eigen::Matrix3d::Identity()) {
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 2;
  Eigen::MatrixX2d uv(3, 2);
  uv << 0, 0, 1, 0, 0, 1;
  Eigen::MatrixX3d v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Garment g = small_garment(v, f, uv);
  g.mesh.vertices = x;
  return g;
}

Eigen::MatrixX3d triangle(double fu_x, double fv_x, double fv_y) {
  // x0 = 0, x1 = F e_u, x2 = F e_v with F columns (fu_x, 0, 0) and (fv_x, fv_y, 0).
  Eigen::MatrixX3d x(3, 3);
  x << 0, 0, 0, fu_x, 0, 0, fv_x, fv_y, 0;
  return x;
}

const Eigen::Vector4d kKnit{16.6, -14.7, 34.5, 36.9};

}  // namespace

TEST_CASE("stretching loads as an energy with stiffness_scale 1 by default", "[stretching]") {
  const PluginDescriptor& d = plugins().get("stretching");
  CHECK(d.kind == "energy");
  CHECK(d.file.find("libdrape_plugin_stretching") != std::string::npos);
  CHECK(params_for("stretching", "{}").get_float("stiffness_scale") == 1.0);
  CHECK_THROWS_WITH(params_for("stretching", "{stiffness_scale: -1}"), Catch::Contains("'stiffness_scale'"));
  CHECK_THROWS_AS(params_for("stretching", "{stiffnes_scale: 2}"), ConfigError);
}

TEST_CASE("stretching matches ArcSim's energy on hand-computed strains", "[stretching]") {
  const Garment g = unit_triangle();
  const auto e = bound_energy("stretching", "{}", g);
  const double area = 0.5;
  // 10% stretch in u: G00 = (1.1^2 - 1) / 2, everything else 0.
  const double g00 = (1.1 * 1.1 - 1.0) / 2.0;
  CHECK(e->value(triangle(1.1, 0.0, 1.0)) == Approx(area * kKnit[0] * g00 * g00 / 2).epsilon(1e-12));
  // 10% in v: k_vv.
  CHECK(e->value(triangle(1.0, 0.0, 1.1)) == Approx(area * kKnit[2] * g00 * g00 / 2).epsilon(1e-12));
  // Both: the coupling k_uv enters as 2 k1 G00 G11 (negative for the knit).
  const double both = area * (kKnit[0] + kKnit[2] + 2 * kKnit[1]) * g00 * g00 / 2;
  CHECK(e->value(triangle(1.1, 0.0, 1.1)) == Approx(both).epsilon(1e-12));
  // Shear x2 = (s, 1, 0): G11 = s^2 / 2, G01 = s / 2, and G01^2 enters once with k_shear.
  const double s = 0.2, g11 = s * s / 2, g01 = s / 2;
  CHECK(e->value(triangle(1.0, s, 1.0)) == Approx(area * (kKnit[2] * g11 * g11 + kKnit[3] * g01 * g01) / 2).epsilon(1e-12));
  // stiffness_scale multiplies it.
  CHECK(bound_energy("stretching", "{stiffness_scale: 3}", g)->value(triangle(1.1, 0.0, 1.0)) ==
        Approx(3 * area * kKnit[0] * g00 * g00 / 2).epsilon(1e-12));
}

TEST_CASE("stretching's axes are the UV axes, whatever the triangle's shape and place", "[stretching]") {
  // A triangle with edges rotated 30 degrees in UV, 0.1 m on a side, placed at
  // (2, 3): stretching it 10% along the UV u axis (x = (1.1 u, v, 0) relative to
  // the first corner) costs A k_uu G00^2 / 2 with A = 0.005, along v A k_vv G11^2 / 2.
  const double c = std::cos(0.5235987755982988), s = std::sin(0.5235987755982988);
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 2;
  Eigen::MatrixX2d uv(3, 2);
  uv.row(0) << 2.0, 3.0;
  uv.row(1) = uv.row(0) + 0.1 * Eigen::RowVector2d(c, s);
  uv.row(2) = uv.row(0) + 0.1 * Eigen::RowVector2d(-s, c);
  Garment g = small_garment(Eigen::MatrixX3d::Zero(3, 3), f, uv);
  const auto e = bound_energy("stretching", "{}", g);
  Eigen::MatrixX3d along_u(3, 3), along_v(3, 3);
  for (int k = 0; k < 3; ++k) {
    const Eigen::RowVector2d p = uv.row(k) - uv.row(0);
    along_u.row(k) << 1.1 * p.x(), p.y(), 0.0;
    along_v.row(k) << p.x(), 1.1 * p.y(), 0.0;
  }
  const double g00 = (1.1 * 1.1 - 1.0) / 2.0;
  CHECK(e->value(along_u) == Approx(0.005 * kKnit[0] * g00 * g00 / 2).epsilon(1e-10));
  CHECK(e->value(along_v) == Approx(0.005 * kKnit[2] * g00 * g00 / 2).epsilon(1e-10));
}

TEST_CASE("stretching is zero at the flat rest state and invariant to rigid motions", "[stretching]") {
  const auto garment = two_material_grid(5, 0.1);
  const auto e = bound_energy("stretching", "{}", *garment);
  const Eigen::MatrixX3d rest = garment->mesh.vertices;
  CHECK(e->value(rest) == Approx(0.0).margin(1e-20));
  CHECK(gradient_of(*e, rest).cwiseAbs().maxCoeff() < 1e-12);  // rounding of F = I
  CHECK(e->value(rigidly_moved(rest)) == Approx(0.0).margin(1e-20));
  const Eigen::MatrixX3d x = perturbed(rest, 0.02, 3);
  const double ex = e->value(x);
  CHECK(ex > 0.0);
  CHECK(e->value(rigidly_moved(x)) == Approx(ex).epsilon(1e-10));
}

TEST_CASE("stretching is anisotropic: stretch along u costs k_uu, along v k_vv", "[stretching]") {
  const auto garment = grid_garment(4, 0.1);  // one knit material, uv = (x, y) of the rest grid
  const auto e = bound_energy("stretching", "{}", *garment);
  Eigen::MatrixX3d along_u = garment->mesh.vertices, along_v = garment->mesh.vertices;
  along_u.col(0) *= 1.05;
  along_v.col(1).array() = 1.0 + (along_v.col(1).array() - 1.0) * 1.05;
  const double g = (1.05 * 1.05 - 1.0) / 2.0, area = 0.3 * 0.3;
  CHECK(e->value(along_u) == Approx(area * kKnit[0] * g * g / 2).epsilon(1e-10));
  CHECK(e->value(along_v) == Approx(area * kKnit[2] * g * g / 2).epsilon(1e-10));
  CHECK(e->value(along_v) / e->value(along_u) == Approx(34.5 / 16.6).epsilon(1e-10));
}

TEST_CASE("stretching derivatives match finite differences on a perturbed grid of two materials", "[stretching][gradcheck]") {
  const auto garment = two_material_grid(5, 0.1);
  const auto e = bound_energy("stretching", "{}", *garment);
  for (double amount : {0.005, 0.03}) {  // mostly tension / a mix of tension and compression
    const Eigen::MatrixX3d x = perturbed(garment->mesh.vertices, amount, 11);
    const GradCheckReport r = check_energy_derivatives(*e, x);
    INFO("perturbation " << amount << "\n" << r.str());
    CHECK(r.entries.size() == 4);
    CHECK(r.ok(1e-5));
  }
}

TEST_CASE("stretching with a 100x stiffer material stays finite and exact", "[stretching][gradcheck]") {
  const auto garment = two_material_grid(5, 0.1);
  garment->materials[1].stretch *= 100.0;
  const auto e = bound_energy("stretching", "{}", *garment);
  const Eigen::MatrixX3d x = perturbed(garment->mesh.vertices, 0.03, 5);
  CHECK(std::isfinite(e->value(x)));
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.ok(1e-5));
}

TEST_CASE("stretching's projected Hessian is the nearest PSD matrix of each face's block", "[stretching]") {
  Eigen::MatrixX3d on_a_line(3, 3), at_a_point = Eigen::MatrixX3d::Constant(3, 3, 0.3);
  on_a_line << 0, 0, 0, 0.5, 0.2, 0.1, -0.4, -0.16, -0.08;  // rank-1 F
  const std::vector<std::pair<std::string, Eigen::MatrixX3d>> states = {
      {"compressed 20%", perturbed(triangle(0.8, 0.1, 0.8), 0.05, 2)},  // S < 0: the exact block is indefinite
      {"stretched 20%", perturbed(triangle(1.2, 0.1, 1.2), 0.05, 2)},   // S > 0: already PSD
      {"stretched in u, compressed in v", perturbed(triangle(1.3, 0.0, 0.7), 0.05, 3)},
      {"collapsed to a line", on_a_line},
      {"collapsed to a point", at_a_point}};
  for (const bool odd_material : {false, true}) {
    Garment g = unit_triangle();
    // A (non-physical) stiffness whose K is indefinite: projection needed even under tension.
    if (odd_material) g.materials[0].stretch << 10.0, 30.0, 10.0, 5.0;
    const auto e = bound_energy("stretching", "{}", g);
    for (const auto& [what, x] : states) {
      const Eigen::MatrixXd exact = dense_hessian(*e, x, false);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(exact);
      const Eigen::MatrixXd nearest =
          eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
      const Eigen::MatrixXd projected = dense_hessian(*e, x, true);
      INFO(what << (odd_material ? ", indefinite K" : "") << ": exact eigenvalues " << eig.eigenvalues().transpose());
      if (what == "compressed 20%") CHECK(eig.eigenvalues().minCoeff() < -1e-3 * eig.eigenvalues().maxCoeff());
      CHECK((projected - nearest).cwiseAbs().maxCoeff() <= 1e-10 * exact.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("for ArcSim's knit the in-plane negative curvature is filtered to its magnitude", "[stretching][arcsim]") {
  // ArcSim's table makes the density non-convex over much of the strain space.
  // For model arcsim faces the projection replaces the in-plane block's negative
  // eigenvalues by their magnitudes (absolute eigenvalue filtering) and clamps
  // the out-of-plane (buckling) ones; in-plane and out-of-plane variations do
  // not couple, so the expected matrix comes from the exact Hessian's eigen-
  // decomposition, each eigenvector classified by whether it moves the vertices
  // out of the triangle's plane.
  Garment g = unit_triangle();
  g.materials[0] = MaterialTable::builtin().get("gray-interlock");
  const auto e = bound_energy("stretching", "{}", g);
  int filtered = 0;
  for (int seed = 1; seed <= 40; ++seed) {
    const Eigen::MatrixX3d x = perturbed(triangle(1.05, 0.05, 1.08), 0.06, seed);
    const Eigen::MatrixXd exact = dense_hessian(*e, x, false);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(exact);
    const Eigen::Vector3d normal = (x.row(1) - x.row(0)).cross(x.row(2) - x.row(0)).normalized().transpose();
    Eigen::VectorXd f(9);
    bool in_plane_negative = false;
    for (int k = 0; k < 9; ++k) {
      const Eigen::VectorXd v = eig.eigenvectors().col(k);
      double out_of_plane = 0;
      for (int a = 0; a < 3; ++a) out_of_plane += std::pow(normal.dot(v.segment<3>(3 * a)), 2);
      const double lambda = eig.eigenvalues()[k];
      const bool in_plane = out_of_plane < 0.5;
      f[k] = in_plane ? std::abs(lambda) : std::max(lambda, 0.0);
      in_plane_negative |= in_plane && lambda < -1e-6 * eig.eigenvalues().cwiseAbs().maxCoeff();
    }
    if (!in_plane_negative) continue;
    ++filtered;
    const Eigen::MatrixXd expected = eig.eigenvectors() * f.asDiagonal() * eig.eigenvectors().transpose();
    const Eigen::MatrixXd projected = dense_hessian(*e, x, true);
    INFO("seed " << seed << ": exact eigenvalues " << eig.eigenvalues().transpose());
    CHECK((projected - expected).cwiseAbs().maxCoeff() <= 1e-8 * exact.cwiseAbs().maxCoeff());
  }
  CHECK(filtered >= 5);  // the states do exercise the filter
}

TEST_CASE("stretching skips faces with zero material-space area and counts them", "[stretching]") {
  // Two faces; the second's UV triangle is collinear (zero area).
  Eigen::MatrixX3d v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  Eigen::MatrixX3i f(2, 3);
  f << 0, 1, 2, 1, 3, 2;
  Eigen::MatrixX2d uv(5, 2);
  uv << 0, 0, 1, 0, 0, 1, 2, 0, 3, 0;
  Eigen::MatrixX3i uvf(2, 3);
  uvf << 0, 1, 2, 1, 3, 4;
  const Garment g = small_garment(v, f, uv, uvf);
  std::unique_ptr<Energy> e;
  {
    CerrCapture cerr;
    e = bound_energy("stretching", "{}", g);
    CHECK_THAT(cerr.str(), Catch::Contains("skipped 1 of 2 faces"));
  }
  Eigen::MatrixX3d x = v;
  x(1, 0) = 1.1;  // stretches face 0 by 10% in u; moves face 1 too, which must not count
  x(3, 1) = 7.0;
  const double g00 = (1.1 * 1.1 - 1.0) / 2.0;
  CHECK(e->value(x) == Approx(0.5 * kKnit[0] * g00 * g00 / 2).epsilon(1e-12));
  const Eigen::MatrixX3d grad = gradient_of(*e, x);
  CHECK(grad.allFinite());
  CHECK(grad.row(3).isZero());
  CHECK(dense_hessian(*e, x, true).allFinite());
}

TEST_CASE("stretching of a thin material-space sliver is finite and exact", "[stretching][gradcheck]") {
  // A UV triangle 1e-4 as high as it is long: kept (it is real material), stiff but finite.
  Eigen::MatrixX3d v(4, 3);
  v << 0, 0, 0, 0.1, 0, 0, 0, 0.1, 0, 0.05, 1e-5, 0;
  Eigen::MatrixX3i f(2, 3);
  f << 0, 1, 2, 0, 3, 1;
  Eigen::MatrixX2d uv(4, 2);
  uv << 0, 0, 0.1, 0, 0, 0.1, 0.05, -1e-5;
  const Garment g = small_garment(v, f, uv);
  CerrCapture cerr;
  const auto e = bound_energy("stretching", "{}", g);
  CHECK(cerr.str().empty());
  const Eigen::MatrixX3d x = perturbed(v, 1e-6, 9);
  CHECK(std::isfinite(e->value(x)));
  const GradCheckReport r = check_energy_derivatives(*e, x, {1e-9, 64, 7});
  INFO(r.str());
  CHECK(r.ok(1e-5));
}

TEST_CASE("stretching handles a 3D triangle collapsed to a point", "[stretching]") {
  const Garment g = unit_triangle();
  const auto e = bound_energy("stretching", "{}", g);
  const Eigen::MatrixX3d x = Eigen::MatrixX3d::Constant(3, 3, 0.25);
  // F = 0, G = -I/2: E = A (k0 + k2 + 2 k1) / 8, zero gradient.
  CHECK(e->value(x) == Approx(0.5 * (kKnit[0] + kKnit[2] + 2 * kKnit[1]) / 8).epsilon(1e-12));
  CHECK(gradient_of(*e, x).isZero());
  CHECK(dense_hessian(*e, x, true).allFinite());
}

TEST_CASE("stretching reports a garment without UVs or with a bad material index", "[stretching]") {
  auto garment = grid_garment(3, 0.1);
  garment->mesh.uv.resize(0, 2);
  garment->mesh.uv_faces.resize(0, 3);
  CHECK_THROWS_WITH(bound_energy("stretching", "{}", *garment), Catch::Contains("UV"));
  auto two = grid_garment(3, 0.1, true);
  two->face_material[3] = 2;
  CHECK_THROWS_WITH(bound_energy("stretching", "{}", *two), Catch::Contains("face 3 names material 2"));
  two->face_material.resize(5);
  CHECK_THROWS_WITH(bound_energy("stretching", "{}", *two), Catch::Contains("5 face materials for 8 faces"));
  const auto e = bound_energy("stretching", "{}", *grid_garment(3, 0.1));
  CHECK_THROWS_WITH(e->value(Eigen::MatrixX3d::Zero(4, 3)), Catch::Contains("4 vertices given"));
}

TEST_CASE("stretching works as a graph loss node on float positions", "[stretching][gradcheck]") {
  const auto garment = two_material_grid(4, 0.1);
  const Assets assets = assets_with(garment);
  auto node = make_node("stretching");
  Tensor x(2, 16, 3);
  for (int b = 0; b < 2; ++b) x.mat(b) = perturbed(garment->mesh.vertices, 0.02, 20 + b).cast<float>();
  const auto out = run_forward(*node, {{"x", x}}, {"g", 0, &assets});
  const auto e = bound_energy("stretching", "{}", *garment);
  for (int b = 0; b < 2; ++b)
    CHECK(out.at("energy")(b, 0, 0) == Approx(e->value(x.mat(b).cast<double>())).epsilon(1e-5));
  const GradCheckReport r = check_node_gradients(*node, {{"x", x}}, {"g", 0, &assets});
  INFO(r.str());
  CHECK(r.ok(1e-2));
}
