// Triangle-triangle intersection from orientation predicates: two triangles in
// different planes meet exactly when an edge of one pierces the other, so six
// segment-triangle tests decide it; coplanar pairs fall back to 2D tests.
#include <drape/geometry/self_intersection.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace drape::geometry {
namespace {

using V3 = Eigen::Vector3d;
using V2 = Eigen::Vector2d;

int sign(double x) { return (x > 0) - (x < 0); }

double orient(const V3& a, const V3& b, const V3& c, const V3& d) { return (b - a).cross(c - a).dot(d - a); }

double orient2(const V2& a, const V2& b, const V2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool on_segment2(const V2& a, const V2& b, const V2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}

bool segments_intersect2(const V2& p, const V2& q, const V2& a, const V2& b) {
  const int d1 = sign(orient2(a, b, p)), d2 = sign(orient2(a, b, q)), d3 = sign(orient2(p, q, a)),
            d4 = sign(orient2(p, q, b));
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && on_segment2(a, b, p)) || (d2 == 0 && on_segment2(a, b, q)) || (d3 == 0 && on_segment2(p, q, a)) ||
         (d4 == 0 && on_segment2(p, q, b));
}

bool inside_triangle2(const V2& p, const V2 t[3]) {
  const int s0 = sign(orient2(t[0], t[1], p)), s1 = sign(orient2(t[1], t[2], p)), s2 = sign(orient2(t[2], t[0], p));
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

bool coplanar_intersect(const V3 a[3], const V3 b[3]) {
  const V3 n = (a[1] - a[0]).cross(a[2] - a[0]).cwiseAbs();
  // Drop the axis the plane is most perpendicular to.
  int drop = 0;
  if (n.y() > n[drop]) drop = 1;
  if (n.z() > n[drop]) drop = 2;
  const int i0 = drop == 0 ? 1 : 0, i1 = drop == 2 ? 1 : 2;
  V2 p[3], q[3];
  for (int k = 0; k < 3; ++k) p[k] = {a[k][i0], a[k][i1]}, q[k] = {b[k][i0], b[k][i1]};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_intersect2(p[i], p[(i + 1) % 3], q[j], q[(j + 1) % 3])) return true;
  return inside_triangle2(p[0], q) || inside_triangle2(q[0], p);
}

// Does segment pq (not in the plane of t) meet triangle t?
bool segment_pierces(const V3& p, const V3& q, const V3 t[3]) {
  const int sp = sign(orient(t[0], t[1], t[2], p)), sq = sign(orient(t[0], t[1], t[2], q));
  if (sp * sq > 0 || (sp == 0 && sq == 0)) return false;
  const int s0 = sign(orient(p, q, t[0], t[1])), s1 = sign(orient(p, q, t[1], t[2])), s2 = sign(orient(p, q, t[2], t[0]));
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

}  // namespace

bool triangles_intersect(const V3& a0, const V3& a1, const V3& a2, const V3& b0, const V3& b1, const V3& b2) {
  const V3 a[3] = {a0, a1, a2}, b[3] = {b0, b1, b2};
  int sb[3], sa[3];
  for (int k = 0; k < 3; ++k) sb[k] = sign(orient(a0, a1, a2, b[k])), sa[k] = sign(orient(b0, b1, b2, a[k]));
  auto one_side = [](const int s[3]) { return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0); };
  if (one_side(sb) || one_side(sa)) return false;
  if (sb[0] == 0 && sb[1] == 0 && sb[2] == 0) return coplanar_intersect(a, b);
  for (int k = 0; k < 3; ++k)
    if (segment_pierces(a[k], a[(k + 1) % 3], b) || segment_pierces(b[k], b[(k + 1) % 3], a)) return true;
  return false;
}

}  // namespace drape::geometry
