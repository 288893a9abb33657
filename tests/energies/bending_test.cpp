#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "energy_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kKnitBending = 1e-5;

// Two unit-height triangles on the edge x0 = (0,0,0) -> x1 = (1,0,0): wing x2 =
// (0.5, 1, 0), wing x3 folded about the edge by phi. Faces (0,1,2) and (1,0,3),
// UVs the flat layout: A0 = A1 = 1/2, l = 1, so E = k_b l^2 / (2 (A0 + A1)) theta^2 / 4 = k_b theta^2 / 8.
Eigen::MatrixX3d hinge_positions(double phi) {
  Eigen::MatrixX3d x(4, 3);
  x << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -std::cos(phi), std::sin(phi);
  return x;
}

Garment hinge_garment(double rest_phi = 0.0) {
  Eigen::MatrixX3i f(2, 3);
  f << 0, 1, 2, 1, 0, 3;
  Eigen::MatrixX2d uv(4, 2);
  uv << 0, 0, 1, 0, 0.5, 1, 0.5, -1;
  return small_garment(hinge_positions(rest_phi), f, uv);
}

}  // namespace

TEST_CASE("bending loads as an energy with flat rest and Gauss-Newton projection by default", "[bending]") {
  const PluginDescriptor& d = plugins().get("bending");
  CHECK(d.kind == "energy");
  CHECK(d.file.find("libdrape_plugin_bending") != std::string::npos);
  const Params p = params_for("bending", "{}");
  CHECK(p.get_float("stiffness_scale") == 1.0);
  CHECK(p.get_string("rest") == "flat");
  CHECK(p.get_string("projection") == "gauss_newton");
  CHECK_THROWS_WITH(params_for("bending", "{rest: curved}"), Catch::Contains("'rest'"));
  CHECK_THROWS_WITH(params_for("bending", "{stiffness_scale: -2}"), Catch::Contains("'stiffness_scale'"));
  CHECK_THROWS_AS(params_for("bending", "{projection: svd}"), ConfigError);
}

TEST_CASE("bending matches ArcSim's energy on a folded hinge", "[bending]") {
  const Garment g = hinge_garment();
  const auto e = bound_energy("bending", "{}", g);
  CHECK(e->value(hinge_positions(0.0)) == Approx(0.0).margin(1e-30));
  for (double phi : {0.3, -0.3, 1.2, 2.5})
    CHECK(e->value(hinge_positions(phi)) == Approx(kKnitBending * phi * phi / 8).epsilon(1e-12));
  CHECK(bound_energy("bending", "{stiffness_scale: 4}", g)->value(hinge_positions(0.3)) ==
        Approx(4 * kKnitBending * 0.09 / 8).epsilon(1e-12));
}

TEST_CASE("bending's signed angle: rest initial measures from the rest fold", "[bending]") {
  // Rest folded by +0.4: folding to -0.2 costs (0.6)^2, to 0.4 nothing, to 0.5 (0.1)^2.
  const Garment g = hinge_garment(0.4);
  const auto e = bound_energy("bending", "{rest: initial}", g);
  CHECK(e->value(hinge_positions(0.4)) == Approx(0.0).margin(1e-25));
  CHECK(e->value(hinge_positions(-0.2)) == Approx(kKnitBending * 0.36 / 8).epsilon(1e-10));
  CHECK(e->value(hinge_positions(0.5)) == Approx(kKnitBending * 0.01 / 8).epsilon(1e-8));
  // The flat rest ignores the garment's fold.
  CHECK(bound_energy("bending", "{}", g)->value(hinge_positions(0.4)) == Approx(kKnitBending * 0.16 / 8).epsilon(1e-12));
}

TEST_CASE("bending uses the mean UV length across a seam and the softer material", "[bending]") {
  // Face 1 has its own UV copy of the edge, 1.2 long (area 0.6): l = 1.1, A0 + A1 = 1.1.
  Garment g = hinge_garment();
  g.mesh.uv.resize(7, 2);
  g.mesh.uv << 0, 0, 1, 0, 0.5, 1, 0.5, -1, 10, 0, 11.2, 0, 10.6, -1;
  g.mesh.uv_faces.resize(2, 3);
  g.mesh.uv_faces << 0, 1, 2, 5, 4, 6;
  const double phi = 0.7;
  CHECK(bound_energy("bending", "{}", g)->value(hinge_positions(phi)) ==
        Approx(kKnitBending * 1.21 / (2 * 1.1) * phi * phi / 4).epsilon(1e-12));

  Garment mixed = hinge_garment();
  mixed.materials.push_back(mixed.materials[0]);
  mixed.face_material.resize(2);
  mixed.face_material << 0, 1;
  mixed.materials[1].bending = 1e-3;  // stiffer: the knit's 1e-5 counts
  CHECK(bound_energy("bending", "{}", mixed)->value(hinge_positions(phi)) == Approx(1e-5 * phi * phi / 8).epsilon(1e-12));
  mixed.materials[1].bending = 1e-6;  // softer: it counts
  CHECK(bound_energy("bending", "{}", mixed)->value(hinge_positions(phi)) == Approx(1e-6 * phi * phi / 8).epsilon(1e-12));
}

TEST_CASE("bending is invariant to rigid motions and uniform scaling", "[bending]") {
  const auto garment = two_material_grid(5, 0.1);
  const auto e = bound_energy("bending", "{}", *garment);
  CHECK(e->value(garment->mesh.vertices) == Approx(0.0).margin(1e-30));
  CHECK(gradient_of(*e, garment->mesh.vertices).isZero());
  const Eigen::MatrixX3d x = perturbed(garment->mesh.vertices, 0.02, 4);
  const double ex = e->value(x);
  CHECK(ex > 0.0);
  CHECK(e->value(rigidly_moved(x)) == Approx(ex).epsilon(1e-10));
  CHECK(e->value(2.5 * x) == Approx(ex).epsilon(1e-10));
}

TEST_CASE("bending derivatives match finite differences on a perturbed grid of two materials", "[bending][gradcheck]") {
  const auto garment = two_material_grid(5, 0.1);
  for (const std::string projection : {"gauss_newton", "eigen"}) {
    const auto e = bound_energy("bending", "{projection: " + projection + "}", *garment);
    for (double amount : {0.005, 0.04}) {
      const Eigen::MatrixX3d x = perturbed(garment->mesh.vertices, amount, 12);
      const GradCheckReport r = check_energy_derivatives(*e, x);
      INFO(projection << ", perturbation " << amount << "\n" << r.str());
      CHECK(r.entries.size() == 4);
      CHECK(r.ok(1e-5));
    }
  }
}

TEST_CASE("bending derivatives with a curved initial rest state and a 100x stiffer material", "[bending][gradcheck]") {
  const auto garment = two_material_grid(5, 0.1);
  garment->mesh.vertices = perturbed(garment->mesh.vertices, 0.03, 1);
  garment->materials[1].bending *= 100.0;
  const auto e = bound_energy("bending", "{rest: initial}", *garment);
  CHECK(e->value(garment->mesh.vertices) == Approx(0.0).margin(1e-30));
  const Eigen::MatrixX3d x = perturbed(garment->mesh.vertices, 0.02, 2);
  CHECK(std::isfinite(e->value(x)));
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.ok(1e-5));
}

TEST_CASE("bending's projections: exact at rest, Gauss-Newton rank one, eigen the nearest PSD block", "[bending]") {
  const Garment g = hinge_garment(0.5);
  const auto gn = bound_energy("bending", "{}", g);
  const auto eigen = bound_energy("bending", "{projection: eigen}", g);
  const auto at_rest = bound_energy("bending", "{rest: initial}", g);
  // At the rest angle the curvature term vanishes: exact = Gauss-Newton.
  const Eigen::MatrixX3d rest = perturbed(hinge_positions(0.5), 0.0, 0);
  const Eigen::MatrixXd exact_rest = dense_hessian(*at_rest, rest, false);
  CHECK((exact_rest - dense_hessian(*at_rest, rest, true)).cwiseAbs().maxCoeff() < 1e-12 * exact_rest.cwiseAbs().maxCoeff());

  const Eigen::MatrixX3d x = perturbed(hinge_positions(1.0), 0.05, 6);
  const Eigen::MatrixXd exact = dense_hessian(*eigen, x, false);
  CHECK((exact - exact.transpose()).cwiseAbs().maxCoeff() <= 1e-14 * exact.cwiseAbs().maxCoeff());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(exact);
  INFO("exact eigenvalues " << eig.eigenvalues().transpose());
  CHECK(eig.eigenvalues().minCoeff() < -1e-3 * eig.eigenvalues().maxCoeff());  // bent away from flat: indefinite
  const Eigen::MatrixXd nearest = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
  CHECK((dense_hessian(*eigen, x, true) - nearest).cwiseAbs().maxCoeff() < 1e-10 * nearest.cwiseAbs().maxCoeff());

  const Eigen::MatrixXd gauss_newton = dense_hessian(*gn, x, true);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gn_eig(gauss_newton);
  const double top = gn_eig.eigenvalues().maxCoeff();
  CHECK(top > 0.0);
  CHECK(gn_eig.eigenvalues().head(11).cwiseAbs().maxCoeff() < 1e-12 * top);  // rank one
  // Its nonzero eigenvector is dtheta: parallel to the gradient.
  const Eigen::MatrixX3d grad = gradient_of(*gn, x);
  Eigen::VectorXd gvec(12);
  for (int k = 0; k < 12; ++k) gvec[k] = grad(k / 3, k % 3);
  CHECK(std::abs(gn_eig.eigenvectors().col(11).dot(gvec.normalized())) == Approx(1.0).epsilon(1e-10));
}

TEST_CASE("bending of a hinge folded nearly shut stays finite and continuous", "[bending][gradcheck]") {
  const Garment g = hinge_garment();
  const auto e = bound_energy("bending", "{projection: eigen}", g);
  for (double phi : {kPi - 1e-7, kPi + 1e-7, -kPi + 1e-9}) {
    const Eigen::MatrixX3d x = hinge_positions(phi);
    INFO("phi " << phi);
    CHECK(e->value(x) == Approx(kKnitBending * kPi * kPi / 8).epsilon(1e-6));
    CHECK(gradient_of(*e, x).allFinite());
    CHECK(dense_hessian(*e, x, false).allFinite());
    CHECK(dense_hessian(*e, x, true).allFinite());
  }
  // Close to the fold the derivatives are still exact.
  const GradCheckReport r = check_energy_derivatives(*e, hinge_positions(kPi - 0.05));
  INFO(r.str());
  CHECK(r.ok(1e-5));
}

TEST_CASE("bending of a hinge with a collapsed 3D face is finite", "[bending]") {
  const Garment g = hinge_garment();
  const auto e = bound_energy("bending", "{projection: eigen}", g);
  Eigen::MatrixX3d tip_on_edge = hinge_positions(0.3), collapsed_edge = hinge_positions(0.3), point = Eigen::MatrixX3d::Zero(4, 3);
  tip_on_edge.row(2) << 0.5, 0.0, 0.0;
  collapsed_edge.row(1) = collapsed_edge.row(0);
  for (const Eigen::MatrixX3d& x : {tip_on_edge, collapsed_edge, point}) {
    CHECK(std::isfinite(e->value(x)));
    CHECK(gradient_of(*e, x).allFinite());
    CHECK(dense_hessian(*e, x, false).allFinite());
    CHECK(dense_hessian(*e, x, true).allFinite());
  }
  // A face nearly but not quite collapsed (height 1e-6) keeps exact derivatives,
  // small ones now that the wing's bending is faded out (bending_fade_test.cpp).
  Eigen::MatrixX3d thin = hinge_positions(0.3);
  thin.row(2) << 0.5, 1e-6, 1e-7;
  const GradCheckReport r = check_energy_derivatives(*e, thin, {1e-10, 64, 7});
  INFO(r.str());
  CHECK(r.ok(1e-6));
}

TEST_CASE("bending finds hinges across UV seams, skips boundaries and rejects non-manifold edges", "[bending]") {
  // The grid's UVs cut along the middle column: hinges there still bend.
  auto garment = grid_garment(3, 0.1);
  const auto e_joined = bound_energy("bending", "{}", *garment);
  Mesh& m = garment->mesh;
  Eigen::MatrixX2d uv(12, 2);
  uv.topRows(9) = m.uv;
  uv.bottomRows(3) = m.uv(Eigen::seq(1, 7, 3), Eigen::all);  // copies of the middle column, u = 0.1
  m.uv = uv;
  for (int f = 0; f < m.num_faces(); ++f) {  // faces right of the seam (columns 1 and 2) use the copies
    if (std::min({m.faces(f, 0) % 3, m.faces(f, 1) % 3, m.faces(f, 2) % 3}) < 1) continue;
    for (int k = 0; k < 3; ++k)
      if (m.faces(f, k) % 3 == 1) m.uv_faces(f, k) = 9 + m.faces(f, k) / 3;
  }
  for (int r : {2, 5, 8, 9, 10, 11}) m.uv(r, 0) += 1.0;  // and move the right chart away
  const auto e_seam = bound_energy("bending", "{}", *garment);
  Eigen::MatrixX3d x = m.vertices;
  x(4, 2) = 0.02;  // lift the centre vertex, on the seam
  CHECK(e_seam->value(x) > 0.0);
  CHECK(e_seam->value(x) == Approx(e_joined->value(x)).epsilon(1e-12));  // same UV lengths: same energy

  Eigen::MatrixX3i f(3, 3);
  f << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  Eigen::MatrixX2d uv5(5, 2);
  uv5 << 0, 0, 1, 0, 0.5, 1, 0.5, -1, 0.5, 2;
  const Garment fan = small_garment(Eigen::MatrixX3d::Zero(5, 3), f, uv5);
  CHECK_THROWS_WITH(bound_energy("bending", "{}", fan), Catch::Contains("shared by 3 faces"));
}

TEST_CASE("bending skips hinges of zero material-space area and reports bad garments", "[bending]") {
  Garment flat_uv = hinge_garment();
  flat_uv.mesh.uv.col(1).setZero();  // both UV triangles collinear
  {
    CerrCapture cerr;
    const auto e = bound_energy("bending", "{}", flat_uv);
    CHECK_THAT(cerr.str(), Catch::Contains("skipped 1 of 1 hinges"));
    CHECK(e->value(hinge_positions(0.5)) == 0.0);
  }
  Garment no_uv = hinge_garment();
  no_uv.mesh.uv.resize(0, 2);
  no_uv.mesh.uv_faces.resize(0, 3);
  CHECK_THROWS_WITH(bound_energy("bending", "{}", no_uv), Catch::Contains("UV"));
  Garment bad_material = hinge_garment();
  bad_material.face_material.resize(2);
  bad_material.face_material << 0, 3;
  CHECK_THROWS_WITH(bound_energy("bending", "{}", bad_material), Catch::Contains("names material 3"));
  bad_material.face_material.resize(1);
  CHECK_THROWS_WITH(bound_energy("bending", "{}", bad_material), Catch::Contains("1 face materials for 2 faces"));
  Garment repeated = hinge_garment();
  repeated.mesh.faces(1, 2) = 1;
  CHECK_THROWS_WITH(bound_energy("bending", "{}", repeated), Catch::Contains("repeats vertex 1"));
}

TEST_CASE("bending works as a graph loss node on float positions", "[bending][gradcheck]") {
  const auto garment = two_material_grid(4, 0.1);
  const Assets assets = assets_with(garment);
  auto node = make_node("bending");
  Tensor x(2, 16, 3);
  for (int b = 0; b < 2; ++b) x.mat(b) = perturbed(garment->mesh.vertices, 0.02, 30 + b).cast<float>();
  const auto out = run_forward(*node, {{"x", x}}, {"g", 0, &assets});
  const auto e = bound_energy("bending", "{}", *garment);
  for (int b = 0; b < 2; ++b)
    CHECK(out.at("energy")(b, 0, 0) == Approx(e->value(x.mat(b).cast<double>())).epsilon(1e-5));
  const GradCheckReport r = check_node_gradients(*node, {{"x", x}}, {"g", 0, &assets});
  INFO(r.str());
  CHECK(r.ok(1e-2));
}

namespace {

// A tube of radius R cut from an equilateral triangle lattice of side s: rows
// of the lattice along the tube's axis (axis_along_rows) or around it, wrapped
// around exactly (the lattice's period around the tube is its circumference),
// `length` rows or columns along the axis. Each face carries its own UV corners
// (the flat lattice before wrapping), so the UV charts are cut along one seam,
// as a garment's are, and the mesh is welded around.
Garment lattice_tube(int around, int along, double s, bool axis_along_rows) {
  const double h = s * std::sqrt(3.0) / 2.0;
  // Lattice point (i, j): row j, column i; x = i s + (j odd) s / 2, y = j h.
  // Rows along the axis: the tube wraps rows (j mod around), the axis is x.
  // Rows around it: the tube wraps columns (i mod around), the axis is y.
  const int ni = axis_along_rows ? along : around, nj = axis_along_rows ? around : along;
  const double circumference = axis_along_rows ? around * h : around * s;
  const double radius = circumference / (2.0 * std::numbers::pi);
  auto vertex = [&](int i, int j) {
    return axis_along_rows ? (j % nj) * ni + i : j * ni + (i % ni);
  };
  Eigen::MatrixX3d x(ni * nj, 3);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const double px = i * s + (j % 2 ? 0.5 * s : 0.0), py = j * h;
      const double around_coord = axis_along_rows ? py : px, axis_coord = axis_along_rows ? px : py;
      const double phi = around_coord / radius;
      x.row(vertex(i, j)) << axis_coord, radius * std::cos(phi), radius * std::sin(phi);
    }
  std::vector<Eigen::Vector3i> faces;
  std::vector<Eigen::Vector2d> uv;
  auto add = [&](int i0, int j0, int i1, int j1, int i2, int j2) {
    faces.emplace_back(vertex(i0, j0), vertex(i1, j1), vertex(i2, j2));
    for (auto [i, j] : {std::pair{i0, j0}, std::pair{i1, j1}, std::pair{i2, j2}})
      uv.emplace_back(i * s + (j % 2 ? 0.5 * s : 0.0), j * h);
  };
  const int last_i = axis_along_rows ? ni - 1 : ni, last_j = axis_along_rows ? nj : nj - 1;
  for (int j = 0; j < last_j; ++j)
    for (int i = 0; i < last_i; ++i) {
      if (j % 2 == 0) {
        add(i, j, i + 1, j, i, j + 1);
        add(i + 1, j, i + 1, j + 1, i, j + 1);
      } else {
        add(i, j, i + 1, j + 1, i, j + 1);
        add(i, j, i + 1, j, i + 1, j + 1);
      }
    }
  Eigen::MatrixX3i f(static_cast<int>(faces.size()), 3), uf(static_cast<int>(faces.size()), 3);
  Eigen::MatrixX2d u(static_cast<int>(uv.size()), 2);
  for (int k = 0; k < f.rows(); ++k) {
    f.row(k) = faces[static_cast<std::size_t>(k)].transpose();
    uf.row(k) << 3 * k, 3 * k + 1, 3 * k + 2;
  }
  for (int k = 0; k < u.rows(); ++k) u.row(k) = uv[static_cast<std::size_t>(k)].transpose();
  return small_garment(x, f, u, uf);
}

}  // namespace

TEST_CASE("bending of a sheet bent to a cylinder converges under refinement to k kappa^2 / 8 per area",
          "[bending]") {
  // ArcSim's hinge energy k theta^2 l^2 / (8 (A0 + A1)) on a lattice bent to
  // curvature kappa: per unit area it tends to k kappa^2 / 8, a quarter of the
  // continuum plate energy k kappa^2 / 2 (the rigidity ArcSim's formula
  // stands for is k / 4), the same for the lattice turned either way to the
  // bending, and the same at half the mesh size (docs/materials.md, "Folds
  // at the scale of knit"). With the lattice's rows along the axis the tube is
  // a prism, bent at the rows' edges alone (exact); with the rows around it
  // every edge bends, the rows and the diagonals with opposite signs (1/3 and
  // -2/3 of kappa h), and the sum is the same to 0.2 %.
  // The ends of a tube lack hinges, so the energy per area is taken from two
  // lengths of tube: (E(long) - E(short)) / the area added.
  const double radius = 0.10;
  for (bool along_rows : {true, false}) {
    std::vector<double> density;
    for (int around : {24, 48}) {
      const double circumference = 2.0 * std::numbers::pi * radius;
      const double s = along_rows ? circumference / (around * std::sqrt(3.0) / 2.0) : circumference / around;
      const double h = s * std::sqrt(3.0) / 2.0;
      const int short_len = around / 2, long_len = 2 * short_len;
      const Garment a = lattice_tube(around, short_len, s, along_rows), b = lattice_tube(around, long_len, s, along_rows);
      const double ea = bound_energy("bending", "{}", a)->value(a.mesh.vertices);
      const double eb = bound_energy("bending", "{}", b)->value(b.mesh.vertices);
      const double added_area = circumference * (long_len - short_len) * (along_rows ? s : h);
      density.push_back((eb - ea) / added_area);
      INFO((along_rows ? "rows along the axis" : "rows around the axis") << ", " << around << " around (s = " << s << " m)");
      CHECK(density.back() / (kKnitBending / (radius * radius) / 8.0) == Approx(1.0).epsilon(0.02));
    }
    // Refinement changes it by the chords' second-order error only.
    CHECK(density[1] == Approx(density[0]).epsilon(0.01));
  }
}
