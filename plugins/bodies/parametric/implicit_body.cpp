#include "implicit_body.hpp"

#include <Eigen/Geometry>

#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace drape::parametric {
namespace {

// Lower bounds are lowered by this much (m) so that rounding can never make
// one exceed the value it bounds: a part is skipped only when it is surely
// further than its blend radius, so skipping never changes a bit of the union.
constexpr double kBoundMargin = 1e-12;

// A unit vector perpendicular to u, as close to +Z (the body's front) as possible,
// so that cone frames are stable as limbs change direction.
Eigen::Vector3d front_perpendicular(const Eigen::Vector3d& u) {
  Eigen::Vector3d ref = std::abs(u.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  return (ref - ref.dot(u) * u).normalized();
}

}  // namespace

Primitive Primitive::ellipsoid(const Eigen::Vector3d& centre, const Eigen::Vector3d& semi, double blend,
                               const Eigen::Matrix3d& frame) {
  Primitive p;
  p.kind = Kind::Ellipsoid;
  p.a = centre;
  p.semi = semi;
  p.frame = frame;
  p.blend = blend;
  p.bound_centre = centre;
  p.bound_radius = semi.maxCoeff();
  p.bound_slope = semi.minCoeff() / semi.maxCoeff();
  return p;
}

Primitive Primitive::cone(const Eigen::Vector3d& a, double ra, const Eigen::Vector3d& b, double rb, double blend) {
  Primitive p;
  p.kind = Kind::Cone;
  p.a = a, p.b = b, p.ra = ra, p.rb = rb;
  const Eigen::Vector3d u = (b - a).normalized(), e1 = front_perpendicular(u);
  p.frame.col(0) = u;
  p.frame.col(1) = e1;
  p.frame.col(2) = u.cross(e1);
  p.blend = blend;
  p.bound_centre = 0.5 * (a + b);
  p.bound_radius = 0.5 * (b - a).norm() + std::max(ra, rb);
  return p;
}

double Primitive::lower_bound(const Eigen::Vector3d& p) const {
  const double gap = (p - bound_centre).norm() - bound_radius;
  if (kind == Kind::Cone) return gap;  // d - r >= |p - mid| - length / 2 - max radius
  // k1 = |q / s^2| <= |q / s| / s_min = k0 / s_min, so k0 (k0 - 1) / k1 >=
  // (k0 - 1) s_min once k0 >= 1; and k0 >= |q| / s_max = D / s_max (the frame
  // is a rotation), so with D > s_max: eval >= (D - s_max) s_min / s_max.
  // Inside the sphere: no bound here (see eval_unless_beyond).
  return gap > 0 ? gap * bound_slope - kBoundMargin : -INFINITY;
}

double Primitive::eval(const Eigen::Vector3d& p, Eigen::Vector3d* gradient) const {
  return eval_unless_beyond(p, INFINITY, gradient);
}

double Primitive::eval_unless_beyond(const Eigen::Vector3d& p, double limit, Eigen::Vector3d* gradient) const {
  if (kind == Kind::Ellipsoid) {
    // Quilez's ellipsoid bound k0 (k0 - 1) / k1: close to the true distance near
    // the surface even for elongated ellipsoids, which keeps blends even.
    const Eigen::Vector3d q = frame.transpose() * (p - a), q1 = q.cwiseQuotient(semi);
    const double q1_norm = q1.norm();
    // The bound of lower_bound() in the ellipsoid's own frame, (k0 - 1) s_min,
    // from k0 alone: most parts a point is tested against end here. Outside
    // only (k0 >= 1): inside, the value lies between (k0 - 1) s_max and
    // (k0 - 1) s_min, so the same expression is no lower bound there.
    if (std::isfinite(limit) && q1_norm >= 1 && (q1_norm - 1) * semi.minCoeff() - kBoundMargin >= limit) return INFINITY;
    const Eigen::Vector3d s2 = semi.cwiseProduct(semi);
    const Eigen::Vector3d q2 = q.cwiseQuotient(s2);
    const double k0 = std::max(q1_norm, 1e-12), k1 = std::max(q2.norm(), 1e-12);
    const double f = k0 * (k0 - 1) / k1;
    if (gradient) {
      const Eigen::Vector3d g0 = q2 / k0;                                 // d k0 / dq
      const Eigen::Vector3d g1 = q2.cwiseQuotient(s2) / k1;               // d k1 / dq
      const Eigen::Vector3d gq = ((2 * k0 - 1) * g0 - f * g1) / k1;
      *gradient = frame * gq;
    }
    return f;
  }
  const Eigen::Vector3d u = frame.col(0);
  const double len = (b - a).norm();
  const double t_raw = (p - a).dot(u) / len, t = std::clamp(t_raw, 0.0, 1.0);
  const Eigen::Vector3d c = a + t * len * u, off = p - c;
  const double d = std::max(off.norm(), 1e-12), r = ra + t * (rb - ra);
  if (gradient) {
    *gradient = off / d;
    if (t_raw > 0 && t_raw < 1) *gradient -= (rb - ra) / len * u;
  }
  return d - r;
}

Eigen::Vector3d Primitive::carry(const Eigen::Vector3d& p, const Primitive& to) const {
  if (kind == Kind::Ellipsoid) {
    const Eigen::Vector3d q = frame.transpose() * (p - a);
    return to.a + to.frame * q.cwiseQuotient(semi).cwiseProduct(to.semi);
  }
  const Eigen::Vector3d u = frame.col(0);
  const double len = (b - a).norm();
  const double t = std::clamp((p - a).dot(u) / len, 0.0, 1.0);
  const Eigen::Vector3d local = frame.transpose() * (p - (a + t * len * u));
  const double r = ra + t * (rb - ra), r_to = to.ra + t * (to.rb - to.ra);
  return to.a + t * (to.b - to.a) + to.frame * local * (r_to / r);
}

namespace {

// The union of parts from the first, each blended in turn; `skip` decides
// which parts may be left out (the value is the same either way when it is right).
template <class Skip>
double blended_union(const std::vector<Primitive>& parts, const Eigen::Vector3d& p, Eigen::Vector3d* gradient, Skip skip) {
  Eigen::Vector3d g, gi;
  double f = parts.front().eval(p, gradient ? &g : nullptr);
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const Primitive& prim = parts[i];
    const double fi = skip(prim, f, gradient ? &gi : nullptr);
    if (fi == INFINITY) continue;
    const double k = prim.blend;
    if (k <= 0 || std::abs(fi - f) >= k) {
      if (fi < f) {
        f = fi;
        if (gradient) g = gi;
      }
      continue;
    }
    // Polynomial smooth minimum; its gradient is exactly the h-weighted mix.
    const double h = 0.5 + 0.5 * (fi - f) / k;  // weight of the union so far
    f = f * h + fi * (1 - h) - k * h * (1 - h);
    if (gradient) g = g * h + gi * (1 - h);
  }
  if (gradient) *gradient = g;
  return f;
}

// DRAPE_BODY_CHECK_CULLING=1: every evaluation is made again without
// skipping any part, and a difference in any bit is an error (the tests'
// check that the bounds are bounds; about twice the time).
const bool kCheckCulling = std::getenv("DRAPE_BODY_CHECK_CULLING") != nullptr;

}  // namespace

double ImplicitBody::eval(const Eigen::Vector3d& p, Eigen::Vector3d* gradient) const {
  // Parts that are surely further than the blend radius cannot change the value.
  const double f = blended_union(parts, p, gradient, [&](const Primitive& prim, double f_so_far, Eigen::Vector3d* gi) -> double {
    if (prim.lower_bound(p) >= f_so_far + prim.blend) return INFINITY;
    return prim.eval_unless_beyond(p, f_so_far + prim.blend, gi);
  });
  if (kCheckCulling) {
    Eigen::Vector3d g_all;
    const double f_all = blended_union(parts, p, gradient ? &g_all : nullptr,
                                       [&](const Primitive& prim, double, Eigen::Vector3d* gi) -> double { return prim.eval(p, gi); });
    if (std::memcmp(&f, &f_all, sizeof f) != 0 || (gradient && *gradient != g_all)) {
      char at[200];
      std::snprintf(at, sizeof at, "(%.17g, %.17g, %.17g): %.17g with parts skipped, %.17g with every part", p.x(), p.y(),
                    p.z(), f, f_all);
      throw Error(std::string("body parametric: skipping parts changed the implicit surface at ") + at);
    }
  }
  return f;
}

Eigen::Vector3d ImplicitBody::project(Eigen::Vector3d p, int steps) const {
  Eigen::Vector3d g;
  for (int i = 0; i < steps; ++i) {
    const double f = eval(p, &g);
    const double g2 = g.squaredNorm();
    if (g2 < 1e-12) break;
    p -= f / g2 * g;
    if (std::abs(f) < 1e-8) break;  // 10 nm: far below any use of the mesh
  }
  return p;
}

}  // namespace drape::parametric
