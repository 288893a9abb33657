#pragma once
// A number that carries its gradient and Hessian with respect to one point in
// space (three variables): forward-mode differentiation to second order. The
// crease penalty (crease_penalty.hpp) is a chain of a dozen sums, products,
// square roots and one smooth step of a vertex's position; written with Dual2
// its exact gradient and Hessian come out of the same code as its value, so
// they cannot drift apart. Each operation applies the product or chain rule to
// (value, gradient, Hessian).
#include <Eigen/Core>

#include <array>
#include <cmath>

namespace drape::collision {

struct Dual2 {
  double v = 0;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();

  static Dual2 constant(double value) { return {value, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()}; }
  // The variable p_axis itself, at value `value`.
  static Dual2 variable(double value, int axis) {
    Dual2 d = constant(value);
    d.g[axis] = 1;
    return d;
  }
};

inline Dual2 operator+(const Dual2& a, const Dual2& b) { return {a.v + b.v, a.g + b.g, a.h + b.h}; }
inline Dual2 operator-(const Dual2& a, const Dual2& b) { return {a.v - b.v, a.g - b.g, a.h - b.h}; }
inline Dual2 operator*(double s, const Dual2& a) { return {s * a.v, s * a.g, s * a.h}; }
inline Dual2 operator*(const Dual2& a, const Dual2& b) {
  return {a.v * b.v, a.g * b.v + b.g * a.v, a.h * b.v + b.h * a.v + a.g * b.g.transpose() + b.g * a.g.transpose()};
}

// f(a) from f, f' and f'' at a.v: the chain rule to second order.
inline Dual2 chain(const Dual2& a, double f, double df, double d2f) {
  return {f, df * a.g, df * a.h + d2f * a.g * a.g.transpose()};
}
inline Dual2 sqrt(const Dual2& a) {
  const double r = std::sqrt(a.v);
  return chain(a, r, 0.5 / r, -0.25 / (r * a.v));
}
inline Dual2 inverse(const Dual2& a) { return chain(a, 1 / a.v, -1 / (a.v * a.v), 2 / (a.v * a.v * a.v)); }
inline Dual2 operator/(const Dual2& a, const Dual2& b) { return a * inverse(b); }

using Dual2Vector = std::array<Dual2, 3>;

inline Dual2 dot(const Dual2Vector& a, const Dual2Vector& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Dual2Vector operator-(const Dual2Vector& a, const Dual2Vector& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

}  // namespace drape::collision
