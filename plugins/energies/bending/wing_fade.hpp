#pragma once
// A smooth weight that switches a hinge's bending off as one of its wings
// collapses, with its exact first and second derivatives.
//
// Why: theta's derivatives grow like 1/h and 1/h^2 as a wing's height h over
// the hinge edge goes to 0 (dihedral_angle.hpp). A triangle crushed flat (the
// armpit of a shirt far too small for the body) then pulled with ~5e6 N on one
// vertex and wrecked the Newton solve, though nothing physical asks a
// collapsed wing to bend: stretching is what resists the collapse. So the
// bending energy is multiplied by
//   w = s(r0) s(r1),  r_i = h_i / H_i,  s(r) = 10 r^3 - 15 r^4 + 6 r^5 (r < 1), 1 (r >= 1),
// with H_i a fraction kFadeFraction of wing i's rest (UV) height. s is C2, so
// the product is still a potential with exact derivatives, and s ~ 10 r^3 at 0
// makes w dtheta ~ h^2, w d2theta ~ h and even w d3theta bounded. The cubic
// start matters: with 3 r^2 - 2 r^3 (until 2026-11-26) the third derivatives
// still grew like 1/h, and the MakeHuman shirt at BMI 36, an armpit face
// crushed to 2 % of its height, had its bending energy change curvature
// within 2 micrometres: Newton's iterates cycled there (stationarity 0.10),
// while with the cubic start it settles (8.5e-3).
//
// The height of a wing (tip x_tip, edge e = x1 - x0, a = x_tip - x0) is h = |p|,
// p = a - t e its offset from the edge line, t = (a . e) / |e|^2; computed as
// |e x a| / |e|. With p^ = p / h and b^ = (e x a) / |e x a| the wing normal:
//   dh/da = p^, dh/de = -t p^, i.e. by vertex (x0, x1, x_tip):
//     dh = (-(1 - t) p^, -t p^, p^).
//   d2h = v v^T / h + (h / |e|^2) g g^T - (dt g^T + g dt^T), where
//     v  = (-(1 - t) b^, -t b^, b^)   (b^ . dp, the motion out of the wing's plane),
//     g  = (-p^, p^, 0)               (p^ . de),
//     dt = (-(e + a - 2 t e), a - 2 t e, e) / |e|^2.
// From d2|p| = dp^T (I - p^ p^^T) dp / h + p^ . d2p: I - p^ p^^T = e^ e^^T +
// b^ b^^T; e^ . dp = -(h / |e|) p^ . de since p . e = 0; b^ . dp = b^ . (da - t de);
// and p^ . d2p = -2 dt (p^ . de), symmetrised, since d2p = -(e d2t + 2 dt de).
//
// In s' d2r the 1/h of d2h meets s'(r) = 30 r^2 (1 - r)^2: their product,
// 30 r (1 - r)^2 / H^2, is formed without dividing by h, so heights down to the
// smallest doubles stay finite. At h = 0 exactly w and its gradient vanish;
// the Hessian, whose limit there depends on the direction of approach, is
// reported as zero too.
#include <Eigen/Core>

#include <algorithm>
#include <cmath>

#include "dihedral_angle.hpp"

namespace drape::bending {

using dihedral::Mat12;
using dihedral::Vec12;

// Wings above this fraction of their rest height bend as before, bit for bit:
// a drape that does not crush triangles never gets near it (wings at 10 % of
// their height mean a 90 % compression), and below it the bending that is
// faded out is the one that made the 1/h forces.
constexpr double kFadeFraction = 0.1;

// (x0, x1, x_tip)'s 3-vectors placed at vertices (0, 1, tip) of the hinge's 12 dofs.
inline Vec12 by_vertex(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& vt, int tip) {
  Vec12 r = Vec12::Zero();
  r.segment<3>(0) = v0;
  r.segment<3>(3) = v1;
  r.segment<3>(3 * tip) = vt;
  return r;
}

// One wing's factor s(r) and, up to `order`, its 12-dof gradient and Hessian.
// H is the wing's fade height; tip is 2 (wing 0) or 3 (wing 1).
struct WingFactor {
  double s = 1.0;
  Vec12 ds = Vec12::Zero();
  Mat12 d2s = Mat12::Zero();

  WingFactor(const Eigen::Vector3d& e, const Eigen::Vector3d& a, double H, int tip, int order) {
    const double e2 = e.squaredNorm();
    const Eigen::Vector3d n = e.cross(a);
    // Outside the fade (H = 0: never faded; |e| = 0: the old degenerate hinge),
    // by the same test as faded() so the two agree to the last bit.
    if (n.squaredNorm() >= H * H * e2) return;
    const double nn = n.norm();
    if (!(nn > 0.0)) {
      s = 0.0;  // collapsed: no bending, no derivatives
      return;
    }
    const double h = nn / std::sqrt(e2);
    const double r = std::min(h / H, 1.0);  // the rounding of h, not the test, may reach 1
    s = r * r * r * (10.0 + r * (6.0 * r - 15.0));
    if (order < 1) return;
    const double len = std::sqrt(e2), t = a.dot(e) / e2;
    const Eigen::Vector3d b = n / nn, p = b.cross(e / len);
    const double ds_dr = 30.0 * r * r * (1.0 - r) * (1.0 - r);
    const Vec12 dh = by_vertex(-(1.0 - t) * p, -t * p, p, tip);
    ds = (ds_dr / H) * dh;
    if (order < 2) return;
    const Vec12 v = by_vertex(-(1.0 - t) * b, -t * b, b, tip);
    const Vec12 g = by_vertex(-p, p, Eigen::Vector3d::Zero(), tip);
    const Eigen::Vector3d dt1 = (a - 2.0 * t * e) / e2, dtt = e / e2;
    const Vec12 dt = by_vertex(-(dt1 + dtt), dt1, dtt, tip);
    // s'' dr dr^T + s' d2h / H, the v v^T / h term as 30 r (1 - r)^2 / H^2.
    d2s = (60.0 * r * (1.0 - r) * (1.0 - 2.0 * r) / (H * H)) * dh * dh.transpose() +
          (30.0 * r * (1.0 - r) * (1.0 - r) / (H * H)) * v * v.transpose() +
          (ds_dr / H) * ((h / e2) * g * g.transpose() - dt * g.transpose() - g * dt.transpose());
  }
};

// w = s(r0) s(r1) over a hinge and, up to `order`, its gradient and Hessian.
struct Fade {
  double w;
  Vec12 dw;
  Mat12 d2w;

  Fade(const dihedral::Hinge& hinge, const double H[2], int order) {
    const WingFactor f0(hinge.e, hinge.a0, H[0], 2, order), f1(hinge.e, hinge.a1, H[1], 3, order);
    w = f0.s * f1.s;
    if (order >= 1) dw = f1.s * f0.ds + f0.s * f1.ds;
    if (order >= 2) d2w = f1.s * f0.d2s + f0.s * f1.d2s + f0.ds * f1.ds.transpose() + f1.ds * f0.ds.transpose();
  }
};

// Whether some wing is below its fade height (h^2 |e|^2 = |N|^2 < H^2 |e|^2),
// from the quantities the angle needs anyway: the cheap test that keeps
// unfaded hinges on their old path.
inline bool faded(const dihedral::Hinge& hinge, const double H[2]) {
  return !(hinge.q0 >= H[0] * H[0] * hinge.e2 && hinge.q1 >= H[1] * H[1] * hinge.e2);
}

}  // namespace drape::bending
