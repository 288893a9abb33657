#include "crease_penalty.hpp"

#include <drape/dual.hpp>

namespace drape::collision {
namespace {

// Value, gradient and Hessian with respect to the vertex's position.
using Dual3 = Dual<3>;
using Dual3Vector = Vec3<Dual3>;

// Below this (m) a direction from one point to the other is not defined; the
// term is left out there (a vertex exactly on the skin, or both closest points
// on the same edge of a seam, where it is zero on every side anyway).
constexpr double kTiny = 1e-9;

// q(p') = point + slide (p' - p) around p: value, gradient, zero Hessian.
Dual3Vector moving_point(const ClosestPoint& q) {
  Dual3Vector out;
  for (int i = 0; i < 3; ++i) out[static_cast<std::size_t>(i)] = {q.point[i], q.slide.row(i).transpose(), Eigen::Matrix3d::Zero()};
  return out;
}

// 6t^5 - 15t^4 + 10t^3 on [0, 1]: 0 and 1 with zero first and second derivatives at the ends.
Dual3 smoother_step(const Dual3& t) {
  if (t.v <= 0) return Dual3::constant(0);
  if (t.v >= 1) return Dual3::constant(1);
  const double x = t.v;
  return chain(t, x * x * x * (x * (6 * x - 15) + 10), 30 * x * x * (x - 1) * (x - 1), 60 * x * (x - 1) * (2 * x - 1));
}

}  // namespace

CreaseTerm crease_term(const Eigen::Vector3d& p, const ClosestPoint& near, const ClosestPoint& far,
                       const CubicPenalty& penalty, double coefficient, CreaseRamp ramp) {
  CreaseTerm out;
  // The gap factor rises from d = gap_lo to gap_lo + gap_width (see the header).
  const double gap_lo = ramp.gap_from * penalty.margin, gap_width = (ramp.gap_full - ramp.gap_from) * penalty.margin;
  const double far_distance = far.sign * (p - far.point).norm();
  const double near_distance = near.sign * (p - near.point).norm();
  if (!(penalty.delta(far_distance) > 0) || !(far_distance > gap_lo) || !(near_distance > gap_lo)) return out;
  const Eigen::Vector3d chord0 = far.point - near.point, offset0 = p - near.point;
  if (chord0.norm() < kTiny || offset0.norm() < kTiny) return out;
  // A cheap test with plain doubles first: most contacts are not in a crease.
  const double c0 = near.sign * chord0.dot(offset0) / (chord0.norm() * offset0.norm());
  if (!(c0 > ramp.from)) return out;

  Dual3Vector x;
  for (int i = 0; i < 3; ++i) x[static_cast<std::size_t>(i)] = Dual3::variable(p[i], i);
  const Dual3Vector q1 = moving_point(near), q2 = moving_point(far);
  const Dual3Vector chord = q2 - q1, offset1 = x - q1, offset2 = x - q2;
  const Dual3 r1 = sqrt(dot(offset1, offset1));  // |d1|
  const Dual3 c = near.sign * (dot(chord, offset1) / (sqrt(dot(chord, chord)) * r1));
  const Dual3 w = smoother_step((1.0 / (ramp.full - ramp.from)) * (c - Dual3::constant(ramp.from)));
  const Dual3 d1 = near.sign * r1, d2 = far.sign * sqrt(dot(offset2, offset2));
  const Dual3 in_gap = smoother_step((1 / gap_width) * (d1 - Dual3::constant(gap_lo))) *
                       smoother_step((1 / gap_width) * (d2 - Dual3::constant(gap_lo)));
  const Dual3 delta = Dual3::constant(penalty.margin) - d2;
  const Dual3 phi = chain(delta, penalty.value(delta.v), penalty.slope(delta.v), penalty.curvature(delta.v));
  const Dual3 term = coefficient * (w * in_gap * phi);
  out.value = term.v;
  out.gradient = term.g;
  out.hessian = term.h;
  return out;
}

}  // namespace drape::collision
