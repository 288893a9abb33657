#pragma once
// The signed dihedral angle of a hinge and its exact first and second
// derivatives with respect to the 12 coordinates of its four vertices.
//
// The hinge is the edge x0 -> x1 with the wing x2 (face (x0, x1, x2)) on one
// side and x3 on the other. With e = x1 - x0, a0 = x2 - x0, a1 = x3 - x0 and
// the wing normals N0 = e x a0, N1 = a1 x e (both the normal of a consistently
// oriented mesh, whatever orientation the faces are stored with),
//   theta = atan2(e^ . (N1 x N0), N0 . N1)   (e^ = e / |e|),
// zero when flat, +-pi when folded shut, positive when the wings turn towards
// the side their normals point to. atan2 of the unnormalised quantities is
// accurate over the whole range, near 0 and near +-pi alike.
//
// Gradient (Bridson, Marino & Fedkiw 2003; Tamstorf & Grinspun 2013): with the
// wing vectors u_i = n_i / h_i = N_i |e| / |N_i|^2 (h_i the wing's height over
// the edge) and t_i = (a_i . e) / |e|^2 (where the wing tip projects on the edge),
//   dtheta/dx2 = u0, dtheta/dx3 = u1,
//   dtheta/dx0 = -(1 - t0) u0 - (1 - t1) u1,  dtheta/dx1 = -t0 u0 - t1 u1.
// Hessian: differentiating those expressions needs only du_i and dt_i, which
// follow from dN = de x a + e x da, d|e| = e^ . de, d|N|^2 = 2 N . dN:
//   du/dN = |e| / |N|^2 (I - 2 n n^T),  du/d|e| = N / |N|^2,
//   dt/da = e / |e|^2,  dt/de = (a - 2 t e) / |e|^2.
// This is the same Hessian as Tamstorf & Grinspun's closed form, organised as
// a product rule.
//
// A wing whose height is below 1e-10 of the edge length (or a collapsed edge)
// has no normal: the angle is still finite (atan2 of ~0), but the derivatives
// are reported as zero (`degenerate`) instead of overflowing.
#include <Eigen/Core>

#include <cmath>

namespace drape::dihedral {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

struct Hinge {
  Eigen::Vector3d e, a0, a1, n0, n1;  // n0, n1 unnormalised wing normals N0, N1
  double e2 = 0.0;                     // |e|^2
  double q0 = 0.0, q1 = 0.0;           // |N0|^2, |N1|^2

  Hinge(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2, const Eigen::Vector3d& x3)
      : e(x1 - x0), a0(x2 - x0), a1(x3 - x0) {
    n0 = e.cross(a0);
    n1 = a1.cross(e);
    e2 = e.squaredNorm();
    q0 = n0.squaredNorm();
    q1 = n1.squaredNorm();
  }
  // sin(theta) |N0| |N1| |e| and cos(theta) |N0| |N1| |e|: no division, so a
  // collapsed edge or wing gives atan2(0, 0) = 0 rather than NaN.
  double angle() const { return std::atan2(e.dot(n1.cross(n0)), std::sqrt(e2) * n0.dot(n1)); }
  bool degenerate() const {
    const double limit = 1e-20 * e2 * e2;  // |N|^2 = h^2 |e|^2 <= (1e-10 |e|)^2 |e|^2
    return !(q0 > limit) || !(q1 > limit);
  }
};

// One wing's u = N |e| / |N|^2 and t = (a . e) / |e|^2 (all the gradient needs).
struct Wing {
  Eigen::Vector3d u;
  double t;
  Wing(const Eigen::Vector3d& e, const Eigen::Vector3d& a, const Eigen::Vector3d& n, double q, double e2)
      : u(n * (std::sqrt(e2) / q)), t(a.dot(e) / e2) {}
};

// The derivatives of a wing's u and t with respect to the edge vector e and the
// wing vector a (what the Hessian needs besides u and t). `sign` is +1 when
// N = e x a (wing 0) and -1 when N = a x e (wing 1).
struct WingDerivatives {
  Eigen::Matrix3d du_de, du_da;
  Eigen::Vector3d dt_de, dt_da;

  WingDerivatives(const Wing& w, const Eigen::Vector3d& e, const Eigen::Vector3d& a, const Eigen::Vector3d& n, double q,
                  double e2, double sign) {
    const double len = std::sqrt(e2);
    // du/dN = |e|/q (I - 2 N N^T / q); dN/de = -sign [a]x, dN/da = sign [e]x.
    const Eigen::Matrix3d du_dn = (len / q) * (Eigen::Matrix3d::Identity() - (2.0 / q) * n * n.transpose());
    du_de = -sign * du_dn * cross_matrix(a) + n * (e.transpose() / (len * q));
    du_da = sign * du_dn * cross_matrix(e);
    dt_da = e / e2;
    dt_de = (a - 2.0 * w.t * e) / e2;
  }
};

// dtheta/dx over (x0, x1, x2, x3).
inline Vec12 gradient(const Wing& w0, const Wing& w1) {
  Vec12 g;
  g.segment<3>(0) = -(1.0 - w0.t) * w0.u - (1.0 - w1.t) * w1.u;
  g.segment<3>(3) = -w0.t * w0.u - w1.t * w1.u;
  g.segment<3>(6) = w0.u;
  g.segment<3>(9) = w1.u;
  return g;
}

// d2theta/dx2 over (x0, x1, x2, x3), symmetric.
inline Mat12 hessian(const Wing& w0, const WingDerivatives& d0, const Wing& w1, const WingDerivatives& d1) {
  // Derivatives of u_i and t_i by vertex: x_tip enters through a, x1 through e,
  // x0 through both (a = x_tip - x0, e = x1 - x0). Wing 0's tip is x2, wing 1's x3.
  Eigen::Matrix3d du[2][4];
  Eigen::Vector3d dt[2][4];
  const Wing* wing[2] = {&w0, &w1};
  const WingDerivatives* d[2] = {&d0, &d1};
  for (int i = 0; i < 2; ++i) {
    du[i][0] = -(d[i]->du_de + d[i]->du_da);
    du[i][1] = d[i]->du_de;
    du[i][2] = du[i][3] = Eigen::Matrix3d::Zero();
    du[i][2 + i] = d[i]->du_da;
    dt[i][0] = -(d[i]->dt_de + d[i]->dt_da);
    dt[i][1] = d[i]->dt_de;
    dt[i][2] = dt[i][3] = Eigen::Vector3d::Zero();
    dt[i][2 + i] = d[i]->dt_da;
  }
  Mat12 h;
  for (int j = 0; j < 4; ++j) {
    Eigen::Matrix3d r0 = Eigen::Matrix3d::Zero(), r1 = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 2; ++i) {
      const Wing& w = *wing[i];
      // g0 = -(1 - t_i) u_i summed, g1 = -t_i u_i summed.
      r0 += w.u * dt[i][j].transpose() - (1.0 - w.t) * du[i][j];
      r1 -= w.u * dt[i][j].transpose() + w.t * du[i][j];
    }
    h.block<3, 3>(0, 3 * j) = r0;
    h.block<3, 3>(3, 3 * j) = r1;
    h.block<3, 3>(6, 3 * j) = du[0][j];
    h.block<3, 3>(9, 3 * j) = du[1][j];
  }
  // Exact in exact arithmetic; symmetrise the rounding.
  return 0.5 * (h + h.transpose());
}

}  // namespace drape::dihedral
