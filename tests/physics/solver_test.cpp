// The backward-Euler Newton solver on energies with known minimisers, and the
// fixed-pattern Hessian assembly against Eigen's own triplet assembly.
#include <drape/energy.hpp>
#include <drape/geometry/vertex_areas.hpp>
#include <drape/nn/blas_threads.hpp>
#include <drape/physics/solver.hpp>

#include "../../framework/src/physics/hessian_pattern.hpp"
#include "../../framework/src/physics/sparse_cholesky.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <random>
#include <thread>

#include "test_support.hpp"

using namespace drape;

namespace {

// A flat n x n grid of cloth with material-space UVs equal to its rest positions.
Garment grid(int n, double spacing) {
  Garment g;
  Mesh& m = g.mesh;
  m.vertices.resize(n * n, 3);
  m.uv.resize(n * n, 2);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.vertices.row(i * n + j) << j * spacing, 0.0, i * spacing;
      m.uv.row(i * n + j) << j * spacing, i * spacing;
    }
  m.faces.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      m.faces.row(f++) << a, b, d;
      m.faces.row(f++) << a, d, c;
    }
  m.uv_faces = m.faces;
  g.materials.push_back(Material{});
  return g;
}

// E = k/2 sum_v |x_v - a_v|^2 - sum_v f^T x_v: minimiser a + f / k.
class AnchorSprings final : public Energy {
 public:
  AnchorSprings(Eigen::MatrixX3d anchors, double k, Eigen::Vector3d force) : a_(std::move(anchors)), k_(k), f_(force) {}
  void bind(const EnergyContext&) override {}
  double value(const Eigen::MatrixX3d& x) const override {
    return 0.5 * k_ * (x - a_).squaredNorm() - (x * f_).sum();
  }
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    g += k_ * (x - a_);
    g.rowwise() -= f_.transpose();
    return value(x);
  }
  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool) const override {
    for (int i = 0; i < 3 * x.rows(); ++i) h.emplace_back(i, i, k_);
  }

 private:
  Eigen::MatrixX3d a_;
  double k_;
  Eigen::Vector3d f_;
};

// Non-convex: each vertex in a double well along y, E = c sum_v (y_v^2 - w^2)^2.
// The projected Hessian drops the concave part, so the Newton model is poor and
// the line search has to do its job.
class DoubleWell final : public Energy {
 public:
  DoubleWell(double c, double w) : c_(c), w_(w) {}
  void bind(const EnergyContext&) override {}
  double value(const Eigen::MatrixX3d& x) const override {
    return c_ * (x.col(1).array().square() - w_ * w_).square().sum();
  }
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    g.col(1).array() += 4 * c_ * x.col(1).array() * (x.col(1).array().square() - w_ * w_);
    return value(x);
  }
  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project) const override {
    for (int v = 0; v < x.rows(); ++v) {
      const double y = x(v, 1), d2 = c_ * (12 * y * y - 4 * w_ * w_);
      h.emplace_back(3 * v + 1, 3 * v + 1, project ? std::max(d2, 0.0) : d2);
    }
  }

 private:
  double c_, w_;
};

// Two per-vertex terms along y whose sum is convex although the second is not:
// E = sum_v [a/2 y^2] + [-b/2 y^2 + c y^4] - f y, exact E'' = a - b + 12 c y^2.
// Projected term by term (as the solver's energies project element by element)
// the second term's curvature is clamped at 0 where -b + 12 c y^2 < 0, so the
// projected Newton matrix is a + max(0, -b + 12 c y^2), about a / (a - b) times
// the exact one near the minimiser, and Newton converges only linearly.
class SplitWell final : public Energy {
 public:
  SplitWell(double a, double b, double c, double f) : a_(a), b_(b), c_(c), f_(f) {}
  void bind(const EnergyContext&) override {}
  double value(const Eigen::MatrixX3d& x) const override {
    const auto y = x.col(1).array();
    return (0.5 * (a_ - b_) * y.square() + c_ * y.square().square() - f_ * y).sum();
  }
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    const auto y = x.col(1).array();
    g.col(1).array() += (a_ - b_) * y + 4 * c_ * y.cube() - f_;
    return value(x);
  }
  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project) const override {
    for (int v = 0; v < x.rows(); ++v) {
      const double y = x(v, 1), second = -b_ + 12 * c_ * y * y;
      h.emplace_back(3 * v + 1, 3 * v + 1, a_ + (project ? std::max(second, 0.0) : second));
    }
  }

 private:
  double a_, b_, c_, f_;
};

std::vector<NamedEnergy> one(std::unique_ptr<Energy> e) {
  std::vector<NamedEnergy> v;
  v.push_back({"test", std::move(e)});
  return v;
}

}  // namespace

TEST_CASE("lumped masses are a third of each face's material-space area times the density", "[solver]") {
  const Garment g = grid(3, 0.5);  // 1 m x 1 m
  const Eigen::VectorXd m = geometry::vertex_masses(g);
  CHECK(m.sum() == Approx(0.187).epsilon(1e-12));
  CHECK(m[4] == Approx(0.187 * 6 * 0.125 / 3).epsilon(1e-12));  // the centre touches 6 faces of 1/8 m^2
}

TEST_CASE("a quasi-static step with a long time step lands on the minimiser of a quadratic energy", "[solver]") {
  const Garment g = grid(4, 0.1);
  const Eigen::Vector3d f(0.0, -2.0, 0.5);
  auto energies = one(std::make_unique<AnchorSprings>(g.mesh.vertices, 50.0, f));
  SolverSettings s;
  s.time_step = 1e4;  // the inertia term vanishes
  s.damping = 1;
  s.tolerance = 1e-10;
  s.max_displacement = 10;
  for (const std::string solver : {"eigen", "auto"}) {
    ClothSolver cs(g, energies, s);
    Eigen::MatrixX3d x = g.mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
    const StepReport r = cs.step(x, v);
    CHECK(r.converged);
    CHECK(r.iterations <= 2);
    // A quadratic model is exact: every Newton step passes at its first trial.
    CHECK(cs.timings().line_search_trials == r.iterations);
    const Eigen::MatrixX3d expected = g.mesh.vertices.rowwise() + (f / 50.0).transpose();
    CHECK((x - expected).cwiseAbs().maxCoeff() < 1e-9);
    CHECK(v.cwiseAbs().maxCoeff() == 0.0);  // damping 1: no velocity carried
    CHECK(r.phi_end < r.phi_start);
  }
}

TEST_CASE("the step length is capped by max_displacement and Newton continues from there", "[solver]") {
  const Garment g = grid(3, 0.1);
  auto energies = one(std::make_unique<AnchorSprings>(g.mesh.vertices, 1.0, Eigen::Vector3d(0, -1, 0)));  // 1 m away
  SolverSettings s;
  s.time_step = 1e4;
  s.damping = 1;
  s.max_displacement = 0.3;
  s.max_newton_iterations = 2;
  ClothSolver cs(g, energies, s);
  Eigen::MatrixX3d x = g.mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
  const StepReport r = cs.step(x, v);
  CHECK_FALSE(r.converged);
  CHECK(r.iterations == 2);
  CHECK(((x - g.mesh.vertices).rowwise().norm().array() - 0.6).abs().maxCoeff() < 1e-9);
}

TEST_CASE("backward Euler carries velocity: a free cloth under a constant force accelerates", "[solver]") {
  const Garment g = grid(3, 0.1);
  auto energies = one(std::make_unique<AnchorSprings>(g.mesh.vertices, 0.0, Eigen::Vector3d(0, -1, 0)));
  SolverSettings s;
  s.time_step = 0.01;
  s.damping = 0;
  s.tolerance = 1e-12;
  s.max_displacement = 100;
  ClothSolver cs(g, energies, s);
  Eigen::MatrixX3d x = g.mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
  cs.step(x, v);
  cs.step(x, v);
  // Implicit Euler with a constant force F on mass m: v_n = n h F/m, x_2 - x_0 = 3 h^2 F / m.
  const Eigen::VectorXd& m = cs.masses();
  for (int i = 0; i < x.rows(); ++i) {
    CHECK(v(i, 1) == Approx(-2 * 0.01 / m[i]).epsilon(1e-8));
    CHECK(x(i, 1) - g.mesh.vertices(i, 1) == Approx(-3 * 1e-4 / m[i]).epsilon(1e-8));
  }
}

namespace {

// 30 steps from the hump's shoulder of a double well (y = 0.05, where the
// exact curvature 10 (12 y^2 - 4 w^2) is negative) into the well at y = 0.2:
// Phi and E never rise. Returns the solver's counters.
ClothSolver::Timings descend_double_well(double exact_hessian_below) {
  const Garment g = grid(4, 0.1);
  auto energies = one(std::make_unique<DoubleWell>(10.0, 0.2));
  SolverSettings s;
  s.time_step = 1.0;
  s.damping = 1;
  s.max_newton_iterations = 50;
  s.tolerance = 1e-8;
  s.exact_hessian_below = exact_hessian_below;
  ClothSolver cs(g, energies, s);
  Eigen::MatrixX3d x = g.mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
  x.col(1).setConstant(0.05);
  double previous = cs.energy(x) + 1;
  for (int k = 0; k < 30; ++k) {
    const StepReport r = cs.step(x, v);
    CHECK(r.phi_end <= r.phi_start);
    CHECK(cs.energy(x) <= previous);
    previous = cs.energy(x);
    CHECK(x.allFinite());
  }
  CHECK((x.col(1).array() - 0.2).abs().maxCoeff() < 1e-4);
  return cs.timings();
}

}  // namespace

TEST_CASE("on a non-convex energy the line search keeps Phi decreasing and Newton reaches a well", "[solver]") {
  descend_double_well(0);  // projected matrices only
}

TEST_CASE("solver settings are checked", "[solver]") {
  const Garment g = grid(3, 0.1);
  auto energies = one(std::make_unique<DoubleWell>(1.0, 0.2));
  SolverSettings s;
  s.time_step = 0;
  CHECK_THROWS_AS(ClothSolver(g, energies, s), ConfigError);
  s = {};
  s.linear_solver = "lu";
  CHECK_THROWS_WITH(ClothSolver(g, energies, s), Catch::Contains("unknown 'lu'"));
}

TEST_CASE("the fixed-pattern assembly equals Eigen's triplet assembly and grows for foreign couplings", "[solver]") {
  const Garment g = grid(5, 0.1);
  physics::HessianPattern pattern(g.mesh);
  const int n = 3 * g.mesh.num_vertices();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Triplets t;
  // Symmetric 3x3 blocks on the pairs of every face, like an energy emits.
  for (int f = 0; f < g.mesh.num_faces(); ++f)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int r = 3 * g.mesh.faces(f, a) + i, c = 3 * g.mesh.faces(f, b) + j;
            if (r >= c) {
              const double value = u(rng);
              t.emplace_back(r, c, value);
              if (r != c) t.emplace_back(c, r, value);
            }
          }
  Eigen::VectorXd diagonal = Eigen::VectorXd::Constant(n, 5.0);
  auto reference = [&](const Triplets& trip) {
    Eigen::SparseMatrix<double> r(n, n);
    r.setFromTriplets(trip.begin(), trip.end());
    Eigen::MatrixXd d = Eigen::MatrixXd(r).triangularView<Eigen::Lower>();
    d.diagonal() += diagonal;
    return d;
  };
  Eigen::SparseMatrix<double> h;
  pattern.assemble(t, diagonal, h);
  CHECK((Eigen::MatrixXd(h) - reference(t)).cwiseAbs().maxCoeff() < 1e-12);
  const auto before = pattern.nonzeros();
  // Couple two far corners of the grid: not in the topology's pattern.
  t.emplace_back(3 * 24, 0, 0.75);
  t.emplace_back(0, 3 * 24, 0.75);
  pattern.assemble(t, diagonal, h);
  CHECK(pattern.nonzeros() > before);
  CHECK((Eigen::MatrixXd(h) - reference(t)).cwiseAbs().maxCoeff() < 1e-12);

  // The same positions with new values (the remembered slots), then in another
  // order (a new search), then fewer triplets: always the reference, no stale values.
  for (auto& e : t) e = Eigen::Triplet<double>(e.row(), e.col(), e.value() * 2 - 0.5);
  diagonal.setConstant(7.0);
  pattern.assemble(t, diagonal, h);
  CHECK((Eigen::MatrixXd(h) - reference(t)).cwiseAbs().maxCoeff() < 1e-12);
  std::shuffle(t.begin(), t.end(), rng);
  pattern.assemble(t, diagonal, h);
  CHECK((Eigen::MatrixXd(h) - reference(t)).cwiseAbs().maxCoeff() < 1e-12);
  t.resize(t.size() / 2);
  pattern.assemble(t, diagonal, h);
  CHECK((Eigen::MatrixXd(h) - reference(t)).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("set_blas_threads reaches OpenBLAS when it is the BLAS linked", "[solver]") {
  using GetThreads = int (*)();
  void* get = dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
  if (!get) {
    SUCCEED("the BLAS linked is not OpenBLAS");
    return;
  }
  const int before = reinterpret_cast<GetThreads>(get)();
  REQUIRE(set_blas_threads(1));
  CHECK(reinterpret_cast<GetThreads>(get)() == 1);
  set_blas_threads(before);
  CHECK(reinterpret_cast<GetThreads>(get)() == before);
}

namespace {

// A cloth-like SPD matrix (its lower triangle): 3 dofs per vertex of a side x
// side grid, coupled to the 2-ring (as bending couples vertices), plus a
// small mass term.
physics::SparseMatrix cloth_like_matrix(int side) {
  const int n = 3 * side * side;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> weight(0.5, 1.5);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (const auto& [di, dj] : std::vector<std::pair<int, int>>{{1, 0}, {0, 1}, {1, 1}, {2, 0}, {0, 2}}) {
        if (i + di >= side || j + dj >= side) continue;
        const int a = i * side + j, b = (i + di) * side + j + dj;
        const double w = weight(rng);
        for (int c = 0; c < 3; ++c)
          for (int d = 0; d < 3; ++d) {
            const double v = c == d ? w : 0.1 * w;
            t.emplace_back(3 * a + c, 3 * a + d, v);
            t.emplace_back(3 * b + c, 3 * b + d, v);
            t.emplace_back(3 * a + c, 3 * b + d, -v);
            t.emplace_back(3 * b + c, 3 * a + d, -v);
          }
      }
  for (int k = 0; k < n; ++k) t.emplace_back(k, k, 1e-2);
  physics::SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

}  // namespace

TEST_CASE("the float copy of CHOLMOD's factor solves to float precision and only preconditions", "[solver]") {
  if (!physics::cholmod_available()) {
    SUCCEED("built without CHOLMOD: Eigen's back end always solves exactly");
    return;
  }
  const physics::SparseMatrix a = cloth_like_matrix(24);
  const int n = static_cast<int>(a.rows());
  const physics::SparseMatrix lower = a.triangularView<Eigen::Lower>();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0).array().sin();

  const auto single = physics::make_sparse_cholesky("cholmod", true);
  REQUIRE(single->factorize(lower));
  const Eigen::VectorXd exact = single->solve(b), approximate = single->precondition(b);
  CHECK((a * exact - b).norm() / b.norm() < 1e-10);
  const double error = (approximate - exact).norm() / exact.norm();
  CHECK(error < 1e-4);    // float precision times the matrix's condition
  CHECK(error > 1e-12);   // and really the float copy, not the double solve
  CHECK(b.dot(approximate) > 0);  // a positive definite preconditioner

  const auto exact_only = physics::make_sparse_cholesky("cholmod", false);
  REQUIRE(exact_only->factorize(lower));
  CHECK(exact_only->precondition(b) == exact_only->solve(b));
}

TEST_CASE("CHOLMOD solvers ordering at the same time in two threads solve bit for bit as one alone", "[solver]") {
  // METIS keeps one random generator for the process; two orderings at once
  // (drape generate's workers) must not change either (drapes would then
  // depend on what ran beside them).
  if (!physics::cholmod_available()) {
    SUCCEED("built without CHOLMOD");
    return;
  }
  const physics::SparseMatrix lower = cloth_like_matrix(40).triangularView<Eigen::Lower>();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(lower.rows(), -1.0, 2.0).array().cos();
  auto solve_fresh = [&]() {
    const auto solver = physics::make_sparse_cholesky("cholmod", false);
    // (Catch's assertions are not thread-safe: a failed factorisation shows as a NaN solve.)
    return solver->factorize(lower) ? solver->solve(b) : Eigen::VectorXd::Constant(b.size(), NAN);
  };
  const Eigen::VectorXd alone = solve_fresh();
  REQUIRE(alone.allFinite());
  int differing = 0;
  for (int round = 0; round < 40; ++round) {
    Eigen::VectorXd x[2];
    std::thread other([&] { x[1] = solve_fresh(); });
    x[0] = solve_fresh();
    other.join();
    differing += (x[0] != alone) + (x[1] != alone);
  }
  CHECK(differing == 0);
}

namespace {

// Threads of this process now (Linux: one entry per thread in /proc/self/task).
int process_threads() {
  int count = 0;
  std::error_code error;
  for (auto it = std::filesystem::directory_iterator("/proc/self/task", error);
       !error && it != std::filesystem::directory_iterator(); it.increment(error))
    ++count;
  return error ? -1 : count;
}

}  // namespace

TEST_CASE("a CHOLMOD factorisation and solve run on the calling thread alone", "[solver]") {
  // Debian's CHOLMOD asks OpenMP for teams of four whatever OMP_NUM_THREADS
  // says; woken per supernode, they cost a one-thread drape a third of its
  // time (sparse_cholesky.cpp). The solver keeps those teams to one thread.
  if (!physics::cholmod_available()) {
    SUCCEED("built without CHOLMOD");
    return;
  }
  // ctest runs each case in a fresh process, where no OpenMP team exists yet
  // (the test main's own threads are counted in `before`).
  const int before = process_threads();
  REQUIRE(before > 0);
  const physics::SparseMatrix lower = cloth_like_matrix(30).triangularView<Eigen::Lower>();
  const auto solver = physics::make_sparse_cholesky("cholmod", true);
  for (int k = 0; k < 3; ++k) REQUIRE(solver->factorize(lower));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(lower.rows());
  CHECK(solver->solve(b).allFinite());
  CHECK(process_threads() == before);
}

TEST_CASE("a matrix that is not positive definite is refused by CHOLMOD without a word on the terminal", "[solver]") {
  // The solver answers a failed factorisation by shifting the diagonal; the
  // library's own warning only alarmed users.
  if (!physics::cholmod_available()) {
    SUCCEED("built without CHOLMOD");
    return;
  }
  physics::SparseMatrix indefinite = cloth_like_matrix(12).triangularView<Eigen::Lower>();
  for (int k = 0; k < indefinite.rows(); k += 7) indefinite.coeffRef(k, k) = -1.0;
  // CHOLMOD prints through printf: both of the terminal's streams are captured.
  test::TempDir dir;
  const std::string captured = (dir / "printed.txt").string();
  std::fflush(stdout);
  std::fflush(stderr);
  const int saved_out = dup(1), saved_err = dup(2);
  FILE* sink = std::fopen(captured.c_str(), "w");
  REQUIRE(sink);
  dup2(fileno(sink), 1);
  dup2(fileno(sink), 2);
  const auto solver = physics::make_sparse_cholesky("cholmod", true);
  const bool factored = solver->factorize(indefinite);
  std::fflush(stdout);
  std::fflush(stderr);
  dup2(saved_out, 1);
  dup2(saved_err, 2);
  close(saved_out);
  close(saved_err);
  std::fclose(sink);
  CHECK_FALSE(factored);
  std::ifstream in(captured);
  const std::string printed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(printed.empty());
}

TEST_CASE("near a minimum the exact Newton matrix converges quadratically where the projected one crawls", "[solver]") {
  // y + 4 y^3 = 0.1 (a - b = 1, c = 1): the root by bisection, independent of the solver.
  double lo = 0, hi = 1;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mid + 4 * mid * mid * mid < 0.1 ? lo : hi) = mid;
  }
  const double root = 0.5 * (lo + hi);
  REQUIRE(-9 + 12 * root * root < 0);  // the second term is concave at the minimiser: projection bites

  const Garment g = grid(3, 0.1);
  auto run = [&](double exact_below, ClothSolver::Timings& timings) {
    auto energies = one(std::make_unique<SplitWell>(10.0, 9.0, 1.0, 0.1));
    SolverSettings s;
    s.time_step = 1e3;  // inertia ~1e-10 of the stiffness: a static solve
    s.damping = 1;
    s.max_newton_iterations = 200;
    s.tolerance = 1e-8;
    s.max_displacement = 1.0;  // no cap: every step is Newton's own
    s.exact_hessian_below = exact_below;
    ClothSolver cs(g, energies, s);
    Eigen::MatrixX3d x = g.mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
    x.col(1).setConstant(0.2);
    const StepReport r = cs.step(x, v);
    timings = cs.timings();
    if (exact_below > 0) {
      CHECK(r.converged);
      CHECK((x.col(1).array() - root).abs().maxCoeff() < 1e-9);
    }
    return r.converged ? r.iterations : 1000;
  };
  ClothSolver::Timings exact_timings, projected_timings;
  const int exact = run(1e30, exact_timings);
  const int projected = run(0, projected_timings);
  CHECK(exact <= 8);
  CHECK(projected >= 3 * exact);  // 1000: not even converged within 200 iterations
  CHECK(exact_timings.exact_steps == exact);
  CHECK(exact_timings.exact_refused == 0);
  CHECK(projected_timings.exact_steps == 0);
}

TEST_CASE("an indefinite exact Newton matrix is refused and the projected one takes the step", "[solver]") {
  const ClothSolver::Timings t = descend_double_well(1e30);  // the exact matrix tried at every iteration
  CHECK(t.exact_refused > 0);  // on the shoulder
  CHECK(t.exact_steps > 0);    // in the well, where it is convex
}

TEST_CASE("a step given a settle tolerance ends at the iteration where the static forces balance", "[solver]") {
  // Springs to anchors under a load, short time steps: each step's Phi has
  // its minimiser short of the static one; the drape balances within a step.
  const Garment g = grid(4, 0.1);
  const Eigen::Vector3d f(0.0, -0.02, 0.0);
  auto run = [&](double settled_below, int& steps, int& iterations) {
    auto energies = one(std::make_unique<AnchorSprings>(g.mesh.vertices, 5.0, f));
    SolverSettings s;
    s.time_step = 0.5;
    s.damping = 1;
    s.tolerance = 1e-12;
    s.max_newton_iterations = 30;
    ClothSolver cs(g, energies, s);
    Eigen::MatrixX3d x = g.mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
    steps = iterations = 0;
    for (; steps < 200 && cs.static_residual(x) > 1e-3; ++steps) {
      const StepReport r = cs.step(x, v, settled_below);
      iterations += r.iterations;
      if (settled_below > 0 && r.settled) CHECK(cs.static_residual(x) <= settled_below);
    }
    return cs.static_residual(x);
  };
  int steps_each = 0, iterations_each = 0, steps_end = 0, iterations_end = 0;
  CHECK(run(1e-3, steps_each, iterations_each) <= 1e-3);
  CHECK(run(0, steps_end, iterations_end) <= 1e-3);
  CHECK(steps_each <= steps_end);
  CHECK(iterations_each < iterations_end);  // the last step stops early
}

TEST_CASE("PCG with the kept factor is tried less after it stalls, and the step lands on the same minimiser", "[solver]") {
  // One CG iteration to a 1e-12 forcing: every PCG attempt on a changed
  // matrix stalls. With adaptive tries the solver stops paying for them.
  const Garment g = grid(5, 0.1);
  auto run = [&](bool adaptive, ClothSolver::Timings& t) {
    auto energies = one(std::make_unique<DoubleWell>(10.0, 0.2));
    SolverSettings s;
    s.time_step = 1.0;
    s.damping = 1;
    s.max_newton_iterations = 60;
    s.tolerance = 1e-9;
    s.newton_forcing = 1e-12;
    s.max_cg_iterations = 1;
    s.adaptive_tries = adaptive;
    ClothSolver cs(g, energies, s);
    Eigen::MatrixX3d x = g.mesh.vertices, v = Eigen::MatrixX3d::Zero(x.rows(), 3);
    for (int k = 0; k < x.rows(); ++k) x(k, 1) = 0.3 + 0.01 * k;
    for (int k = 0; k < 5; ++k) cs.step(x, v);
    t = cs.timings();
    return x;
  };
  ClothSolver::Timings adaptive, every;
  const Eigen::MatrixX3d a = run(true, adaptive), b = run(false, every);
  CHECK((a.col(1).array() - 0.2).abs().maxCoeff() < 1e-6);
  CHECK((b.col(1).array() - 0.2).abs().maxCoeff() < 1e-6);
  REQUIRE(every.cg_failures > 4);
  CHECK(every.cg_skipped == 0);
  CHECK(adaptive.cg_skipped > 0);
  CHECK(adaptive.cg_attempts < every.cg_attempts);
}
