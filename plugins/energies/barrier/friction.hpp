#pragma once
// The barrier's friction as its own potential (physics/dissipation.hpp): IPC's
// lagged friction over the barrier's pairs (barrier.hpp says what D is).
// Nested in BarrierContact, so it reads the pairs, contacts and settings.
#include "barrier.hpp"

#include <drape/physics/dissipation.hpp>

#include <vector>

namespace drape::barrier {

class BarrierContact::Friction final : public Dissipation {
 public:
  explicit Friction(const BarrierContact& barrier) : barrier_(barrier) {}
  void begin_step(const Eigen::MatrixX3d& x_start, double time_step) override;
  double value(const Eigen::MatrixX3d& x) const override;
  void add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override;
  void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h) const override;
  double slip_ratio(const Eigen::MatrixX3d& x) const override;

 private:
  // A contact's friction, lagged at the step's start.
  struct LaggedContact {
    Contact contact;
    Eigen::Matrix<double, 3, 2> tangent;  // orthonormal basis of the plane normal to contact.normal
    double limit = 0;                     // mu lambda, N
  };
  // The slip u of a contact at x (2-vector in its tangent plane).
  Eigen::Vector2d slip(const LaggedContact& c, const Eigen::MatrixX3d& x) const;

  const BarrierContact& barrier_;
  Eigen::MatrixX3d x_start_;
  double epsilon_ = 0;  // m: eps_v h
  std::vector<LaggedContact> contacts_;
};

}  // namespace drape::barrier
