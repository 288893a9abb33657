#pragma once
// The cloth solver: implicit (backward) Euler written as an optimisation.
//
// One time step from (x_n, v_n) minimises the incremental potential
//     Phi(x) = 1/(2 h^2) (x - x_hat)^T M (x - x_hat) + sum_i E_i(x),  x_hat = x_n + h v_n,
// whose minimiser is exactly the backward-Euler update (the inertia term is a
// mass-weighted proximal term). Newton's method on Phi with the energies'
// PSD-projected Hessians, a sparse Cholesky factorisation whose symbolic
// analysis is done once (the pattern is fixed by the garment's topology),
// and a backtracking (Armijo) line search, so Phi decreases at every accepted
// iteration. `damping` scales the velocity carried to the next step: 0 is
// plain backward Euler, 1 makes every step a quasi-static proximal step.
//
// Convergence is measured on forces: a step has converged when
// |grad Phi| <= tolerance * |W|, with |W| the norm of the garment's weight
// vector (m_v * 9.81 per vertex) -- a physical force scale that does not
// depend on which effects a scene names (zero gravity included).
#include <drape/energy.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace drape {

struct SolverSettings {
  double time_step = 0.1;          // s
  double damping = 0.2;            // fraction of the velocity dropped per step (0..1)
  // Per time step. A settling step need not be solved to its own tolerance:
  // friction's lagged normal forces and the body's contacts change at the
  // next step anyway. Measured 2026-12-02 (docs/scenes.md, "A settling
  // step's Newton budget"): 15 instead of 30 took 14 % (posed) and 20 %
  // (A-pose) fewer Newton iterations over 24 coarse drapes with friction,
  // 27 % on the six costliest A-pose drapes, 14-17 % on the default shirt
  // at BMI 35 and 45, every drape settled; 10 no cheaper than 15 and
  // closer to the settling step limit.
  int max_newton_iterations = 15;
  double tolerance = 1e-3;         // per step: |grad Phi| / |W|
  double settle_tolerance = 5e-3;  // drape done: |grad E| / |W| of the static energy
  double rest_displacement = 1e-5; // m: or done when no vertex moved farther in a step (at rest)...
  double kink_tolerance = 5e-2;    // ...and |grad E| / |W| is below this (the floor contact kinks leave)
  double kink_radius = 1e-3;       // m: radius of the gradient samples of stationarity()
  double max_displacement = 0.02;  // m, a Newton step moves no vertex farther (keeps thin parts from being crossed)
  double armijo = 1e-4;            // sufficient-decrease constant of the line search
  int max_line_search = 12;        // halvings (down to alpha = 2.4e-4) before an iteration is given up
  std::string linear_solver = "auto";  // auto | eigen | cholmod
  // Keep the last Cholesky factor (across iterations and time steps) as the
  // preconditioner of conjugate gradients; factorise anew only when PCG does
  // not reach |H d + g| <= newton_forcing |g| within max_cg_iterations.
  bool reuse_factorization = true;
  // CG applies that factor in single precision (CHOLMOD back end): a
  // preconditioner need not be exact, and the float copy's solves stream half
  // the bytes. The Newton direction is still CG's, in double, and a direct
  // solve with a fresh factor stays in double. Measured in docs/scenes.md.
  bool float_preconditioner = true;
  double newton_forcing = 1e-3;
  int max_cg_iterations = 20;
  // Below this step residual (|grad Phi| / |W|) an iteration first tries the
  // exact Newton matrix, the energies' Hessians without the per-element PSD
  // projection, and keeps it when it is positive definite. Near an
  // equilibrium the sum is usually definite although single elements are not
  // (a compressed face, a bent hinge under load, a barrier pair near a body
  // edge), and projecting each element changes the matrix enough that Newton
  // converges only linearly, ~8 % per iteration (docs/scenes.md). When the
  // exact matrix is indefinite the projected one is used. 0 turns it off.
  double exact_hessian_below = 1.0;
  // Try PCG with the kept factor and the exact matrix by what they have been
  // saving: after a PCG attempt that stopped at max_cg_iterations, or an
  // exact matrix found indefinite, skip the next tries for a while (ClothSolver::Impl).
  // false: try them at every iteration, the solver of 2026-11-28 (docs/scenes.md).
  bool adaptive_tries = true;
};

// An energy term with the name its scene gave it.
struct NamedEnergy {
  std::string name;
  std::unique_ptr<Energy> energy;
};

struct EnergyTerm {
  std::string name;
  double value = 0;
};

struct StepReport {
  int iterations = 0;             // Newton iterations taken
  int line_search_failures = 0;   // iterations whose line search found no decrease
  double residual = 0;            // |grad Phi| / |W| at the end
  double phi_start = 0, phi_end = 0;
  double max_displacement = 0;    // m, the farthest any vertex moved in the step
  bool converged = false;
  bool settled = false;           // ended early: the static forces balanced (step's settled_below)
};

class ClothSolver {
 public:
  // Energies must already be bound (to the same garment). Masses for the
  // inertia term come from the garment's material-space areas and densities.
  ClothSolver(const Garment& garment, std::vector<NamedEnergy>& energies, SolverSettings settings);
  ~ClothSolver();
  ClothSolver(const ClothSolver&) = delete;
  ClothSolver& operator=(const ClothSolver&) = delete;

  // One backward-Euler step: updates x and v in place. With settled_below > 0
  // the step also ends, at any Newton iteration, as soon as the static forces
  // balance to that tolerance (|grad E + friction's push| / |W|, an upper
  // bound of stationarity()): a settling drape stops where it settles
  // instead of finishing a step it no longer needs.
  StepReport step(Eigen::MatrixX3d& x, Eigen::MatrixX3d& v, double settled_below = 0);

  // Static energy sum_i E_i(x), its gradient's relative norm |grad E| / |W|, and the terms.
  double energy(const Eigen::MatrixX3d& x, std::vector<EnergyTerm>* terms = nullptr) const;
  double static_residual(const Eigen::MatrixX3d& x) const;
  // grad E per vertex (N): the unbalanced force on each vertex, negated.
  Eigen::MatrixX3d static_gradient(const Eigen::MatrixX3d& x) const;
  // Stationarity of the non-smooth static energy, relative to |W|: like
  // static_residual, but a vertex touched by a non-smooth energy (the exact
  // contact, whose push jumps between two faces of a body crease) counts the
  // smallest unbalanced force over the convex hull of that energy's gradients
  // at its position and `radius` around it (Energy::vertex_gradient_samples):
  // Goldstein's epsilon-subdifferential, the stationarity of gradient sampling
  // methods (Burke, Lewis & Overton 2005). At a crease the cloth is balanced
  // by the sum of both faces' pushes, which no single closest face gives; on
  // smooth parts it equals the plain residual.
  double stationarity(const Eigen::MatrixX3d& x, double radius) const;
  // With friction: whether some contact still slides at x (Dissipation::slip_ratio);
  // stationarity counts friction's push, so a drape has settled only when
  // its stationarity is small and nothing slides.
  bool sliding(const Eigen::MatrixX3d& x) const { return slip_ratio(x) >= 1; }
  // The fastest contact's slip in the last step relative to the slip friction
  // holds (Dissipation::slip_ratio); 0 without friction.
  double slip_ratio(const Eigen::MatrixX3d& x) const;

  // The largest fraction in [0, 1] of the move x -> x + dx (and of the body's
  // from -> to, when given) that every energy allows (Energy::max_step): 1
  // without a barrier contact.
  double max_step(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, const Eigen::MatrixX3d* body_from = nullptr,
                  const Eigen::MatrixX3d* body_to = nullptr) const;

  const Eigen::VectorXd& masses() const { return masses_; }
  double force_scale() const { return force_scale_; }
  const SolverSettings& settings() const { return settings_; }
  // Changes the Newton budget per step (the morph needs fewer than the settling).
  void set_max_newton_iterations(int n) { settings_.max_newton_iterations = std::max(1, n); }
  // The linear solver in use ("eigen" or "cholmod").
  std::string linear_solver() const;

  struct Timings {
    double gradient = 0, hessian = 0, assembly = 0, linear_solves = 0, line_search = 0;  // s; linear solves: factorisations and PCG
    double collision_checks = 0;  // s: continuous collision checks (part of line_search; also the morph's body moves)
    int factorizations = 0;
    long cg_iterations = 0;  // PCG iterations of the steps solved with an earlier factor
    int exact_steps = 0;     // Newton iterations that used the exact (unprojected) matrix
    int exact_refused = 0;   // iterations whose exact matrix was tried and found indefinite
    int exact_skipped = 0;   // iterations below exact_hessian_below that did not try it, as it was refused just before
    int cg_attempts = 0, cg_failures = 0;  // PCG solves with the kept factor, and those that reached max_cg_iterations
    int cg_skipped = 0;      // iterations that factorised without trying PCG, as the last attempts had failed
    long line_search_trials = 0;  // energy evaluations of the line search (1 per iteration when full steps pass)
  };
  const Timings& timings() const { return timings_; }

  struct Impl;

 private:
  double phi(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& x_hat) const;
  const Garment& garment_;
  std::vector<NamedEnergy>& energies_;
  SolverSettings settings_;
  Eigen::VectorXd masses_;
  double force_scale_ = 1;
  mutable Timings timings_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace drape
