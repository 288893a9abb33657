#pragma once
// Whether each energy's gradient is the derivative of its value, checked
// where a drape stalled: a plugin whose add_gradient is not the derivative of
// its value() sends Newton along a direction the line search then finds no
// decrease in, and the run ends "not settled" with nothing pointing at the
// plugin (an outside tester's spring with twice its gradient was blamed on
// the body). Cheap: two values of each energy at two steps.
#include <drape/physics/solver.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape::scene_detail {

// "; energy 'spring': its gradient is not the derivative of its value (...)"
// for each energy whose directional derivative along `direction` (the
// unbalanced force; scaled here so its largest vertex move is 1) differs
// from its value's central difference by more than 5 %, at two step lengths
// (a kink in the energy moves the difference with the step, a wrong gradient
// does not), beyond the difference's rounding; "" when all agree.
std::string inconsistent_gradients(const std::vector<NamedEnergy>& energies, const Eigen::MatrixX3d& x,
                                   const Eigen::MatrixX3d& direction);

}  // namespace drape::scene_detail
