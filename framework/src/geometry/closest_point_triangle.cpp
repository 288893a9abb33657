#include <drape/geometry/closest_point.hpp>

#include <Eigen/Geometry>

#include <algorithm>

namespace drape::geometry {
namespace {

// n / d clamped to [0, 1]; 0 when d vanishes (a zero-length edge), where every
// t gives the same point, so that degenerate triangles never produce NaN.
double ratio(double n, double d) { return d > 0 ? std::clamp(n / d, 0.0, 1.0) : 0.0; }

TrianglePoint on_edge(const Eigen::Vector3d& p, const Eigen::Vector3d& from, const Eigen::Vector3d& to, int i, int j,
                      TriangleFeature feature) {
  const Eigen::Vector3d e = to - from;
  const double t = ratio(e.dot(p - from), e.squaredNorm());
  TrianglePoint r{from + t * e, Eigen::Vector3d::Zero(), feature};
  r.barycentric[i] = 1 - t;
  r.barycentric[j] = t;
  return r;
}

// The best of the three edges: the answer for a degenerate triangle, whose
// "interior" has no area, and a safe fallback when rounding breaks the region tests.
TrianglePoint on_boundary(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
  const TrianglePoint candidates[3] = {on_edge(p, a, b, 0, 1, TriangleFeature::edge_ab),
                                       on_edge(p, b, c, 1, 2, TriangleFeature::edge_bc),
                                       on_edge(p, c, a, 2, 0, TriangleFeature::edge_ca)};
  const TrianglePoint* best = &candidates[0];
  for (const TrianglePoint& q : candidates)
    if ((q.point - p).squaredNorm() < (best->point - p).squaredNorm()) best = &q;
  return *best;
}

}  // namespace

TrianglePoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                        const Eigen::Vector3d& c) {
  using F = TriangleFeature;
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  // The region tests below assume three distinct, non-collinear corners (with a
  // zero-length edge ab they would accept "edge ab" for every p). For a
  // triangle collinear to rounding, the closest point is on its segments.
  if (ab.cross(ac).squaredNorm() <= 1e-30 * ab.squaredNorm() * ac.squaredNorm()) return on_boundary(p, a, b, c);
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, {1, 0, 0}, F::vertex_a};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, {0, 1, 0}, F::vertex_b};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = ratio(d1, d1 - d3);
    return {a + t * ab, {1 - t, t, 0}, F::edge_ab};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, {0, 0, 1}, F::vertex_c};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = ratio(d2, d2 - d6);
    return {a + t * ac, {1 - t, 0, t}, F::edge_ca};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = ratio(d4 - d3, (d4 - d3) + (d5 - d6));
    return {b + t * (c - b), {0, 1 - t, t}, F::edge_bc};
  }
  // Interior: va, vb, vc are the (scaled) barycentric areas, all positive in
  // exact arithmetic. Rounding on slivers can break that; the edges then decide.
  const double sum = va + vb + vc;
  if (!(va > 0 && vb > 0 && vc > 0 && sum > 0)) return on_boundary(p, a, b, c);
  const double v = vb / sum, w = vc / sum;
  return {a + v * ab + w * ac, {1 - v - w, v, w}, F::interior};
}

}  // namespace drape::geometry
