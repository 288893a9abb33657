#pragma once
// The kinematics of a membrane (in-plane stretching) energy of one triangle
// whose density psi(g) depends on the Green strain g = (G00, G11, G01): its
// gradient and (projected) Hessian in the positions, for any psi
// (drape/physics/arcsim_material.hpp gives ArcSim's and the linear one).
//
// With material-space (UV) edge matrix Dm = [u1 - u0, u2 - u0] and world
// positions x0, x1, x2, the deformation gradient is
//   F = [x1 - x0, x2 - x0] Dm^-1 = X C,   X = [x0 x1 x2] (3x3), C = D Dm^-1 (3x2),
// with D = [[-1, -1], [1, 0], [0, 1]]. The Green strain is G = (F^T F - I) / 2,
// g = (G00, G11, G01), and the face's energy is E = A psi(g), A the
// material-space area. With s = dpsi/dg and K = d2psi/dg2:
//   dE/dF = A J^T s,
//   d2E/dF2 = A (J^T K J + S (x) I3),  S = [[s0, s2/2], [s2/2, s1]],
// where J = dg/dvec(F) (rows [f0^T, 0], [0, f1^T], [f1^T/2, f0^T/2] for
// F = [f0 f1]) and S (x) I3 comes from the second derivatives of g. The first
// term is PSD whenever K is; the second is PSD iff S is (which fails under
// compression), so a face's Hessian is PSD whenever K and S both are.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>

namespace drape::membrane {

using Mat32 = Eigen::Matrix<double, 3, 2>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat9 = Eigen::Matrix<double, 9, 9>;

// F = X c for the face's positions X (3x3, one vertex per column).
// (Summed vertex by vertex, in the order drape always has, so that the linear
// model's drapes are reproduced bit for bit.)
inline Mat32 deformation_gradient(const Eigen::Matrix3d& X, const Mat32& c) {
  Mat32 F = X.col(0) * c.row(0);
  F.noalias() += X.col(1) * c.row(1);
  F.noalias() += X.col(2) * c.row(2);
  return F;
}

// g = (G00, G11, G01) of the Green strain.
inline Eigen::Vector3d green_strain(const Mat32& F) {
  return {0.5 * (F.col(0).squaredNorm() - 1.0), 0.5 * (F.col(1).squaredNorm() - 1.0), 0.5 * F.col(0).dot(F.col(1))};
}

// dE/dF = [s0 f0 + s2 f1 / 2, s1 f1 + s2 f0 / 2].
inline Mat32 stress(const Mat32& F, const Eigen::Vector3d& s) {
  Mat32 P;
  P.col(0) = s[0] * F.col(0) + 0.5 * s[2] * F.col(1);
  P.col(1) = s[1] * F.col(1) + 0.5 * s[2] * F.col(0);
  return P;
}

// d2E/dvec(F)^2 (vec stacks the columns f0, f1).
// K = d2psi/dg2 (3x3), s = dpsi/dg.
inline Mat6 hessian_in_F(const Mat32& F, const Eigen::Matrix3d& K, const Eigen::Vector3d& s) {
  Eigen::Matrix<double, 3, 6> J = Eigen::Matrix<double, 3, 6>::Zero();
  J.block<1, 3>(0, 0) = F.col(0).transpose();
  J.block<1, 3>(1, 3) = F.col(1).transpose();
  J.block<1, 3>(2, 0) = 0.5 * F.col(1).transpose();
  J.block<1, 3>(2, 3) = 0.5 * F.col(0).transpose();
  Mat6 H = J.transpose() * K * J;
  for (int i = 0; i < 3; ++i) {
    H(i, i) += s[0];
    H(3 + i, 3 + i) += s[1];
    H(i, 3 + i) += 0.5 * s[2];
    H(3 + i, i) += 0.5 * s[2];
  }
  return H;
}

inline bool stiffness_is_psd(const Eigen::Matrix3d& K) {
  return K(2, 2) >= 0.0 && K(0, 0) >= 0.0 && K(1, 1) >= 0.0 && Eigen::LLT<Eigen::Matrix3d>(K).info() == Eigen::Success;
}

inline bool stress_is_psd(const Eigen::Vector3d& s) {
  return s[0] >= 0.0 && s[1] >= 0.0 && s[0] * s[1] >= 0.25 * s[2] * s[2];
}

// The 9x9 Hessian over (x0, x1, x2) of a function of F = X m: blocks
// H_ab = sum_pq m(a, p) m(b, q) h_pq.
inline Mat9 lift(const Mat6& h, const Mat32& m) {
  Mat9 H;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) {
      Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
      for (int p = 0; p < 2; ++p)
        for (int q = 0; q < 2; ++q) block += m(a, p) * m(b, q) * h.block<3, 3>(3 * p, 3 * q);
      H.block<3, 3>(3 * a, 3 * b) = block;
      if (b != a) H.block<3, 3>(3 * b, 3 * a) = block.transpose();
    }
  return H;
}

// The nearest PSD matrix of a symmetric 2x2 matrix, in closed form.
inline Eigen::Matrix2d project_to_psd_2x2(const Eigen::Matrix2d& m) {
  const double a = m(0, 0), b = 0.5 * (m(0, 1) + m(1, 0)), c = m(1, 1);
  if (a >= 0.0 && c >= 0.0 && a * c >= b * b) return m;
  const double mean = 0.5 * (a + c), radius = std::hypot(0.5 * (a - c), b);
  const double top = mean + radius;  // the other eigenvalue is negative
  if (!(top > 0.0)) return Eigen::Matrix2d::Zero();
  // Eigenvector of `top` from whichever row of (m - top I) is better conditioned.
  Eigen::Vector2d v = std::abs(a - top) > std::abs(c - top) ? Eigen::Vector2d(b, top - a) : Eigen::Vector2d(top - c, b);
  const double norm = v.norm();
  if (!(norm > 0.0)) return m;  // a = c = top, b = 0: cannot happen with a negative eigenvalue
  v /= norm;
  return top * v * v.transpose();
}

// An orthonormal frame (u0, u1, n) whose first two vectors span F's columns
// (completed arbitrarily when F has rank < 2).
inline Eigen::Matrix3d column_frame(const Mat32& F) {
  const double tiny = 1e-12 * (F.col(0).norm() + F.col(1).norm());
  Eigen::Vector3d u0 = Eigen::Vector3d::UnitX();
  int first = -1;
  for (int c = 0; c < 2 && first < 0; ++c)
    if (F.col(c).norm() > tiny && F.col(c).norm() > 0.0) {
      u0 = F.col(c).normalized();
      first = c;
    }
  Eigen::Vector3d u1;
  const Eigen::Vector3d other = first >= 0 ? Eigen::Vector3d(F.col(1 - first)) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d w = other - u0.dot(other) * u0;
  if (w.norm() > tiny && w.norm() > 0.0) {
    u1 = w.normalized();
  } else {
    Eigen::Index axis;
    u0.cwiseAbs().minCoeff(&axis);
    u1 = u0.cross(Eigen::Vector3d::Unit(axis)).normalized();
  }
  Eigen::Matrix3d frame;
  frame << u0, u1, u0.cross(u1);
  return frame;
}

// The nearest PSD matrix of d2E/dvec(Y)^2 for F = Y t (t 2x2), found without a
// 6x6 eigen-decomposition. In a frame (u0, u1, n) with F's columns in the
// (u0, u1) plane, variations split exactly into in-plane ones (Y = U Z, 4 dofs)
// and out-of-plane ones (n w^T, 2 dofs): the latter leave F^T F unchanged to
// first order, so they do not couple to the former and their block is the
// closed form t S t^T (the membrane's buckling modes under compression). The
// in-plane 4x4 block is the 2D version of hessian_in_F; it is PSD-tested with a
// Cholesky factorisation and eigen-decomposed only when that fails. Its
// negative eigenvalues are clamped to zero (the nearest PSD matrix) or, with
// `absolute`, replaced by their magnitudes (Chen et al. 2024, "Stabler
// Neo-Hookean simulation: absolute eigenvalue filtering for projected Newton"):
// a direction of negative curvature then gets a finite step instead of an
// unbounded one. The out-of-plane block is always clamped: its negative
// eigenvalues are the buckling of a compressed face, which should stay free.
inline Mat6 projected_hessian_in_Y(const Mat32& F, const Eigen::Matrix3d& K, const Eigen::Vector3d& s,
                                   const Eigen::Matrix2d& t, bool absolute = false) {
  const Eigen::Matrix3d frame = column_frame(F);
  const Eigen::Matrix<double, 3, 2> U = frame.leftCols<2>();
  const Eigen::Vector3d n = frame.col(2);
  const Eigen::Matrix2d Fp = U.transpose() * F;  // F in the plane's coordinates

  Eigen::Matrix<double, 3, 4> J = Eigen::Matrix<double, 3, 4>::Zero();
  J.block<1, 2>(0, 0) = Fp.col(0).transpose();
  J.block<1, 2>(1, 2) = Fp.col(1).transpose();
  J.block<1, 2>(2, 0) = 0.5 * Fp.col(1).transpose();
  J.block<1, 2>(2, 2) = 0.5 * Fp.col(0).transpose();
  Eigen::Matrix4d hf = J.transpose() * K * J;
  for (int i = 0; i < 2; ++i) {
    hf(i, i) += s[0];
    hf(2 + i, 2 + i) += s[1];
    hf(i, 2 + i) += 0.5 * s[2];
    hf(2 + i, i) += 0.5 * s[2];
  }
  Eigen::Matrix4d in_plane;
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q) {
      Eigen::Matrix2d b = Eigen::Matrix2d::Zero();
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) b += t(p, r) * t(q, c) * hf.block<2, 2>(2 * r, 2 * c);
      in_plane.block<2, 2>(2 * p, 2 * q) = b;
    }
  if (Eigen::LLT<Eigen::Matrix4d>(in_plane).info() != Eigen::Success) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(in_plane);
    const Eigen::Vector4d filtered = absolute ? Eigen::Vector4d(eig.eigenvalues().cwiseAbs()) : Eigen::Vector4d(eig.eigenvalues().cwiseMax(0.0));
    in_plane = eig.eigenvectors() * filtered.asDiagonal() * eig.eigenvectors().transpose();
  }
  Eigen::Matrix2d S;
  S << s[0], 0.5 * s[2], 0.5 * s[2], s[1];
  const Eigen::Matrix2d out_of_plane = project_to_psd_2x2(t * S * t.transpose());

  const Eigen::Matrix3d nn = n * n.transpose();
  Mat6 h;
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q)
      h.block<3, 3>(3 * p, 3 * q) = U * in_plane.block<2, 2>(2 * p, 2 * q) * U.transpose() + out_of_plane(p, q) * nn;
  return h;
}

}  // namespace drape::membrane
