#pragma once
// The one-sided penalty of the body collision energy as a function of the
// penetration into the margin, delta = margin - signed distance (meters):
//
//   phi(delta) = 0                                        delta <= 0
//              = delta^3 / 3                              0 < delta <= delta_max
//              = delta_max^3 / 3 + delta_max^2 (delta - delta_max)   delta > delta_max
//
// The cubic is PBNS/SNUG's collision term (Bertiche et al. 2021, Santesteban et
// al. 2022: max(eps - d, 0)^3); it is C^2 at delta = 0, so Newton sees no jump
// when a vertex enters the margin. The optional linear tail (delta_max = margin
// + max_depth) caps the push of a vertex deeper than max_depth at the value it
// has there: see body_collision.hpp for why. It is C^1 at delta_max.
#include <limits>

namespace drape::collision {

struct CubicPenalty {
  double margin = 0;                                          // m
  double delta_max = std::numeric_limits<double>::infinity();  // m: margin + max_depth

  // delta for a signed distance d (positive: inside the margin).
  double delta(double d) const { return margin - d; }
  double value(double delta) const {
    if (delta <= 0) return 0;
    if (delta <= delta_max) return delta * delta * delta / 3;
    return delta_max * delta_max * (delta_max / 3 + (delta - delta_max));
  }
  // d phi / d delta: the pressure per unit stiffness.
  double slope(double delta) const {
    if (delta <= 0) return 0;
    return delta <= delta_max ? delta * delta : delta_max * delta_max;
  }
  // d^2 phi / d delta^2 (>= 0: phi is convex in delta).
  double curvature(double delta) const { return delta > 0 && delta <= delta_max ? 2 * delta : 0; }
};

}  // namespace drape::collision
