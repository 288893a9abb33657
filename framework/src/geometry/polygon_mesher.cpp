#include <drape/geometry/polygon_mesher.hpp>

#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace drape::geometry {
namespace {

using Tri = std::array<int, 3>;

double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// > 0 when d lies inside the circumcircle of the counter-clockwise triangle (a, b, c).
double in_circle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                 const Eigen::Vector2d& d) {
  const Eigen::Vector2d p = a - d, q = b - d, r = c - d;
  return p.squaredNorm() * (q.x() * r.y() - r.x() * q.y()) - q.squaredNorm() * (p.x() * r.y() - r.x() * p.y()) +
         r.squaredNorm() * (p.x() * q.y() - q.x() * p.y());
}

// Bowyer-Watson with a naive cavity search: the panels have a few thousand
// points, so O(n^2) costs milliseconds and needs no point-location structure.
std::vector<Tri> delaunay(Polygon2& pts) {
  const int n = static_cast<int>(pts.size());
  Eigen::Vector2d lo = pts[0], hi = pts[0];
  for (const auto& p : pts) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector2d mid = 0.5 * (lo + hi);
  const double span = 20.0 * std::max(hi.x() - lo.x(), hi.y() - lo.y());
  pts.push_back(mid + Eigen::Vector2d(-span, -span));
  pts.push_back(mid + Eigen::Vector2d(span, -span));
  pts.push_back(mid + Eigen::Vector2d(0, span));
  struct Cell {
    Tri t;
    Eigen::Vector2d centre;
    double radius2;
  };
  auto make = [&](int a, int b, int c) {
    const Eigen::Vector2d &A = pts[a], &B = pts[b], &C = pts[c];
    const double d = 2 * orient(A, B, C);
    const Eigen::Vector2d ba = B - A, ca = C - A;
    const Eigen::Vector2d off((ca.y() * ba.squaredNorm() - ba.y() * ca.squaredNorm()) / d,
                              (ba.x() * ca.squaredNorm() - ca.x() * ba.squaredNorm()) / d);
    return Cell{{a, b, c}, A + off, off.squaredNorm()};
  };
  std::vector<Cell> cells{make(n, n + 1, n + 2)};
  std::vector<std::pair<int, int>> rim;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = pts[i];
    rim.clear();
    std::vector<Cell> kept;
    kept.reserve(cells.size() + 4);
    for (const Cell& c : cells) {
      if ((p - c.centre).squaredNorm() < c.radius2 * (1 - 1e-12)) {
        for (int k = 0; k < 3; ++k) rim.emplace_back(c.t[k], c.t[(k + 1) % 3]);
      } else {
        kept.push_back(c);
      }
    }
    // Cavity edges seen twice (once per direction) are interior to the cavity.
    for (const auto& [a, b] : rim)
      if (std::find(rim.begin(), rim.end(), std::make_pair(b, a)) == rim.end()) kept.push_back(make(a, b, i));
    cells.swap(kept);
  }
  pts.resize(static_cast<std::size_t>(n));
  std::vector<Tri> out;
  for (const Cell& c : cells)
    if (c.t[0] < n && c.t[1] < n && c.t[2] < n) out.push_back(c.t);
  return out;
}

// Lawson flips of interior edges until every one is locally Delaunay. Edges
// with a single triangle (the polygon's boundary) are never touched.
void flip_to_delaunay(const Polygon2& pts, std::vector<Tri>& tris) {
  for (int pass = 0; pass < 100; ++pass) {
    std::map<std::pair<int, int>, std::pair<int, int>> owner;  // directed edge -> (triangle, corner opposite)
    for (int t = 0; t < static_cast<int>(tris.size()); ++t)
      for (int k = 0; k < 3; ++k) owner[{tris[t][k], tris[t][(k + 1) % 3]}] = {t, (k + 2) % 3};
    std::vector<char> touched(tris.size(), 0);
    int flips = 0;
    for (const auto& [edge, left] : owner) {
      const auto it = owner.find({edge.second, edge.first});
      if (it == owner.end() || edge.first > edge.second) continue;
      const auto [t1, k1] = left;
      const auto [t2, k2] = it->second;
      if (touched[t1] || touched[t2]) continue;
      const int a = edge.first, b = edge.second, c = tris[t1][k1], d = tris[t2][k2];
      if (in_circle(pts[a], pts[b], pts[c], pts[d]) <= 1e-14 * std::pow((pts[a] - pts[b]).squaredNorm(), 2)) continue;
      if (orient(pts[a], pts[d], pts[c]) <= 0 || orient(pts[d], pts[b], pts[c]) <= 0) continue;  // not convex
      tris[t1] = {a, d, c};
      tris[t2] = {d, b, c};
      touched[t1] = touched[t2] = 1;
      ++flips;
    }
    if (flips == 0) return;
  }
}

bool all_positive(const Polygon2& pts, const std::vector<Tri>& tris) {
  for (const Tri& t : tris)
    if (orient(pts[t[0]], pts[t[1]], pts[t[2]]) <= 0) return false;
  return true;
}

}  // namespace

double min_angle_degrees(const Polygon2& points, const std::vector<std::array<int, 3>>& triangles) {
  double smallest = 180;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d u = points[t[(k + 1) % 3]] - points[t[k]], w = points[t[(k + 2) % 3]] - points[t[k]];
      smallest = std::min(smallest, std::atan2(std::abs(u.x() * w.y() - u.y() * w.x()), u.dot(w)) * 180 / M_PI);
    }
  return smallest;
}

PlanarMesh mesh_polygon(const Polygon2& boundary, double spacing, int smoothing_iterations) {
  const int nb = static_cast<int>(boundary.size());
  if (nb < 3 || !(spacing > 0)) throw Error("mesh_polygon: need a loop of three points and a positive spacing");
  if (signed_area(boundary) <= 0) throw Error("mesh_polygon: the boundary loop is not counter-clockwise");
  PlanarMesh mesh;
  mesh.points = boundary;
  mesh.num_boundary = nb;

  // Interior lattice in rows (alternate rows shifted by half a step). Points
  // closer than half a step to the boundary would sit inside the diametral
  // circle of a boundary edge and push that edge out of the Delaunay triangulation.
  Eigen::Vector2d lo = boundary[0], hi = boundary[0];
  for (const auto& p : boundary) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double row = spacing * std::sqrt(3.0) / 2;
  for (int j = 0; lo.y() + j * row <= hi.y(); ++j)
    for (int i = 0; lo.x() + (i + 0.5 * (j % 2)) * spacing <= hi.x(); ++i) {
      const Eigen::Vector2d p(lo.x() + (i + 0.5 * (j % 2)) * spacing, lo.y() + j * row);
      if (point_in_polygon(boundary, p) && distance_to_boundary(boundary, p) > 0.55 * spacing)
        mesh.points.push_back(p);
    }

  std::vector<Tri> tris = delaunay(mesh.points);
  // Drop the triangles outside the polygon (concave parts of the hull).
  std::erase_if(tris, [&](const Tri& t) {
    return !point_in_polygon(boundary, (mesh.points[t[0]] + mesh.points[t[1]] + mesh.points[t[2]]) / 3);
  });
  std::map<std::pair<int, int>, int> directed;
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (int i = 0; i < nb; ++i)
    if (!directed.count({i, (i + 1) % nb}))
      throw Error("mesh_polygon: boundary edge " + std::to_string(i) + "-" + std::to_string((i + 1) % nb) +
                  " is missing from the triangulation (boundary points too far apart for spacing " +
                  std::to_string(spacing) + ")");

  // Relax the interior: move each point to the mean of its neighbours, undo the
  // moves that would invert a triangle, and restore the Delaunay property.
  const int n = static_cast<int>(mesh.points.size());
  for (int it = 0; it < smoothing_iterations; ++it) {
    std::vector<Eigen::Vector2d> sum(static_cast<std::size_t>(n), Eigen::Vector2d::Zero());
    std::vector<int> count(static_cast<std::size_t>(n), 0);
    for (const auto& [edge, unused] : directed) {
      (void)unused;
      sum[edge.first] += mesh.points[edge.second];
      ++count[edge.first];
    }
    const Polygon2 before = mesh.points;
    for (int v = nb; v < n; ++v)
      if (count[v]) mesh.points[v] = sum[v] / count[v];
    for (int guard = 0; guard < 10 && !all_positive(mesh.points, tris); ++guard)
      for (const Tri& t : tris)
        if (orient(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]) <= 0)
          for (int v : t) mesh.points[v] = before[v];
    if (!all_positive(mesh.points, tris)) mesh.points = before;
    flip_to_delaunay(mesh.points, tris);
    directed.clear();
    for (const Tri& t : tris)
      for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  if (!all_positive(mesh.points, tris)) throw Error("mesh_polygon: an inverted triangle survived smoothing");
  mesh.triangles = std::move(tris);
  return mesh;
}

}  // namespace drape::geometry
