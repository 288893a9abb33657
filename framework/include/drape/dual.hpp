#pragma once
// A number that carries its gradient and Hessian with respect to N variables:
// forward-mode differentiation to second order. Contact distances (a point to
// a triangle's plane, two lines) are short chains of products, quotients and
// cross products whose hand-written Hessians run to pages; written once over
// Dual<N>, the value, the exact gradient and the exact Hessian come out of the
// same code and cannot drift apart. Each operation applies the product or
// chain rule to (value, gradient, Hessian). Cost: O(N^2) per operation, meant
// for stencils of a few vertices (N <= 12).
#include <Eigen/Core>

#include <array>
#include <cmath>

namespace drape {

// Order 2 carries the Hessian; order 1 only the gradient (what a gradient
// evaluation needs: O(N) per operation instead of O(N^2)).
template <int N, int Order = 2>
struct Dual {
  static_assert(Order == 1 || Order == 2, "Dual: order 1 or 2");
  static constexpr int kHessianSize = Order == 2 ? N : 0;
  using Gradient = Eigen::Matrix<double, N, 1>;
  using Hessian = Eigen::Matrix<double, kHessianSize, kHessianSize>;
  double v = 0;
  Gradient g = Gradient::Zero();
  Hessian h = Hessian::Zero();

  static Dual constant(double value) {
    Dual d;
    d.v = value;
    return d;
  }
  // The variable number `index` itself, at value `value`.
  static Dual variable(double value, int index) {
    Dual d = constant(value);
    d.g[index] = 1;
    return d;
  }
};

template <int N, int O>
Dual<N, O> operator+(const Dual<N, O>& a, const Dual<N, O>& b) {
  return {a.v + b.v, a.g + b.g, a.h + b.h};
}
template <int N, int O>
Dual<N, O> operator-(const Dual<N, O>& a, const Dual<N, O>& b) {
  return {a.v - b.v, a.g - b.g, a.h - b.h};
}
template <int N, int O>
Dual<N, O> operator-(const Dual<N, O>& a) {
  return {-a.v, -a.g, -a.h};
}
template <int N, int O>
Dual<N, O> operator*(double s, const Dual<N, O>& a) {
  return {s * a.v, s * a.g, s * a.h};
}
template <int N, int O>
Dual<N, O> operator*(const Dual<N, O>& a, const Dual<N, O>& b) {
  Dual<N, O> r;
  r.v = a.v * b.v;
  r.g = a.g * b.v + b.g * a.v;
  if constexpr (O == 2) {
    r.h = a.h * b.v + b.h * a.v;
    r.h.noalias() += a.g * b.g.transpose();
    r.h.noalias() += b.g * a.g.transpose();
  }
  return r;
}

// f(a) from f, f' and f'' at a.v: the chain rule to second order.
template <int N, int O>
Dual<N, O> chain(const Dual<N, O>& a, double f, double df, double d2f) {
  Dual<N, O> r;
  r.v = f;
  r.g = df * a.g;
  if constexpr (O == 2) {
    r.h = df * a.h;
    r.h.noalias() += d2f * a.g * a.g.transpose();
  }
  return r;
}
template <int N, int O>
Dual<N, O> inverse(const Dual<N, O>& a) {
  return chain(a, 1 / a.v, -1 / (a.v * a.v), 2 / (a.v * a.v * a.v));
}
template <int N, int O>
Dual<N, O> operator/(const Dual<N, O>& a, const Dual<N, O>& b) {
  return a * inverse(b);
}
template <int N, int O>
Dual<N, O> sqrt(const Dual<N, O>& a) {
  const double r = std::sqrt(a.v);
  return chain(a, r, 0.5 / r, -0.25 / (r * a.v));
}

// Plain doubles take the same code paths (value only), so one function
// template gives a value in double and its derivatives in Dual<N>.
inline double inverse(double a) { return 1 / a; }
inline double chain(double /*a*/, double f, double /*df*/, double /*d2f*/) { return f; }
inline double primal(double a) { return a; }
template <int N, int O>
double primal(const Dual<N, O>& a) {
  return a.v;
}

// A 3-vector of scalars (double or Dual<N>) and the few operations contact needs.
template <class S>
using Vec3 = std::array<S, 3>;

template <class S>
Vec3<S> operator-(const Vec3<S>& a, const Vec3<S>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <class S>
S dot(const Vec3<S>& a, const Vec3<S>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <class S>
Vec3<S> cross(const Vec3<S>& a, const Vec3<S>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// A point of a stencil as scalars: variables first_index..+2, or constants.
template <class D>
Vec3<D> variable_point(const Eigen::Vector3d& p, int first_index) {
  return {D::variable(p[0], first_index), D::variable(p[1], first_index + 1), D::variable(p[2], first_index + 2)};
}
template <class D>
Vec3<D> constant_point(const Eigen::Vector3d& p) {
  return {D::constant(p[0]), D::constant(p[1]), D::constant(p[2])};
}
inline Vec3<double> plain_point(const Eigen::Vector3d& p) { return {p[0], p[1], p[2]}; }

}  // namespace drape
