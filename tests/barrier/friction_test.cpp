// The barrier contact's friction (plugins/energies/barrier/friction.cpp): its
// dissipative potential on one triangle against IPC's lagged friction
// computed by hand, its gradient and Hessian against finite differences (every
// pair kind, static and kinetic slip), and Coulomb's law on a tilted table: a
// sheet is held when mu > tan(theta) and slides when mu < tan(theta).
#include <drape/physics/dissipation.hpp>
#include <drape/energy.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/physics/solver.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include <cmath>
#include <numbers>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "barrier_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

constexpr double kFrictionDhat = 1e-3, kFrictionKappa = 1e3, kStep = 0.1, kSlipVelocity = 1e-3;
constexpr double kEpsilon = kSlipVelocity * kStep;  // IPC's eps_v h: static below this slip

// IPC's smoothed friction magnitude f0 (Li et al. 2020, eq. 16), by its definition.
double ipc_f0(double y) {
  return y >= kEpsilon ? y : -y * y * y / (3 * kEpsilon * kEpsilon) + y * y / kEpsilon + kEpsilon / 3;
}

// The push of IPC's barrier on a pair at distance d with weight w, |dE/dd| of
// E = kappa d_hat w b(d^2 / d_hat^2), b(r) = -(r - 1)^2 ln r.
double ipc_push(double d, double w) {
  const double r = d * d / (kFrictionDhat * kFrictionDhat);
  const double db = -2 * (r - 1) * std::log(r) - (r - 1) * (r - 1) / r;
  return std::abs(kFrictionKappa * kFrictionDhat * w * db * 2 * d / (kFrictionDhat * kFrictionDhat));
}

Eigen::MatrixXd dense_dissipation_hessian(const Dissipation& d, const Eigen::MatrixX3d& x) {
  Triplets t;
  d.add_hessian_lower(x, t);
  Eigen::SparseMatrix<double> lower(3 * x.rows(), 3 * x.rows());
  lower.setFromTriplets(t.begin(), t.end());
  Eigen::MatrixXd h = Eigen::MatrixXd(lower);
  Eigen::MatrixXd full = h + h.transpose();
  full.diagonal() = h.diagonal();
  return full;
}

Eigen::MatrixX3d dissipation_gradient(const Dissipation& d, const Eigen::MatrixX3d& x) {
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
  d.add_gradient(x, g);
  return g;
}

// The barrier's friction, its own potential (physics/dissipation.hpp).
Dissipation& friction_of(Energy& barrier) {
  Dissipation* d = barrier.dissipation();
  REQUIRE(d != nullptr);
  return *d;
}

}  // namespace

TEST_CASE("friction: a triangle resting over a face dissipates mu lambda f0(|slip|) per vertex", "[barrier][friction]") {
  const geometry::BodySurface body(box(-1, 1, 0, 2, -2, 0));
  const double h = 0.4e-3, mu = 0.3;
  auto g = std::make_shared<Garment>();
  Eigen::MatrixX3d v(3, 3);
  v << -0.5, 0.5, h, -0.49, 0.5, h, -0.5, 0.51, h;
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 2;
  Eigen::MatrixX2d uv(3, 2);
  uv << 0, 0, 0.01, 0, 0, 0.01;
  *g = small_garment(v, f, uv);
  const auto e = barrier_on(*g, body, "{friction: 0.3, slip_velocity: 0.001}");
  Dissipation& d = friction_of(*e);
  // Before any step, and without friction, nothing dissipates.
  CHECK(d.value(v) == 0);
  d.begin_step(v, kStep);
  // Each vertex is one pair with the face under it, weighted by a third of
  // the triangle's material area; its normal force is the barrier's push.
  const double lambda = ipc_push(h, 0.5 * 0.01 * 0.01 / 3);
  for (const double slide : {0.0, 0.3 * kEpsilon, 0.9 * kEpsilon, 2 * kEpsilon, 0.01}) {
    Eigen::MatrixX3d x = v;
    x.col(0).array() += 0.6 * slide;
    x.col(1).array() += 0.8 * slide;
    x.col(2).array() += 0.1e-3;  // a move along the normal does not slip
    INFO("slide " << slide);
    CHECK(d.value(x) == Approx(3 * mu * lambda * ipc_f0(slide)).epsilon(1e-10));
  }
  // Still lagged: the contacts are those at the step's start, wherever x goes.
  Eigen::MatrixX3d away = v;
  away.col(2).array() += 0.05;
  CHECK(d.value(away) == Approx(3 * mu * lambda * ipc_f0(0)).epsilon(1e-10));
  // Frictionless: no dissipation at all.
  const auto frictionless = barrier_on(*g, body, "{}");
  CHECK(frictionless->dissipation() == nullptr);
}

TEST_CASE("friction: derivatives match finite differences over a box corner, static and sliding", "[barrier][friction][gradcheck]") {
  const geometry::BodySurface body(box(-0.5, 0, -0.5, 0, -0.5, 0));
  auto g = grid_garment(7, 0.004);
  Eigen::MatrixX3d& v = g->mesh.vertices;
  const double half = 0.5 * 6 * 0.004;
  for (Eigen::Index i = 0; i < v.rows(); ++i) v.row(i) << v(i, 0) - half + 0.0013, v(i, 1) - 1.0 - half + 0.0007, 0.5e-3;
  const Eigen::MatrixX3d start = perturbed(v, 2e-4, 11);
  const auto e = barrier_on(*g, body, "{friction: 0.4, slip_velocity: 0.001}");
  Dissipation& d = friction_of(*e);
  d.begin_step(start, kStep);
  for (const double scale : {0.2 * kEpsilon, 30 * kEpsilon}) {
    const Eigen::MatrixX3d x = perturbed(start, scale, 5);
    INFO("moves up to " << scale << " m (slip " << (scale < kEpsilon ? "static" : "kinetic") << ")");
    const Eigen::MatrixX3d grad = dissipation_gradient(d, x);
    REQUIRE(grad.norm() > 0);
    const Eigen::MatrixXd hess = dense_dissipation_hessian(d, x);
    const double step = 1e-9;
    double grad_error = 0, hess_error = 0;
    for (Eigen::Index k = 0; k < x.size(); ++k) {
      Eigen::MatrixX3d plus = x, minus = x;
      plus.data()[k] += step;
      minus.data()[k] -= step;
      // Flattened as 3 * vertex + axis, like the Hessian's rows.
      const Eigen::Index row = 3 * (k % x.rows()) + k / x.rows();
      grad_error = std::max(grad_error, std::abs((d.value(plus) - d.value(minus)) / (2 * step) - grad.data()[k]));
      const Eigen::MatrixX3d dg = (dissipation_gradient(d, plus) - dissipation_gradient(d, minus)) / (2 * step);
      for (Eigen::Index j = 0; j < x.rows(); ++j)
        for (int a = 0; a < 3; ++a) hess_error = std::max(hess_error, std::abs(dg(j, a) - hess(3 * j + a, row)));
    }
    CHECK(grad_error <= 1e-5 * grad.cwiseAbs().maxCoeff());
    CHECK(hess_error <= 1e-5 * hess.cwiseAbs().maxCoeff());
    // Positive semidefinite as assembled: Newton needs no projection.
    const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(hess).eigenvalues();
    CHECK(eig.minCoeff() >= -1e-10 * eig.maxCoeff());
  }
}

TEST_CASE("friction: the same dissipation, gradient and Hessian with 1 and 2 threads", "[barrier][friction]") {
#ifndef _OPENMP
  WARN("built without OpenMP: nothing to compare");
#else
  // 4,900 vertices 4 mm apart over a box top: past the candidate count from
  // which the barrier's pair search runs in parallel.
  const geometry::BodySurface body(box(-1, 1, -1, 1, -0.5, 0));
  auto g = grid_garment(70, 0.004);
  Eigen::MatrixX3d& v = g->mesh.vertices;
  for (Eigen::Index i = 0; i < v.rows(); ++i) v(i, 1) -= 1.0, v(i, 2) = 0.5e-3;
  const Eigen::MatrixX3d start = perturbed(v, 2e-4, 3), x = perturbed(start, 3e-4, 4);
  struct Result {
    double value;
    Eigen::MatrixX3d gradient;
    Triplets hessian;
  };
  auto evaluate = [&](int threads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    const auto e = barrier_on(*g, body, "{friction: 0.3}");
    Dissipation& d = friction_of(*e);
    d.begin_step(start, kStep);
    Result r{d.value(x), dissipation_gradient(d, x), {}};
    d.add_hessian_lower(x, r.hessian);
    omp_set_num_threads(before);
    return r;
  };
  const Result one = evaluate(1), two = evaluate(2);
  REQUIRE(one.value > 0);
  CHECK(one.value == two.value);
  CHECK(one.gradient == two.gradient);
  REQUIRE(one.hessian.size() == two.hessian.size());
  bool same = true;
  for (std::size_t i = 0; i < one.hessian.size(); ++i)
    same = same && one.hessian[i].row() == two.hessian[i].row() && one.hessian[i].col() == two.hessian[i].col() &&
           one.hessian[i].value() == two.hessian[i].value();
  CHECK(same);
#endif
}

namespace {

struct TiltedTable {
  Mesh table = box(-1, 1, -1, 1, -0.1, 0);  // wide enough to slide on for a second
  geometry::BodySurface body{table};
  std::shared_ptr<Garment> sheet;
  std::vector<NamedEnergy> energies;
  // A 15 x 15 sheet (1 cm apart) resting on the table, gravity tilted by
  // theta towards +x: the table tilted the other way.
  TiltedTable(double theta, const std::string& barrier) {
    sheet = grid_garment(15, 0.01);
    Eigen::MatrixX3d& v = sheet->mesh.vertices;
    const double half = 0.5 * 14 * 0.01;
    for (Eigen::Index i = 0; i < v.rows(); ++i) v.row(i) << v(i, 0) - half + 0.0013, v(i, 1) - 1.0 - half + 0.0007, 0.6e-3;
    EnergyContext ctx;
    ctx.garment = sheet.get();
    ctx.body = &body;
    ctx.gravity = 9.81 * Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta));
    for (const char* name : {"gravity", "stretching", "bending", "barrier"}) {
      auto e = plugins().create_energy(name, params_for(name, name == std::string("barrier") ? barrier : "{}"));
      e->bind(ctx);
      energies.push_back({name, std::move(e)});
    }
  }
};

// Steps the sheet; returns how far its centre moved along x (m).
double slide_of(TiltedTable& t, int steps, bool* held) {
  SolverSettings settings;
  settings.max_newton_iterations = 30;
  ClothSolver solver(*t.sheet, t.energies, settings);
  Eigen::MatrixX3d x = t.sheet->mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
  const double start = x.col(0).mean();
  for (int k = 0; k < steps; ++k) {
    solver.step(x, v);
    REQUIRE(x.allFinite());
    REQUIRE(t.body.signed_distances(x).minCoeff() > 0);
    REQUIRE(geometry::surface_crossings(x, t.sheet->mesh.faces, t.table.vertices, t.table.faces).total() == 0);
  }
  // Held: nothing slides, and the unbalanced force beyond what friction
  // holds is within the settling tolerance, while the plain residual (the
  // tilted weight's pull along the table) is not.
  *held = !solver.sliding(x) && solver.stationarity(x, 1e-3) <= settings.settle_tolerance &&
          solver.static_residual(x) > 10 * settings.settle_tolerance;
  return x.col(0).mean() - start;
}

}  // namespace

TEST_CASE("friction: a sheet on a table tilted by 15 degrees is held when mu > tan 15 and slides when below", "[barrier][friction][solver]") {
  const double theta = 15 * std::numbers::pi / 180;  // tan 15 degrees = 0.268
  bool held = false;
  TiltedTable sticky(theta, "{friction: 0.4, slip_velocity: 0.001}");
  const double held_slide = slide_of(sticky, 20, &held);
  INFO("mu 0.4: slid " << held_slide << " m");
  CHECK(held);
  // Held, it still creeps as the smoothing allows: at a steady slip s eps per
  // step friction pushes back mu lambda (2 s - s^2), which balances the pull
  // tan(theta) lambda at s = 1 - sqrt(1 - tan(theta) / mu).
  const double creep_per_step = 1 - std::sqrt(1 - std::tan(theta) / 0.4);
  CHECK(held_slide == Approx(20 * creep_per_step * 1e-3 * kStep).epsilon(0.25));
  // The default eps_v, 1 cm/s, holds it too, creeping ten times as fast.
  TiltedTable sticky_default(theta, "{friction: 0.4}");
  const double default_slide = slide_of(sticky_default, 20, &held);
  CHECK(held);
  CHECK(default_slide == Approx(20 * creep_per_step * 1e-2 * kStep).epsilon(0.25));

  TiltedTable slippery(theta, "{friction: 0.15, slip_velocity: 0.001}");
  const double slid = slide_of(slippery, 10, &held);
  INFO("mu 0.15: slid " << slid << " m");
  CHECK_FALSE(held);
  // Coulomb: accelerated by g (sin theta - mu cos theta) = 1.12 m/s^2 for 1 s
  // (less the solver's damping): decimetres, not millimetres.
  CHECK(slid > 0.05);

  TiltedTable frictionless(theta, "{}");
  const double free_slide = slide_of(frictionless, 10, &held);
  CHECK_FALSE(held);
  // The solver's damping scales both slides alike, so their ratio is that of
  // the accelerations, g (sin theta - mu cos theta) against g sin theta (0.44);
  // the first step's static regime takes a little off the rougher one.
  INFO("slid " << slid << " m with mu 0.15, " << free_slide << " m without friction");
  CHECK(slid / free_slide == Approx(1 - 0.15 / std::tan(theta)).epsilon(0.2));
}
