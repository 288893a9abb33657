#pragma once
// The far side of a crease. Where an arm meets the torso, a garment vertex in
// the armpit has body on two sides, both within the margin. The one-sided
// penalty sees only the nearer side: its energy is the larger of the two
// sides' penalties, which has a kink where the sides are equally near, and the
// cloth squeezed into the crease has no smooth equilibrium (Newton stalls with
// the vertex flipping between the sides: the drapes at BMI 61.5 and 65 that
// did not settle). So, besides the nearest point, the collision energy also
// pushes off the nearest point on the body's faces that face another way (the
// groups of normal_groups.hpp):
//
//   E_v = a_v k [ phi(margin - d1) + w(c) g(d1) g(d2) phi(margin - d2) ]
//
// d1 the signed distance to the body (the usual term), d2 the signed distance
// to the faces outside the normal group of d1's closest face. w counts the
// far side only where the two points face each other across a concave crease:
// c = n1 . (q2 - q1) / |q2 - q1|, the sine of how far the far point q2 rises
// above the near point's tangent plane (n1 the near normal). Across a 90 degree
// crease c is 0.71 for a vertex on the bisector; where an arm continues
// smoothly into the shoulder the two points lie side by side on one surface
// and c is 0 (or negative where the seam is convex), and the far side, which is
// just the same skin seen again, must not push twice. w rises smoothly (C2)
// from 0 at c = 0.2, above the faceting of the body mesh, to 1 at c = 0.5.
// g(d) rises the same way from 0 at d = -margin to 1 at d = 0: the term pushes
// a vertex in the gap between the sides and fades out as it enters the body,
// where the near side's penalty takes over (a vertex deep inside one part may
// be anywhere relative to the other's open surface). So the far point matters
// only within the margin of the vertex, and is searched no further.
//
// The energy is continuous: where the nearest group changes the two terms swap,
// and at equal distances c is the same seen from either side. Its gradient and
// Hessian are exact: both closest points move linearly with the vertex on the
// feature they lie on (ClosestPoint::slide), and the rest is a chain
// of elementary functions differentiated by Dual2.
#include "dual2.hpp"
#include "penalty.hpp"

#include <Eigen/Core>

namespace drape::collision {

// A closest body point and how it moves with the query point (dq/dp).
struct ClosestPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Matrix3d slide = Eigen::Matrix3d::Zero();
  double sign = 1;  // +1 outside the surface, -1 inside
};

struct CreaseTerm {
  double value = 0;  // J
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();  // exact, not projected
};

// c of the header where w starts to rise, and where it reaches 1.
constexpr double kCreaseFrom = 0.2, kCreaseFull = 0.5;

// The far side's term for a vertex at p with near point `near` and far point
// `far`; coefficient = a_v k. Zero where the far point is beyond the margin or
// the two do not face each other.
CreaseTerm crease_term(const Eigen::Vector3d& p, const ClosestPoint& near, const ClosestPoint& far,
                       const CubicPenalty& penalty, double coefficient);

}  // namespace drape::collision
