// The barrier contact (plugins/energies/barrier): its energy on one pair of
// each kind against IPC's barrier computed by hand, its derivatives on a
// sheet over a box corner (every pair kind and distance type at once), its
// continuous collision bound, and a sheet falling onto the corner that is
// never inside or through the body at any step (checked by the independent
// crossing count and signed distances, which share no code with the contact).
#include <drape/energy.hpp>
#include <drape/geometry/ccd.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/gradcheck.hpp>
#include <drape/physics/solver.hpp>

#include <catch2/catch.hpp>

#include <cmath>

#include "barrier_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

constexpr double kDhat = 1e-3, kKappa = 1e3;

// IPC's barrier by its definition, -(r - 1)^2 ln r on r = d^2 / d_hat^2.
double ipc_barrier(double d) {
  const double r = d * d / (kDhat * kDhat);
  return r >= 1 ? 0.0 : -(r - 1) * (r - 1) * std::log(r);
}

double triangle_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

// A garment of one triangle whose material space is its own 3D shape.
Garment one_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  Eigen::MatrixX3d v(3, 3);
  v << a.transpose(), b.transpose(), c.transpose();
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 2;
  // UVs: the triangle laid flat with the same edge lengths.
  const double ab = (b - a).norm(), t = (c - a).dot(b - a) / ab, h = (c - a - t * (b - a) / ab).norm();
  Eigen::MatrixX2d uv(3, 2);
  uv << 0, 0, ab, 0, t, h;
  return small_garment(v, f, uv);
}

// A sheet of n x n vertices (spacing s) at height z over the box's top corner
// at (0, 0): a quarter over the top face, the rest over the sides' edges.
std::shared_ptr<Garment> sheet_over_corner(int n, double s, double z) {
  auto g = grid_garment(n, s);
  Eigen::MatrixX3d& v = g->mesh.vertices;
  const double half = 0.5 * (n - 1) * s;
  for (Eigen::Index i = 0; i < v.rows(); ++i) v.row(i) << v(i, 0) - half + 0.0013, v(i, 1) - 1.0 - half + 0.0007, z;
  return g;
}

}  // namespace

TEST_CASE("barrier: bad parameters, a missing body and a wrong vertex count are refused", "[barrier]") {
  CHECK_THROWS_WITH(params_for("barrier", "{distance: 0}"), Catch::Contains("'distance'"));
  CHECK_THROWS_WITH(params_for("barrier", "{stiffness: -1}"), Catch::Contains("'stiffness'"));
  CHECK_THROWS_WITH(params_for("barrier", "{min_separation: 1}"), Catch::Contains("'min_separation'"));
  CHECK_THROWS_WITH(params_for("barrier", "{friction: -0.1}"), Catch::Contains("'friction'"));
  CHECK_THROWS_WITH(params_for("barrier", "{slip_velocity: 0}"), Catch::Contains("'slip_velocity'"));
  CHECK_THROWS_AS(params_for("barrier", "{distanse: 0.001}"), ConfigError);
  const geometry::BodySurface body(box(-1, 1, 0, 2, -2, 0));
  const Garment g = one_triangle({-0.5, 0.5, 1e-3}, {-0.49, 0.5, 1e-3}, {-0.5, 0.51, 1e-3});
  auto e = plugins().create_energy("barrier", params_for("barrier", "{}"));
  EnergyContext no_body;
  no_body.garment = &g;
  CHECK_THROWS_WITH(e->bind(no_body), Catch::Contains("barrier: needs the body"));
  const auto bound = barrier_on(g, body);
  CHECK_THROWS_WITH(bound->value(Eigen::MatrixX3d::Zero(4, 3)), Catch::Contains("4 vertices given, the bound garment has 3"));
}

TEST_CASE("barrier: a garment triangle over a face costs kappa d_hat a_v b(d) per vertex", "[barrier]") {
  // Top face z = 0 of a 2 m box; the triangle 0.5 mm above it, far from the
  // face's diagonal and edges, so only its three vertex-face pairs are active.
  const geometry::BodySurface body(box(-1, 1, 0, 2, -2, 0));
  const double h = 0.5e-3;
  const Garment g = one_triangle({-0.5, 0.5, h}, {-0.49, 0.5, h}, {-0.5, 0.51, h});
  const auto e = barrier_on(g, body);
  const double vertex_area = 0.5 * 0.01 * 0.01 / 3;
  // r = 0.25: b = -(0.75)^2 ln 0.25 = 0.779791...
  CHECK(ipc_barrier(h) == Approx(0.5625 * std::log(4.0)).epsilon(1e-12));
  CHECK(e->value(g.mesh.vertices) == Approx(3 * kKappa * kDhat * vertex_area * 0.779791).epsilon(1e-5));
  // Beyond d_hat: nothing.
  Eigen::MatrixX3d far = g.mesh.vertices;
  far.col(2).setConstant(1.2e-3);
  CHECK(e->value(far) == 0.0);
  // The reach it reports is the scene's d_hat: a hair inside it costs, a hair beyond does not.
  const auto wide = barrier_on(g, body, "{distance: 0.003}");
  CHECK(e->activation_distance() == kDhat);
  CHECK(wide->activation_distance() == 0.003);
  for (const auto* b : {e.get(), wide.get()}) {
    Eigen::MatrixX3d at = g.mesh.vertices;
    at.col(2).setConstant(0.99 * b->activation_distance());
    CHECK(b->value(at) > 0);
    at.col(2).setConstant(1.01 * b->activation_distance());
    CHECK(b->value(at) == 0.0);
  }
}

TEST_CASE("barrier: a body vertex under a garment triangle costs kappa d_hat A_v b(d)", "[barrier]") {
  // A steep tetrahedron with its apex at the origin, a wide horizontal garment
  // triangle 0.3 mm above it: only the apex-triangle pair is within d_hat.
  Mesh tet;
  tet.vertices.resize(4, 3);
  tet.vertices << 0, 0, 0, 0.05, 0, -0.1, -0.025, 0.0433, -0.1, -0.025, -0.0433, -0.1;
  tet.faces.resize(4, 3);
  tet.faces << 0, 2, 1, 0, 3, 2, 0, 1, 3, 1, 2, 3;
  const geometry::BodySurface body(tet);
  const double h = 0.3e-3;
  const Garment g = one_triangle({-0.03, -0.02, h}, {0.03, -0.02, h}, {0.0, 0.04, h});
  const auto e = barrier_on(g, body);
  const Eigen::MatrixX3d& b = tet.vertices;
  auto corner = [&](int i) -> Eigen::Vector3d { return b.row(i).transpose(); };
  const double apex_area = (triangle_area(corner(0), corner(2), corner(1)) + triangle_area(corner(0), corner(3), corner(2)) +
                            triangle_area(corner(0), corner(1), corner(3))) / 3;
  CHECK(e->value(g.mesh.vertices) == Approx(kKappa * kDhat * apex_area * ipc_barrier(h)).epsilon(1e-9));
}

TEST_CASE("barrier: a garment edge across a body edge costs kappa d_hat A_e b(d)", "[barrier]") {
  // A long ridge along x (a prism with 60-degree flanks) and a garment triangle
  // standing over it in the y-z plane; its bottom edge crosses the ridge 0.4 mm
  // above it, every other primitive is centimetres away.
  Mesh prism;
  prism.vertices.resize(6, 3);
  const double y = 0.1 * std::tan(M_PI / 6);  // flank half-width at depth 0.1
  prism.vertices << -0.1, 0, 0, 0.1, 0, 0, -0.1, -y, -0.1, 0.1, -y, -0.1, -0.1, y, -0.1, 0.1, y, -0.1;
  prism.faces.resize(8, 3);
  prism.faces << 0, 1, 3, 0, 3, 2, 0, 4, 5, 0, 5, 1, 2, 3, 5, 2, 5, 4, 0, 2, 4, 1, 5, 3;
  const geometry::BodySurface body(prism);
  const double h = 0.4e-3;
  const Garment g = one_triangle({0, -0.03, h}, {0, 0.03, h}, {0, 0, h + 0.05});
  const auto e = barrier_on(g, body);
  const double edge_area = triangle_area({0, -0.03, 0}, {0, 0.03, 0}, {0, 0, 0.05}) / 3;
  // |AB x ridge|^2 = (0.06 * 0.2)^2 is far above 1e-3 |AB|^2 |ridge|^2: no mollification.
  CHECK(e->value(g.mesh.vertices) == Approx(kKappa * kDhat * edge_area * ipc_barrier(h)).epsilon(1e-9));
  // Turned parallel to the ridge, the bottom edge's pair with the ridge fades
  // out (IPC's mollifier: |AB x ridge| = 0). Each end is then held by its
  // pairs with the two flanks (closest point on the ridge, A/3 each) and by its
  // slanted edge's pair with the ridge (closest at that end, A/3): A per end.
  const Garment parallel = one_triangle({-0.03, 0, h}, {0.03, 0, h}, {0, 0, h + 0.05});
  const auto p = barrier_on(parallel, body);
  const double ends = 2 * kKappa * kDhat * triangle_area({-0.03, 0, 0}, {0.03, 0, 0}, {0, 0, 0.05}) * ipc_barrier(h);
  CHECK(p->value(parallel.mesh.vertices) == Approx(ends).epsilon(1e-9));
}

TEST_CASE("barrier: derivatives match finite differences over a box corner (every pair kind)", "[barrier][gradcheck]") {
  const geometry::BodySurface body(box(-0.5, 0, -0.5, 0, -0.5, 0));
  auto g = sheet_over_corner(7, 0.004, 0.5e-3);
  const Eigen::MatrixX3d x = perturbed(g->mesh.vertices, 2e-4, 11);
  // The configuration has pairs of all three kinds within d_hat (counted here
  // with the framework's distances, not the plugin's).
  int vertex_face = 0, face_vertex = 0, edge_edge = 0;
  const Eigen::MatrixX3d& b = body.vertices();
  const Eigen::MatrixX3i& bf = body.faces();
  const Eigen::MatrixX3i& gf = g->mesh.faces;
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    for (Eigen::Index f = 0; f < bf.rows(); ++f)
      vertex_face += geometry::point_triangle_distance2(x.row(v), b.row(bf(f, 0)), b.row(bf(f, 1)), b.row(bf(f, 2))) < kDhat * kDhat;
  for (Eigen::Index v = 0; v < b.rows(); ++v)
    for (Eigen::Index f = 0; f < gf.rows(); ++f)
      face_vertex += geometry::point_triangle_distance2(b.row(v), x.row(gf(f, 0)), x.row(gf(f, 1)), x.row(gf(f, 2))) < kDhat * kDhat;
  for (Eigen::Index f = 0; f < gf.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      for (Eigen::Index c = 0; c < bf.rows(); ++c)
        for (int l = 0; l < 3; ++l)
          edge_edge += geometry::edge_edge_distance2(x.row(gf(f, k)), x.row(gf(f, (k + 1) % 3)), b.row(bf(c, l)),
                                                     b.row(bf(c, (l + 1) % 3))) < kDhat * kDhat;
  CHECK(vertex_face > 0);
  CHECK(face_vertex > 0);
  CHECK(edge_edge > 0);
  const auto e = barrier_on(*g, body);
  REQUIRE(std::isfinite(e->value(x)));
  REQUIRE(e->value(x) > 0);
  // Distances here are ~0.5 mm: a 1e-8 m step keeps the truncation error small.
  const GradCheckReport r = check_energy_derivatives(*e, x, {1e-8, 200, 3});
  INFO(r.str());
  CHECK(r.ok(1e-4));
}

// The pairs are found through candidates kept while the cloth moves less
// than a skin (a Verlet list): evaluations after small and large moves must
// give, bit for bit, what a contact that has seen nothing before gives.
TEST_CASE("barrier: kept candidates give a fresh search's energy, gradient and Hessian after every move", "[barrier]") {
  const geometry::BodySurface body(box(-0.5, 0, -0.5, 0, -0.5, 0));
  auto g = sheet_over_corner(7, 0.004, 0.5e-3);
  const auto kept = barrier_on(*g, body);
  Eigen::MatrixX3d x = perturbed(g->mesh.vertices, 2e-4, 11);
  // Moves of 0.1, 0.6 and 2.5 mm (within the skin of d_hat = 1 mm, and past
  // it), up and back down, each vertex its own way.
  const double moves[] = {1e-4, 6e-4, 2.5e-3, -2.5e-3, -6e-4, 3e-4};
  int seed = 20;
  for (const double m : moves) {
    Eigen::MatrixX3d step = perturbed(Eigen::MatrixX3d::Zero(x.rows(), 3), std::abs(m), seed++);
    step.col(2).array() += m;
    x += step;
    const auto fresh = barrier_on(*g, body);
    INFO("after a move of " << m << " m");
    const double value = fresh->value(x);
    CHECK(kept->value(x) == value);
    Eigen::MatrixX3d a = Eigen::MatrixX3d::Zero(x.rows(), 3), b = a;
    CHECK(kept->add_gradient(x, a) == fresh->add_gradient(x, b));
    CHECK(a == b);
    Triplets ha, hb;
    kept->add_hessian(x, ha);
    fresh->add_hessian(x, hb);
    REQUIRE(ha.size() == hb.size());
    bool same = true;
    for (std::size_t i = 0; i < ha.size(); ++i)
      same = same && ha[i].row() == hb[i].row() && ha[i].col() == hb[i].col() && ha[i].value() == hb[i].value();
    CHECK(same);
  }
  // Some of those states have pairs within d_hat, some none (the sheet lifted 2.5 mm).
  CHECK(barrier_on(*g, body)->value(x) > 0);
}

// max_step takes its pairs from the kept candidates when the move stays
// within their reach (the drift since they were found plus the step, at most
// d_hat + skin = 2 mm on every coordinate): the bound must be, bit for bit,
// the one a contact that has seen nothing before finds through its grids,
// for steps that stop at the corner and steps that do not, and past the reach.
TEST_CASE("barrier: kept candidates bound a step as a fresh search does", "[barrier]") {
  const geometry::BodySurface body(box(-0.5, 0, -0.5, 0, -0.5, 0));
  auto g = sheet_over_corner(7, 0.004, 0.5e-3);
  const auto kept = barrier_on(*g, body);
  const Eigen::MatrixX3d x0 = perturbed(g->mesh.vertices, 2e-4, 11);
  REQUIRE(kept->value(x0) > 0);  // the candidates are found here
  int seed = 40, stopped = 0;
  for (const double drift : {0.0, 3e-4, 8e-4}) {
    Eigen::MatrixX3d x = x0 + perturbed(Eigen::MatrixX3d::Zero(x0.rows(), 3), 0.5 * drift, seed++);
    x.col(2).array() += drift;  // up, so that x stays clear of the body
    for (const double step : {2e-4, 9e-4, 1.5e-3, 3e-3}) {
      for (const double sign : {-1.0, 1.0}) {
        Eigen::MatrixX3d dx = perturbed(Eigen::MatrixX3d::Zero(x0.rows(), 3), 0.3 * step, seed++);
        dx.col(2).array() += sign * step;
        INFO("drift " << drift << " m, step " << sign * step << " m");
        const double alpha = kept->max_step(x, dx);
        CHECK(alpha == barrier_on(*g, body)->max_step(x, dx));
        stopped += alpha < 1.0;
      }
    }
  }
  CHECK(stopped >= 4);  // downward steps that reach the corner were bounded
}

TEST_CASE("barrier: the step bound stops a move before the surfaces touch", "[barrier]") {
  const geometry::BodySurface body(box(-1, 1, 0, 2, -2, 0));
  const double h = 0.5e-3;
  const Garment g = one_triangle({-0.5, 0.5, h}, {-0.49, 0.5, h}, {-0.5, 0.51, h});
  const auto e = barrier_on(g, body);
  const Eigen::MatrixX3d& x = g.mesh.vertices;
  Eigen::MatrixX3d down = Eigen::MatrixX3d::Zero(3, 3);
  down.col(2).setConstant(-0.01);  // would go 9.5 mm through the face
  const double alpha = e->max_step(x, down);
  CHECK(alpha > 0);
  CHECK(alpha < h / 0.01);  // before the face, which is reached at h / 1 cm
  CHECK(std::isfinite(e->value(x + alpha * down)));
  CHECK(e->max_step(x, -down) == 1.0);  // moving away: no bound
  // The body rising 1 cm into the resting triangle is bounded the same way.
  Eigen::MatrixX3d from = body.vertices(), to = from;
  to.col(2).array() += 0.01;
  const double body_alpha = e->max_step(x, Eigen::MatrixX3d::Zero(3, 3), &from, &to);
  CHECK(body_alpha > 0);
  CHECK(body_alpha < h / 0.01);
  // Sliding sideways at constant height: nothing comes closer.
  Eigen::MatrixX3d slide = Eigen::MatrixX3d::Zero(3, 3);
  slide.col(0).setConstant(0.2);
  CHECK(e->max_step(x, slide) == 1.0);
}

TEST_CASE("barrier: a sheet falling on a table is never inside or through it, and comes to rest on it", "[barrier][solver]") {
  // 15 x 15 vertices 1 cm apart, dropped from 5 mm onto a 40 cm table top
  // (a frictionless sheet draped over an edge would slide off: the table holds it).
  const Mesh table = box(-0.2, 0.2, -0.2, 0.2, -0.1, 0);
  geometry::BodySurface body(table);
  auto g = sheet_over_corner(15, 0.01, 0.005);
  std::vector<NamedEnergy> energies;
  EnergyContext ctx;
  ctx.garment = g.get();
  ctx.body = &body;
  ctx.gravity = Eigen::Vector3d(0, 0, -9.81);
  for (const char* name : {"gravity", "stretching", "bending", "barrier"}) {
    auto e = plugins().create_energy(name, params_for(name, "{}"));
    e->bind(ctx);
    energies.push_back({name, std::move(e)});
  }
  SolverSettings settings;
  settings.max_newton_iterations = 20;
  ClothSolver solver(*g, energies, settings);
  Eigen::MatrixX3d x = g->mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
  int steps = 0;
  for (; steps < 60; ++steps) {
    const StepReport r = solver.step(x, v);
    REQUIRE(x.allFinite());
    // Independent checks: no vertex inside, no edge through a face.
    const Eigen::VectorXd d = body.signed_distances(x);
    INFO("step " << steps);
    REQUIRE(d.minCoeff() > 0);
    REQUIRE(geometry::surface_crossings(x, g->mesh.faces, table.vertices, table.faces).total() == 0);
    if (solver.static_residual(x) <= settings.settle_tolerance && r.max_displacement < 1e-5) break;
  }
  // At rest on the table: within d_hat of it, its weight (1.8 Pa) held by the barrier.
  CHECK(steps < 60);
  CHECK(solver.static_residual(x) <= settings.settle_tolerance);
  const Eigen::VectorXd d = body.signed_distances(x);
  CHECK(d.maxCoeff() < kDhat);
  CHECK(d.minCoeff() > 0.5 * kDhat);
}
