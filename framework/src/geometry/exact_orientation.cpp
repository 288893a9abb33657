// Exact orientation signs: a filtered double evaluation, and exact expansion
// arithmetic (J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates", 1997) when the filter cannot decide.
#include "exact_orientation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace drape::geometry::exact {
namespace {

// Shewchuk's error bounds of the plain double evaluations (orient3d: errboundA
// = (7 + 56 eps) eps, orient2d: (3 + 16 eps) eps, eps = 2^-53), times 2: with
// -march=native the compiler may fuse a product into an FMA, which only
// removes roundings, but the margin costs nothing (a few more exact calls).
constexpr double kEps = 0x1p-53;
constexpr double kOrient3dBound = 2 * (7.0 + 56.0 * kEps) * kEps;
constexpr double kOrient2dBound = 2 * (3.0 + 16.0 * kEps) * kEps;

// A sum of doubles, exact: components non-overlapping, by increasing
// magnitude, zeros dropped (so the last component carries the sign).
using Expansion = std::vector<double>;

// x + y == a + b exactly, x = fl(a + b). Additions only, so no FMA contraction can touch it.
void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a, a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}

void two_diff(double a, double b, double& x, double& y) {
  x = a - b;
  const double b_virtual = a - x, a_virtual = x + b_virtual;
  y = (a - a_virtual) + (b_virtual - b);
}

// x + y == a * b exactly: the FMA computes the product's rounding error exactly.
void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);
}

Expansion difference(double a, double b) {
  double x, y;
  two_diff(a, b, x, y);
  Expansion e;
  if (y != 0) e.push_back(y);
  if (x != 0) e.push_back(x);
  return e;
}

// e + b (Shewchuk's GROW-EXPANSION with zero elimination).
Expansion grow(const Expansion& e, double b) {
  Expansion h;
  h.reserve(e.size() + 1);
  double q = b;
  for (double c : e) {
    double s, err;
    two_sum(q, c, s, err);
    q = s;
    if (err != 0) h.push_back(err);
  }
  if (q != 0) h.push_back(q);
  return h;
}

Expansion sum(Expansion e, const Expansion& f) {
  for (double b : f) e = grow(e, b);
  return e;
}

Expansion negated(Expansion e) {
  for (double& c : e) c = -c;
  return e;
}

// e * b (Shewchuk's SCALE-EXPANSION with zero elimination).
Expansion scale(const Expansion& e, double b) {
  Expansion h;
  if (e.empty() || b == 0) return h;
  h.reserve(2 * e.size());
  double q, err;
  two_product(e[0], b, q, err);
  if (err != 0) h.push_back(err);
  for (std::size_t i = 1; i < e.size(); ++i) {
    double high, low, s;
    two_product(e[i], b, high, low);
    two_sum(q, low, s, err);
    if (err != 0) h.push_back(err);
    two_sum(high, s, q, err);
    if (err != 0) h.push_back(err);
  }
  if (q != 0) h.push_back(q);
  return h;
}

Expansion product(const Expansion& e, const Expansion& f) {
  Expansion p;
  for (double b : f) p = sum(std::move(p), scale(e, b));
  return p;
}

int sign(const Expansion& e) { return e.empty() ? 0 : (e.back() > 0 ? 1 : -1); }

int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  Expansion u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) u[k] = difference(b[k], a[k]), v[k] = difference(c[k], a[k]), w[k] = difference(d[k], a[k]);
  // det = u . (v x w), each cofactor of u exactly.
  Expansion det;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const Expansion cofactor = sum(product(v[k1], w[k2]), negated(product(v[k2], w[k1])));
    det = sum(std::move(det), product(u[k], cofactor));
  }
  return sign(det);
}

int orient2d_exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Expansion ux = difference(b.x(), a.x()), uy = difference(b.y(), a.y());
  const Expansion vx = difference(c.x(), a.x()), vy = difference(c.y(), a.y());
  return sign(sum(product(ux, vy), negated(product(uy, vx))));
}

}  // namespace

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const double ux = b.x() - a.x(), uy = b.y() - a.y(), uz = b.z() - a.z();
  const double vx = c.x() - a.x(), vy = c.y() - a.y(), vz = c.z() - a.z();
  const double wx = d.x() - a.x(), wy = d.y() - a.y(), wz = d.z() - a.z();
  const double vywz = vy * wz, vzwy = vz * wy, vzwx = vz * wx, vxwz = vx * wz, vxwy = vx * wy, vywx = vy * wx;
  const double det = ux * (vywz - vzwy) + uy * (vzwx - vxwz) + uz * (vxwy - vywx);
  const double permanent = std::abs(ux) * (std::abs(vywz) + std::abs(vzwy)) + std::abs(uy) * (std::abs(vzwx) + std::abs(vxwz)) +
                           std::abs(uz) * (std::abs(vxwy) + std::abs(vywx));
  const double bound = kOrient3dBound * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient3d_exact(a, b, c, d);
}

int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double uxvy = (b.x() - a.x()) * (c.y() - a.y()), uyvx = (b.y() - a.y()) * (c.x() - a.x());
  const double det = uxvy - uyvx, bound = kOrient2dBound * (std::abs(uxvy) + std::abs(uyvx));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient2d_exact(a, b, c);
}

namespace {

// r inside the bounding box of (p, q): on the closed segment when the three are collinear.
bool in_box(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) && std::min(p.y(), q.y()) <= r.y() &&
         r.y() <= std::max(p.y(), q.y());
}

}  // namespace

bool segments_meet_2d(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const int o1 = orient2d(p, q, a), o2 = orient2d(p, q, b);
  const int o3 = orient2d(a, b, p), o4 = orient2d(a, b, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && in_box(p, q, a)) || (o2 == 0 && in_box(p, q, b)) || (o3 == 0 && in_box(a, b, p)) ||
         (o4 == 0 && in_box(a, b, q));
}

}  // namespace drape::geometry::exact
