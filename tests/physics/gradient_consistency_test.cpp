// A drape that stalls names an energy whose gradient is not the derivative of
// its value (scene_detail::inconsistent_gradients): an outside tester's spring
// plugin with twice its gradient ended "not settled", blamed on the body.
#include <catch2/catch.hpp>

#include <drape/energy.hpp>
#include <drape/physics/solver.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "../../framework/src/scene/gradient_consistency.hpp"

using namespace drape;

namespace {

// k/2 |x - p|^2 summed over vertices, with its gradient scaled by `wrong`
// (1: the true gradient), plus a constant `offset` (a large energy whose
// differences must not be taken for rounding).
class Spring final : public Energy {
 public:
  Spring(double k, double wrong, double offset) : k_(k), wrong_(wrong), offset_(offset) {}
  void bind(const EnergyContext&) override {}
  double value(const Eigen::MatrixX3d& x) const override { return offset_ + 0.5 * k_ * (x.rowwise() - p_).squaredNorm(); }
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    g += wrong_ * k_ * (x.rowwise() - p_);
    return value(x);
  }
  void add_hessian(const Eigen::MatrixX3d&, Triplets&, bool) const override {}

 private:
  double k_, wrong_, offset_;
  Eigen::RowVector3d p_{0.1, 1.2, -0.05};
};

// Hangs to infinity just beyond x (a barrier one step from contact).
class Wall final : public Energy {
 public:
  void bind(const EnergyContext&) override {}
  double value(const Eigen::MatrixX3d& x) const override {
    return x(0, 1) < 1.0 ? std::numeric_limits<double>::infinity() : 1.0 / (x(0, 1) - 1.0);
  }
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    g(0, 1) += 3.0;  // wrong, but its value cannot be differenced here
    return value(x);
  }
  void add_hessian(const Eigen::MatrixX3d&, Triplets&, bool) const override {}
};

std::vector<NamedEnergy> energies(double wrong, double offset = 0) {
  std::vector<NamedEnergy> out;
  out.push_back({"gravity_like", std::make_unique<Spring>(3.0, 1.0, offset)});
  out.push_back({"spring", std::make_unique<Spring>(40.0, wrong, offset)});
  return out;
}

Eigen::MatrixX3d state() {
  Eigen::MatrixX3d x(4, 3);
  x << 0.0, 1.0, 0.0, 0.1, 1.0, 0.0, 0.0, 1.1, 0.02, 0.1, 1.1, 0.05;
  return x;
}

Eigen::MatrixX3d total_gradient(const std::vector<NamedEnergy>& list, const Eigen::MatrixX3d& x) {
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
  for (const auto& e : list) e.energy->add_gradient(x, g);
  return g;
}

}  // namespace

TEST_CASE("an energy whose gradient is twice its value's derivative is named and the others are not", "[physics]") {
  const auto list = energies(2.0);
  const Eigen::MatrixX3d x = state();
  const std::string why = scene_detail::inconsistent_gradients(list, x, total_gradient(list, x));
  CHECK_THAT(why, Catch::Contains("energy 'spring'") && Catch::Contains("not the derivative of its value") &&
                      Catch::Contains("check_energy_derivatives"));
  CHECK_THAT(why, !Catch::Contains("gravity_like"));
  // 10 % off is named too; true gradients are not, however large the energy's value (rounding).
  CHECK_THAT(scene_detail::inconsistent_gradients(energies(1.1), x, total_gradient(energies(1.1), x)),
             Catch::Contains("energy 'spring'"));
  const auto right = energies(1.0, 1e4);
  CHECK(scene_detail::inconsistent_gradients(right, x, total_gradient(right, x)).empty());
}

TEST_CASE("the gradient check says nothing where a value cannot be differenced or nothing moves", "[physics]") {
  std::vector<NamedEnergy> list;
  list.push_back({"wall", std::make_unique<Wall>()});
  Eigen::MatrixX3d x = state();
  x(0, 1) = 1.0 + 1e-8;  // 0.1 um from the wall: one step of the difference reaches it
  CHECK(scene_detail::inconsistent_gradients(list, x, total_gradient(list, x)).empty());
  const auto springs = energies(2.0);
  CHECK(scene_detail::inconsistent_gradients(springs, x, Eigen::MatrixX3d::Zero(4, 3)).empty());  // balanced: no direction
  // The wall skipped, the energies after it are still checked.
  list.push_back({"spring", std::make_unique<Spring>(40.0, 2.0, 0.0)});
  CHECK_THAT(scene_detail::inconsistent_gradients(list, x, total_gradient(list, x)),
             Catch::Contains("energy 'spring'") && !Catch::Contains("energy 'wall'"));
}
