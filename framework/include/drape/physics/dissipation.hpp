#pragma once
// A dissipative potential lagged per time step: friction, after IPC's lagged
// friction (Li et al. 2020, section 5). It is its own potential, as IPC
// Toolkit's FrictionPotential and polyfem's FrictionForm are, built by the
// contact energy whose contacts it lags (the barrier with a friction
// coefficient: Energy::dissipation). begin_step fixes what D lags at the start
// of each time step (the contacts at x_start, their normal forces, tangent
// planes and closest points); D(x) is then a smooth convex function of the
// step's move that the solver adds to the step's incremental potential. It is
// no part of the stored energy: the drape's energies do not include it. Before
// the first begin_step (and in `drape optimize`, which takes no time steps) D
// is 0.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace drape {

class Dissipation {
 public:
  virtual ~Dissipation() = default;
  virtual void begin_step(const Eigen::MatrixX3d& x_start, double time_step) = 0;
  virtual double value(const Eigen::MatrixX3d& x) const = 0;
  // Adds dD/dx to g ([V, 3]).
  virtual void add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const = 0;
  // Its Hessian's entries with row >= column (positive semidefinite by construction).
  virtual void add_hessian_lower(const Eigen::MatrixX3d& x, std::vector<Eigen::Triplet<double>>& h) const = 0;
  // The largest slip of the lagged contacts at x, relative to the slip that
  // friction still holds (the static regime): 1 or more while some contact
  // slides (kinetic friction), below 1 when friction holds every contact.
  // A drape with friction has settled only when nothing slides.
  virtual double slip_ratio(const Eigen::MatrixX3d& x) const = 0;
};

}  // namespace drape
