// Newton on the backward-Euler incremental potential (see solver.hpp).
#include <drape/energy.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/vertex_areas.hpp>
#include <drape/physics/dissipation.hpp>
#include <drape/physics/solver.hpp>

#include <Eigen/LU>

#include "hessian_pattern.hpp"
#include "sparse_cholesky.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace drape {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The Hessian's index is 3 * vertex + axis (energy.hpp); Eigen's MatrixX3d is
// column-major, so vectors are interleaved explicitly.
Eigen::VectorXd interleaved(const Eigen::MatrixX3d& m) {
  Eigen::VectorXd v(m.size());
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(v.data(), m.rows(), 3) = m;
  return v;
}

Eigen::MatrixX3d per_vertex(const Eigen::VectorXd& v) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(v.data(), v.size() / 3, 3);
}

bool finite(const Eigen::MatrixX3d& m) { return m.allFinite(); }

// The energies whose value or gradient is not finite at x, each named with
// what failed, so that a NaN from one plugin is blamed on it and not on the
// step that met it (a drape that cannot move reads as blocked contact).
std::string non_finite_energies(const std::vector<NamedEnergy>& energies, const Eigen::MatrixX3d& x) {
  std::string named;
  for (const NamedEnergy& e : energies) {
    const double value = e.energy->value(x);
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
    e.energy->add_gradient(x, g);
    std::string what;
    if (!std::isfinite(value)) what = "its value is " + std::to_string(value);
    if (!g.allFinite()) what += std::string(what.empty() ? "" : " and ") + "its gradient is not finite";
    if (!what.empty()) named += std::string(named.empty() ? "" : "; ") + "'" + e.name + "' (" + what + ")";
  }
  return named;
}

// Scales a step so that no vertex moves farther than `limit` (a long step
// could carry cloth through a thin limb).
void cap_longest_move(Eigen::MatrixX3d& step, double limit) {
  const double longest = step.rowwise().norm().maxCoeff();
  if (longest > limit) step *= limit / longest;
}

}  // namespace

struct ClothSolver::Impl {
  physics::HessianPattern pattern;
  std::unique_ptr<physics::SparseCholesky> cholesky;
  bool have_factor = false;  // the factor of an earlier Newton matrix, kept across iterations and steps
  // What reusing the kept factor has been saving. A PCG attempt that reaches
  // max_cg_iterations costs more than the factorisation that follows it
  // (docs/scenes.md), and on a sliding drape most attempts do; so after a
  // failed attempt the next 1, 2, 4, ... 16 iterations factorise without
  // trying, and a success starts trusting the factor again.
  int cg_failures_in_row = 0, cg_skip = 0;
  // Likewise the exact matrix: refused (indefinite) at some step residual, it
  // is not tried again until the residual has halved or 1, 2, 4, ... 32
  // iterations have passed, since far from equilibrium it is refused again
  // and again (an assembly and a failed solve each time).
  int exact_refusals_in_row = 0, exact_wait = 0;
  double exact_refused_residual = std::numeric_limits<double>::infinity();
  Triplets triplets;
  physics::SparseMatrix hessian;

  class NewtonIterations;  // one ClothSolver::step
};

namespace {

// Preconditioned conjugate gradients on H d = b from d = 0, with the factor of
// an earlier Newton matrix as the preconditioner. Every iterate from 0 is a
// descent direction of the quadratic model (H and the preconditioner are
// positive definite), so stopping early still gives a usable Newton step.
// Returns the iterations taken, -1 when |H d - b| <= tolerance |b| was not
// reached within max_iterations, or kIndefinite when a direction of
// non-positive curvature (p^T H p <= 0) proved H indefinite.
constexpr int kIndefinite = -2;
int preconditioned_cg(const physics::SparseMatrix& h, const physics::SparseCholesky& preconditioner,
                      const Eigen::VectorXd& b, double tolerance, int max_iterations, Eigen::VectorXd& d) {
  // The matrix holds its lower triangle only (sparse_cholesky.hpp).
  const auto sym = h.selfadjointView<Eigen::Lower>();
  d.setZero(b.size());
  Eigen::VectorXd r = b, z = preconditioner.precondition(r), p = z, hp(b.size());
  double rz = r.dot(z);
  const double goal = tolerance * b.norm();
  for (int k = 1; k <= max_iterations; ++k) {
    hp.noalias() = sym * p;
    const double php = p.dot(hp);
    if (!(php > 0)) return kIndefinite;
    const double step = rz / php;
    d += step * p;
    r -= step * hp;
    if (r.norm() <= goal) return k;
    z = preconditioner.precondition(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return -1;
}

}  // namespace

ClothSolver::ClothSolver(const Garment& garment, std::vector<NamedEnergy>& energies, SolverSettings settings)
    : garment_(garment), energies_(energies), settings_(std::move(settings)), impl_(std::make_unique<Impl>()) {
  if (!(settings_.time_step > 0)) throw ConfigError("solver: time_step must be > 0");
  if (settings_.damping < 0 || settings_.damping > 1) throw ConfigError("solver: damping must be in [0, 1]");
  if (settings_.max_newton_iterations < 1) throw ConfigError("solver: max_newton_iterations must be >= 1");
  masses_ = geometry::vertex_masses(garment);
  // A vertex whose faces all have zero material-space area would have no
  // inertia and make the Newton matrix singular: give it a tiny mass floor.
  const double floor = 1e-9 * std::max(masses_.maxCoeff(), 1e-12);
  masses_ = masses_.cwiseMax(floor);
  force_scale_ = std::max(masses_.norm() * 9.81, 1e-12);
  impl_->pattern = physics::HessianPattern(garment.mesh);
  impl_->cholesky = physics::make_sparse_cholesky(settings_.linear_solver, settings_.float_preconditioner);
}

ClothSolver::~ClothSolver() = default;

std::string ClothSolver::linear_solver() const { return impl_->cholesky->name(); }

double ClothSolver::energy(const Eigen::MatrixX3d& x, std::vector<EnergyTerm>* terms) const {
  double total = 0;
  if (terms) terms->clear();
  for (const NamedEnergy& e : energies_) {
    const double v = e.energy->value(x);
    total += v;
    if (terms) terms->push_back({e.name, v});
  }
  return total;
}

Eigen::MatrixX3d ClothSolver::static_gradient(const Eigen::MatrixX3d& x) const {
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
  for (const NamedEnergy& e : energies_) e.energy->add_gradient(x, g);
  return g;
}

double ClothSolver::static_residual(const Eigen::MatrixX3d& x) const { return static_gradient(x).norm() / force_scale_; }

namespace {

// min |base + sum_k l_k p_k| over the simplex l >= 0, sum l = 1, exactly: the
// nearest point of the hull of the p_k to -base lies on one of its triangles
// (edges and corners are degenerate triangles), unless -base is inside one of
// its tetrahedra. A handful of points, so enumerating them all is cheap.
double min_norm_in_hull(const Eigen::Vector3d& base, const std::vector<Eigen::Vector3d>& p) {
  const Eigen::Vector3d target = -base;
  const std::size_t n = p.size();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      for (std::size_t k = j; k < n; ++k)
        best = std::min(best, (geometry::closest_point_on_triangle(target, p[i], p[j], p[k]).point - target).norm());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k)
        for (std::size_t l = k + 1; l < n; ++l) {
          Eigen::Matrix3d m;
          m << p[j] - p[i], p[k] - p[i], p[l] - p[i];
          const double scale = m.colwise().norm().prod();
          if (!(std::abs(m.determinant()) > 1e-12 * scale)) continue;
          const Eigen::Vector3d w = m.partialPivLu().solve(target - p[i]);
          if (w.minCoeff() >= 0 && w.sum() <= 1) return 0;
        }
  return best;
}

}  // namespace

double ClothSolver::stationarity(const Eigen::MatrixX3d& x, double radius) const {
  Eigen::MatrixX3d smooth = Eigen::MatrixX3d::Zero(x.rows(), 3), rough = smooth;
  std::vector<const Energy*> kinked;
  for (const NamedEnergy& e : energies_) {
    const bool kinks = e.energy->has_kinks();
    e.energy->add_gradient(x, kinks ? rough : smooth);
    // Friction's push (the last step's lagged contacts) balances the cloth
    // too; ClothSolver::sliding tells whether it held it still.
    if (const Dissipation* d = e.energy->dissipation()) d->add_gradient(x, smooth);
    if (kinks) kinked.push_back(e.energy.get());
  }
  double sum = 0;
  std::vector<Eigen::Vector3d> points, samples;
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const Eigen::Vector3d base = smooth.row(v).transpose(), own = rough.row(v).transpose();
    double r = (base + own).norm();
    if (!kinked.empty() && own.squaredNorm() > 0 && r > 0) {
      // The hull of the non-smooth gradients at v and around it; with several
      // non-smooth energies, their k-th samples summed (a subset of the
      // Minkowski sum, so r can only be overestimated).
      points.assign(1, own);
      for (const Energy* e : kinked) {
        samples.clear();
        e->vertex_gradient_samples(x, static_cast<int>(v), radius, samples);
        if (points.size() < samples.size() + 1) points.resize(samples.size() + 1, Eigen::Vector3d::Zero());
        for (std::size_t k = 0; k < samples.size(); ++k) points[k + 1] += samples[k];
      }
      r = std::min(r, min_norm_in_hull(base, points));
    }
    sum += r * r;
  }
  return std::sqrt(sum) / force_scale_;
}

double ClothSolver::slip_ratio(const Eigen::MatrixX3d& x) const {
  double largest = 0;
  for (const NamedEnergy& e : energies_)
    if (const Dissipation* d = e.energy->dissipation()) largest = std::max(largest, d->slip_ratio(x));
  return largest;
}

double ClothSolver::max_step(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, const Eigen::MatrixX3d* body_from,
                             const Eigen::MatrixX3d* body_to) const {
  const auto t = Clock::now();
  double alpha = 1;
  for (const NamedEnergy& e : energies_) alpha = std::min(alpha, e.energy->max_step(x, dx, body_from, body_to));
  timings_.collision_checks += since(t);
  return alpha;
}

double ClothSolver::phi(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& x_hat) const {
  const double inv_h2 = 1.0 / (settings_.time_step * settings_.time_step);
  const double inertia = 0.5 * inv_h2 * (masses_.asDiagonal() * (x - x_hat)).cwiseProduct(x - x_hat).sum();
  double dissipation = 0;
  for (const NamedEnergy& e : energies_)
    if (const Dissipation* d = e.energy->dissipation()) dissipation += d->value(x);
  return inertia + energy(x) + dissipation;
}

// The Newton iterations of one backward-Euler step (ClothSolver::step): each
// takes the gradient of Phi, a Newton direction (by PCG with a kept factor, or
// a factorisation; the exact matrix near equilibrium) and a line search along
// it. A member of ClothSolver::Impl, so it sees the solver's settings,
// energies and timings.
class ClothSolver::Impl::NewtonIterations {
 public:
  NewtonIterations(ClothSolver& solver, Eigen::MatrixX3d& x, const Eigen::MatrixX3d& x_hat, StepReport& report)
      : s_(solver), m_(*solver.impl_), x_(x), x_hat_(x_hat), report_(report) {}

  // Iterates until converged, settled, out of iterations or without a
  // decrease; returns Phi at the end.
  double run(double settled_below) {
    report_.phi_start = s_.phi(x_, x_hat_);
    // An accepted state has a finite energy (a barrier is infinite only at
    // contact, which no accepted step reaches), so NaN here is an energy's bug.
    if (std::isnan(report_.phi_start)) fail_non_finite();
    phi_x_ = report_.phi_start;
    g_.resize(n_, 3);
    // The inertia's diagonal M / h^2 of every Newton matrix of this step.
    diagonal_.resize(3 * n_);
    for (int i = 0; i < n_; ++i) diagonal_.segment<3>(3 * i).setConstant(s_.masses_[i] * inv_h2_);
    for (;;) {
      if (balanced(settled_below)) break;
      if (report_.iterations >= s_.settings_.max_newton_iterations) break;
      ++report_.iterations;
      Eigen::MatrixX3d d = per_vertex(newton_direction());
      if (!finite(d)) throw Error("solver: the Newton direction is not finite");
      cap_longest_move(d, s_.settings_.max_displacement);
      if (!move_downhill(d)) {
        ++report_.line_search_failures;
        break;  // no decrease along either direction: the step is as good as it gets
      }
    }
    return phi_x_;
  }

 private:
  // One Newton matrix's linear solve: the right-hand side -g, the direction
  // found, and how PCG with the kept factor went.
  struct LinearSolve {
    Eigen::VectorXd rhs, direction;
    bool try_cg = false;
    int cg = -1;
  };

  void gradient(const Eigen::MatrixX3d& at);
  bool balanced(double settled_below);
  Eigen::VectorXd newton_direction();
  bool should_try_cg();
  bool should_try_exact();
  void newton_matrix(bool project);
  bool reuse_factor(LinearSolve& solve);
  bool solve_exact(LinearSolve& solve);
  void solve_projected(LinearSolve& solve);
  bool move_downhill(const Eigen::MatrixX3d& d);
  bool line_search(const Eigen::MatrixX3d& dir);

  ClothSolver& s_;
  Impl& m_;
  Eigen::MatrixX3d& x_;
  const Eigen::MatrixX3d& x_hat_;
  StepReport& report_;
  const int n_ = static_cast<int>(x_.rows());
  const double h_ = s_.settings_.time_step, inv_h2_ = 1.0 / (h_ * h_);
  // Names the energies that are not finite at x_ and throws.
  [[noreturn]] void fail_non_finite() const;
  double phi_x_ = 0;
  Eigen::MatrixX3d g_;
  Eigen::VectorXd diagonal_;
};

void ClothSolver::Impl::NewtonIterations::gradient(const Eigen::MatrixX3d& at) {
  const auto t = Clock::now();
  g_ = inv_h2_ * (s_.masses_.asDiagonal() * (at - x_hat_));
  for (NamedEnergy& e : s_.energies_) {
    e.energy->add_gradient(at, g_);
    if (const Dissipation* d = e.energy->dissipation()) d->add_gradient(at, g_);
  }
  s_.timings_.gradient += since(t);
  if (!finite(g_)) fail_non_finite();
}

void ClothSolver::Impl::NewtonIterations::fail_non_finite() const {
  const std::string named = non_finite_energies(s_.energies_, x_);
  throw Error("solver: the energy is not finite at an accepted state: " +
              (named.empty() ? std::string("no single energy is (their sum or the inertia is)") : named) +
              "; an energy plugin must return finite values and gradients wherever the cloth may go");
}

// The gradient at x, and whether it is small enough to stop: converged, or
// (settled_below > 0) the drape balances without the inertia.
bool ClothSolver::Impl::NewtonIterations::balanced(double settled_below) {
  gradient(x_);
  report_.residual = g_.norm() / s_.force_scale_;
  if (report_.residual <= s_.settings_.tolerance) {
    report_.converged = true;
    return true;
  }
  if (settled_below > 0) {
    // The static forces without the inertia: the drape's own balance.
    const double balance = (g_ - inv_h2_ * (s_.masses_.asDiagonal() * (x_ - x_hat_))).norm() / s_.force_scale_;
    if (balance <= settled_below) {
      report_.settled = true;
      return true;
    }
  }
  return false;
}

void ClothSolver::Impl::NewtonIterations::newton_matrix(bool project) {
  auto t = Clock::now();
  Triplets& trip = m_.triplets;
  trip.clear();
  for (NamedEnergy& e : s_.energies_) {
    e.energy->add_hessian_lower(x_, trip, project);
    if (const Dissipation* d = e.energy->dissipation()) d->add_hessian_lower(x_, trip);
  }
  s_.timings_.hessian += since(t);
  t = Clock::now();
  m_.pattern.assemble(trip, diagonal_, m_.hessian);
  s_.timings_.assembly += since(t);
}

// Factorising dominates an iteration. The matrix changes little from one
// iteration (and time step) to the next, so an earlier factor is a very
// good preconditioner: an inexact Newton step by PCG costs a few
// triangular solves. Only when PCG stalls is the matrix factorised anew.
bool ClothSolver::Impl::NewtonIterations::should_try_cg() {
  bool try_cg = s_.settings_.reuse_factorization && m_.have_factor;
  if (try_cg && m_.cg_skip > 0) {
    --m_.cg_skip;
    try_cg = false;
    ++s_.timings_.cg_skipped;
  }
  return try_cg;
}

bool ClothSolver::Impl::NewtonIterations::reuse_factor(LinearSolve& solve) {
  solve.cg = -1;
  if (!solve.try_cg || !m_.have_factor) return false;
  ++s_.timings_.cg_attempts;
  solve.cg = preconditioned_cg(m_.hessian, *m_.cholesky, solve.rhs, s_.settings_.newton_forcing,
                               s_.settings_.max_cg_iterations, solve.direction);
  if (solve.cg > 0) {
    s_.timings_.cg_iterations += solve.cg;
    m_.cg_failures_in_row = 0;
  } else if (solve.cg == -1) {
    ++s_.timings_.cg_failures;
    if (s_.settings_.adaptive_tries) m_.cg_skip = 1 << std::min(m_.cg_failures_in_row++, 4);
  }
  return solve.cg > 0;
}

// Near equilibrium: the exact matrix, when it is positive definite. CG
// preconditioned by the kept factor, or else a Cholesky factorisation,
// finds out: both break down on an indefinite matrix (and a breakdown in
// CG spares the factorisation, keeping the old factor for the projected
// matrix). -H^-1 g is then a descent direction; checked all the same, as
// round-off could flip it.
bool ClothSolver::Impl::NewtonIterations::should_try_exact() {
  bool try_exact = s_.settings_.exact_hessian_below > 0 && report_.residual < s_.settings_.exact_hessian_below;
  if (try_exact && m_.exact_wait > 0 && !(report_.residual < 0.5 * m_.exact_refused_residual)) {
    --m_.exact_wait;
    try_exact = false;
    ++s_.timings_.exact_skipped;
  }
  return try_exact;
}

bool ClothSolver::Impl::NewtonIterations::solve_exact(LinearSolve& solve) {
  newton_matrix(false);
  auto t = Clock::now();
  bool solved = reuse_factor(solve) && solve.direction.dot(solve.rhs) > 0;
  if (!solved && solve.cg != kIndefinite) {
    m_.have_factor = m_.cholesky->factorize(m_.hessian);
    ++s_.timings_.factorizations;
    if (m_.have_factor) {
      solve.direction = m_.cholesky->solve(solve.rhs);
      solved = solve.direction.allFinite() && solve.direction.dot(solve.rhs) > 0;
    }
  }
  s_.timings_.linear_solves += since(t);
  if (solved) {
    ++s_.timings_.exact_steps;
    m_.exact_refusals_in_row = 0;
    m_.exact_wait = 0;
  } else {
    ++s_.timings_.exact_refused;
    m_.exact_refused_residual = report_.residual;
    if (s_.settings_.adaptive_tries) m_.exact_wait = 1 << std::min(m_.exact_refusals_in_row++, 5);
  }
  return solved;
}

// Newton matrix: M / h^2 + sum of projected Hessians, on the fixed pattern.
void ClothSolver::Impl::NewtonIterations::solve_projected(LinearSolve& solve) {
  newton_matrix(true);
  auto t = Clock::now();
  if (!reuse_factor(solve)) {
    // The inertia term makes the matrix positive definite in exact arithmetic;
    // a failed factorisation (round-off on a huge stiffness ratio) is retried
    // with a growing diagonal shift, which keeps the direction a descent one.
    m_.have_factor = false;
    bool factored = m_.cholesky->factorize(m_.hessian);
    ++s_.timings_.factorizations;
    for (double shift = 1e-8 * m_.hessian.diagonal().cwiseAbs().maxCoeff(); !factored && shift < 1e30; shift *= 100) {
      physics::SparseMatrix shifted = m_.hessian;
      for (int k = 0; k < shifted.rows(); ++k) shifted.coeffRef(k, k) += shift;
      factored = m_.cholesky->factorize(shifted);
      ++s_.timings_.factorizations;
    }
    if (!factored) throw Error("solver: the Newton matrix could not be factorised even with a diagonal shift");
    m_.have_factor = true;
    solve.direction = m_.cholesky->solve(solve.rhs);
  }
  s_.timings_.linear_solves += since(t);
}

// The Newton direction at x (interleaved, see interleaved()).
Eigen::VectorXd ClothSolver::Impl::NewtonIterations::newton_direction() {
  LinearSolve solve;
  solve.rhs = -interleaved(g_);
  solve.try_cg = should_try_cg();
  bool solved = false;
  if (should_try_exact()) solved = solve_exact(solve);
  if (!solved) solve_projected(solve);
  return std::move(solve.direction);
}

// Armijo backtracking along d; at a contact kink (the closest body face
// switches across a crease) the Newton model can point where Phi does not
// fall, so a failed search is retried along the Jacobi-preconditioned
// gradient, which is a descent direction of the non-smooth Phi too.
bool ClothSolver::Impl::NewtonIterations::move_downhill(const Eigen::MatrixX3d& d) {
  auto t = Clock::now();
  bool accepted = line_search(d);
  if (!accepted) {
    // |diag|: the exact matrix's diagonal may hold a negative entry (a
    // projected one never does, where this is the diagonal itself).
    const Eigen::VectorXd diag = m_.hessian.diagonal().cwiseAbs();
    Eigen::MatrixX3d jacobi = -g_.cwiseQuotient(per_vertex(diag));
    cap_longest_move(jacobi, s_.settings_.max_displacement);
    accepted = jacobi.allFinite() && line_search(jacobi);
  }
  s_.timings_.line_search += since(t);
  return accepted;
}

bool ClothSolver::Impl::NewtonIterations::line_search(const Eigen::MatrixX3d& dir) {
  const double slope = g_.cwiseProduct(dir).sum();
  if (!(slope < 0)) return false;
  // A barrier contact bounds the step where its closest pair would come
  // too close (continuous collision detection): searching only below that
  // bound, no accepted state has crossed the body.
  double alpha = s_.max_step(x_, dir);
  if (!(alpha > 0)) return false;
  for (int k = 0; k < s_.settings_.max_line_search; ++k, alpha *= 0.5) {
    const Eigen::MatrixX3d trial = x_ + alpha * dir;
    const double phi_trial = s_.phi(trial, x_hat_);
    ++s_.timings_.line_search_trials;
    if (std::isfinite(phi_trial) && phi_trial <= phi_x_ + s_.settings_.armijo * alpha * slope) {
      x_ = trial;
      phi_x_ = phi_trial;
      return true;
    }
  }
  return false;
}

StepReport ClothSolver::step(Eigen::MatrixX3d& x, Eigen::MatrixX3d& v, double settled_below) {
  const int n = static_cast<int>(x.rows());
  if (n != masses_.size() || v.rows() != n)
    throw Error("solver: state has " + std::to_string(n) + " vertices, the garment " + std::to_string(masses_.size()));
  const double h = settings_.time_step;
  const Eigen::MatrixX3d x_start = x;
  const Eigen::MatrixX3d x_hat = x + h * v;
  // Friction lags its contacts at the step's start (Dissipation::begin_step).
  for (NamedEnergy& e : energies_)
    if (Dissipation* d = e.energy->dissipation()) d->begin_step(x_start, h);
  StepReport report;
  Impl::NewtonIterations newton(*this, x, x_hat, report);
  report.phi_end = newton.run(settled_below);
  report.max_displacement = (x - x_start).rowwise().norm().maxCoeff();
  v = (x - x_start) / h * (1.0 - settings_.damping);
  return report;
}

}  // namespace drape
