#pragma once
// Slow, independent references for the closest-point tests: exhaustive
// searches in long double and the generalised winding number for inside/outside.
#include <drape/mesh.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace drape::test {

using Vec3L = Eigen::Matrix<long double, 3, 1>;

inline Vec3L to_long(const Eigen::Vector3d& v) { return v.cast<long double>(); }

inline long double segment_distance2(const Vec3L& p, const Vec3L& a, const Vec3L& b) {
  const Vec3L e = b - a;
  const long double len2 = e.squaredNorm();
  const long double t = len2 > 0 ? std::clamp((p - a).dot(e) / len2, 0.0L, 1.0L) : 0.0L;
  return (a + t * e - p).squaredNorm();
}

// Squared distance from p to the closed triangle: the plane projection when it
// falls inside (solved from the 2x2 Gram system), else the nearest of the edges.
inline long double triangle_distance2(const Eigen::Vector3d& pd, const Eigen::Vector3d& ad, const Eigen::Vector3d& bd,
                                      const Eigen::Vector3d& cd) {
  const Vec3L p = to_long(pd), a = to_long(ad), b = to_long(bd), c = to_long(cd);
  long double best = std::min({segment_distance2(p, a, b), segment_distance2(p, b, c), segment_distance2(p, c, a)});
  const Vec3L u = b - a, v = c - a, w = p - a;
  const long double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), det = uu * vv - uv * uv;
  if (det > 1e-20L * uu * vv) {
    const long double s = (vv * u.dot(w) - uv * v.dot(w)) / det, t = (uu * v.dot(w) - uv * u.dot(w)) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) best = std::min(best, (a + s * u + t * v - p).squaredNorm());
  }
  return best;
}

inline double mesh_distance(const Mesh& m, const Eigen::Vector3d& p) {
  long double best = INFINITY;
  for (int f = 0; f < m.num_faces(); ++f)
    best = std::min(best, triangle_distance2(p, m.vertices.row(m.faces(f, 0)), m.vertices.row(m.faces(f, 1)),
                                             m.vertices.row(m.faces(f, 2))));
  return static_cast<double>(std::sqrt(best));
}

// Sum of the solid angles of the faces seen from p over 4 pi (van Oosterom &
// Strackee): 1 inside a closed counter-clockwise mesh, 0 outside, whatever its
// shape, and well defined arbitrarily close to (but off) the surface.
inline double winding_number(const Mesh& m, const Eigen::Vector3d& pd) {
  const Vec3L p = to_long(pd);
  long double total = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3L a = to_long(m.vertices.row(m.faces(f, 0))) - p, b = to_long(m.vertices.row(m.faces(f, 1))) - p,
                c = to_long(m.vertices.row(m.faces(f, 2))) - p;
    const long double la = a.norm(), lb = b.norm(), lc = c.norm();
    const long double num = a.dot(b.cross(c));
    const long double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2 * std::atan2(num, den);
  }
  return static_cast<double>(total / (4 * std::numbers::pi_v<long double>));
}

inline double signed_volume(const Mesh& m) {
  double v = 0;
  for (int f = 0; f < m.num_faces(); ++f)
    v += Eigen::Vector3d(m.vertices.row(m.faces(f, 0)))
             .dot(Eigen::Vector3d(m.vertices.row(m.faces(f, 1))).cross(Eigen::Vector3d(m.vertices.row(m.faces(f, 2))))) /
         6;
  return v;
}

}  // namespace drape::test
