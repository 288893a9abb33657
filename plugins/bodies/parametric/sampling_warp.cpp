#include "sampling_warp.hpp"

#include <drape/errors.hpp>

#include <cmath>

namespace drape::parametric {
namespace {

// The radial slope W' = 1 + (s - 1) psi(r): psi is 1 inside, falls linearly to
// -kappa at outer and rises linearly back to 0 at the support, where its
// integral (W(r) - r over s - 1) has come back to 0.
double kappa(const Magnifier& m) { return (1 - m.min_slope) / (m.scale - 1); }
double lift_at_outer(const Magnifier& m) { return m.inner + 0.5 * (m.outer - m.inner) * (1 - kappa(m)); }

// W(r) - r.
double lift(const Magnifier& m, double r) {
  const double k = kappa(m), l1 = m.outer - m.inner;
  double psi_integral;
  if (r <= m.inner) {
    psi_integral = r;
  } else if (r <= m.outer) {
    const double u = r - m.inner;
    psi_integral = m.inner + u - 0.5 * (1 + k) * u * u / l1;
  } else if (r < m.support()) {
    const double v = r - m.outer, l2 = m.support() - m.outer;
    psi_integral = lift_at_outer(m) - k * (v - 0.5 * v * v / l2);
  } else {
    psi_integral = 0;
  }
  return (m.scale - 1) * psi_integral;
}

}  // namespace

double Magnifier::support() const { return outer + 2 * lift_at_outer(*this) / kappa(*this); }

void check_magnifiers(const Magnifiers& ms) {
  for (const Magnifier& m : ms)
    if (!(m.scale > 1 && m.inner > 0 && m.outer > m.inner && m.min_slope > 0 && m.min_slope < 1))
      throw Error("body parametric: a sampling magnifier needs scale > 1, 0 < inner < outer and 0 < min_slope < 1");
  for (std::size_t i = 0; i < ms.size(); ++i)
    for (std::size_t j = i + 1; j < ms.size(); ++j)
      if ((ms[i].centre - ms[j].centre).norm() < ms[i].support() + ms[j].support())
        throw Error("body parametric: two sampling magnifiers overlap");
}

Eigen::Vector3d warp(const Magnifiers& ms, const Eigen::Vector3d& x) {
  for (const Magnifier& m : ms) {
    const Eigen::Vector3d q = x - m.centre;
    const double r = q.norm();
    if (r < m.support()) return r > 0 ? Eigen::Vector3d(m.centre + q * ((r + lift(m, r)) / r)) : x;
  }
  return x;
}

Eigen::Vector3d unwarp(const Magnifiers& ms, const Eigen::Vector3d& y) {
  for (const Magnifier& m : ms) {
    const Eigen::Vector3d q = y - m.centre;
    const double target = q.norm();
    if (!(target < m.support())) continue;
    if (target == 0) return y;
    // W is increasing from 0 to the support: bisection to the rounding.
    double lo = 0, hi = target;  // W(r) >= r, so the answer is at most target
    for (int it = 0; it < 80 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      (mid + lift(m, mid) < target ? lo : hi) = mid;
    }
    return m.centre + q * (0.5 * (lo + hi) / target);
  }
  return y;
}

}  // namespace drape::parametric
