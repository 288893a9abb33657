#pragma once
// The far side of a crease. Where an arm meets the torso, a garment vertex in
// the armpit has body on two sides, both within the margin. The one-sided
// penalty sees only the nearer side: its energy is the larger of the two
// sides' penalties, which has a kink where the sides are equally near, and the
// cloth squeezed into the crease has no smooth equilibrium (Newton stalls with
// the vertex flipping between the sides: the drapes at BMI 61.5 and 65 that
// did not settle). So, besides the nearest point, the collision energy also
// pushes off far points: the nearest point on the body's faces that face
// another way (the groups of normal_groups.hpp), and the nearest point on each
// face across an edge of the near face (a fold milder than a group's spread):
//
//   E_v = a_v k [ phi(margin - d1) + w(c) g(d1) g(d2) phi(margin - d2) ]
//
// d1 the signed distance to the body (the usual term), d2 the signed distance
// to the far point (one term per far point). w counts the
// far side only where the two points face each other across a concave crease:
// c = n1 . (q2 - q1) / |q2 - q1|, the sine of how far the far point q2 rises
// above the near point's tangent plane (n1 the near normal). Across a 90 degree
// crease c is 0.71 for a vertex on the bisector; where an arm continues
// smoothly into the shoulder the two points lie side by side on one surface
// and c is 0 (or negative where the seam is convex), and the far side, which is
// just the same skin seen again, must not push twice. w rises smoothly (C2)
// between the two c of a CreaseRamp: for the far wall from 0 at c = 0.2,
// above the faceting of the body mesh, to 1 at c = 0.5; for a face across an
// edge from 0 at c = 0 (flat) to 1 at c = 0.2. Where w = 1 on the bisector
// the energy is smooth there; a partial w leaves (1 - w) of the kink.
// g(d) rises the same way, for the far wall from 0 at d = -margin to 1 at d = 0 (for a
// face across an edge from 0 at d = 0 to 1 at a quarter margin): the term pushes
// a vertex in the gap between the sides and fades out as it enters the body,
// where the near side's penalty takes over (a vertex deep inside one part may
// be anywhere relative to the other's open surface). So the far point matters
// only within the margin of the vertex, and is searched no further.
//
// The energy is continuous: where the nearest group changes the two terms swap,
// and at equal distances c is the same seen from either side. Its gradient and
// Hessian are exact: both closest points move linearly with the vertex on the
// feature they lie on (ClosestPoint::slide), and the rest is a chain
// of elementary functions differentiated by drape::Dual<3> (drape/dual.hpp).
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

  CreaseTerm& operator+=(const CreaseTerm& other) {
    value += other.value;
    gradient += other.gradient;
    hessian += other.hessian;
    return *this;
  }
};

// Where a far term counts: its weight w rises with c from `from` to `full`,
// and its gap factor with each signed distance from gap_from to gap_full
// margins.
struct CreaseRamp {
  double from, full;
  double gap_from, gap_full;
};
// The far wall found outside the near face's normal group: above the faceting
// of the body mesh, whose smooth skin seen again from a group's border must
// not push twice; it fades out over one margin inside either wall.
constexpr CreaseRamp kFarWallRamp{0.2, 0.5, -1.0, 0.0};
// A face across an edge of the near face: a crease between two adjacent faces
// is milder than the groups' spread (their normals can be 23 degrees apart in
// one group, c = sin(angle / 2) = 0.2 on the bisector), so it counts fully
// from there; on flat skin c = 0 and nothing is added, and across a convex
// edge c < 0. It fades out towards the skin, over the first quarter margin:
// c climbs from 0 to its value on the bisector across a wedge whose width is
// proportional to the distance, so w's gradient would grow like 1 / d there
// (the cost: the kink is left whole within a quarter margin of the skin).
constexpr CreaseRamp kNeighbourRamp{0.0, 0.2, 0.0, 0.25};

// The far side's term for a vertex at p with near point `near` and far point
// `far`; coefficient = a_v k. Zero where the far point is beyond the margin or
// the two do not face each other.
CreaseTerm crease_term(const Eigen::Vector3d& p, const ClosestPoint& near, const ClosestPoint& far,
                       const CubicPenalty& penalty, double coefficient, CreaseRamp ramp);

}  // namespace drape::collision
