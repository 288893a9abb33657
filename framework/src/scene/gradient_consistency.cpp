// inconsistent_gradients (gradient_consistency.hpp).
#include "gradient_consistency.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace drape::scene_detail {
namespace {

// The central difference's steps: a tenth of a micrometre and half that
// for the largest vertex move. Far below the barrier's 1 mm activation
// distance and the mesh's edges, far above rounding for energies of a few
// joules (rounding: about 1e-16 J / 1e-7 m = 1e-9 N).
constexpr double kSteps[] = {1e-7, 5e-8};
constexpr double kDisagreement = 0.05;

}  // namespace

std::string inconsistent_gradients(const std::vector<NamedEnergy>& energies, const Eigen::MatrixX3d& x,
                                   const Eigen::MatrixX3d& direction) {
  const double longest = direction.rows() > 0 ? direction.rowwise().norm().maxCoeff() : 0.0;
  if (!(longest > 0) || !std::isfinite(longest)) return "";
  const Eigen::MatrixX3d d = direction / longest;
  std::string out;
  for (const NamedEnergy& e : energies) {
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
    e.energy->add_gradient(x, g);
    const double slope = (g.array() * d.array()).sum();
    bool disagrees = std::isfinite(slope);
    double difference = 0;
    for (const double h : kSteps) {
      if (!disagrees) break;
      const double up = e.energy->value(x + h * d), down = e.energy->value(x - h * d);
      // (A barrier's infinity one step away, or a plugin's NaN: nothing to compare for this energy; the others still are.)
      if (!std::isfinite(up) || !std::isfinite(down)) {
        disagrees = false;
        break;
      }
      difference = (up - down) / (2 * h);
      const double rounding = 64 * std::numeric_limits<double>::epsilon() * (std::abs(up) + std::abs(down)) / (2 * h);
      disagrees = disagrees && std::abs(slope - difference) > kDisagreement * std::max(std::abs(slope), std::abs(difference)) + rounding;
    }
    if (!disagrees) continue;
    char line[400];
    std::snprintf(line, sizeof line,
                  "; energy '%s': its gradient is not the derivative of its value (along the unbalanced force its "
                  "gradient gives a slope of %.4g N, its value's central difference %.4g N), so Newton's steps go "
                  "where the energy does not fall: check its add_gradient against its value "
                  "(drape::check_energy_derivatives, <drape/gradcheck.hpp>)",
                  e.name.c_str(), slope, difference);
    out += line;
  }
  return out;
}

}  // namespace drape::scene_detail
