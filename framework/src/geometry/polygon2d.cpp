#include <drape/geometry/polygon2d.hpp>

#include <drape/errors.hpp>

#include "exact_orientation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace drape::geometry {

double signed_area(const Polygon2& polygon) {
  double twice = 0;
  for (std::size_t i = 0, n = polygon.size(); i < n; ++i) {
    const Eigen::Vector2d &a = polygon[i], &b = polygon[(i + 1) % n];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

bool point_in_polygon(const Polygon2& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, n = polygon.size(), j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d &a = polygon[i], &b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

double distance_to_boundary(const Polygon2& polygon, const Eigen::Vector2d& p) {
  double best = INFINITY;
  for (std::size_t i = 0, n = polygon.size(); i < n; ++i)
    best = std::min(best, distance_to_segment(p, polygon[i], polygon[(i + 1) % n]));
  return best;
}

double polyline_length(const Polygon2& polyline) {
  double length = 0;
  for (std::size_t i = 1; i < polyline.size(); ++i) length += (polyline[i] - polyline[i - 1]).norm();
  return length;
}

Polygon2 resample_polyline(const Polygon2& polyline, int segments) {
  if (polyline.size() < 2 || segments < 1) throw Error("resample_polyline: need two points and one segment");
  const double total = polyline_length(polyline);
  Polygon2 out{polyline.front()};
  std::size_t piece = 1;
  double start = 0;  // arc length at polyline[piece - 1]
  for (int k = 1; k < segments; ++k) {
    const double target = total * k / segments;
    while (piece + 1 < polyline.size() && start + (polyline[piece] - polyline[piece - 1]).norm() < target) {
      start += (polyline[piece] - polyline[piece - 1]).norm();
      ++piece;
    }
    const double len = (polyline[piece] - polyline[piece - 1]).norm();
    const double t = len > 0 ? std::clamp((target - start) / len, 0.0, 1.0) : 0.0;
    out.push_back(polyline[piece - 1] + t * (polyline[piece] - polyline[piece - 1]));
  }
  out.push_back(polyline.back());
  return out;
}

Polygon2 polygon_from_flat(const std::vector<double>& flat, const char* what) {
  if (flat.size() % 2 != 0 || flat.size() < 6)
    throw ConfigError(std::string(what) + ": expected x, y pairs of at least three points, got " +
                      std::to_string(flat.size()) + " numbers");
  Polygon2 out;
  for (std::size_t i = 0; i < flat.size(); i += 2) out.emplace_back(flat[i], flat[i + 1]);
  // A loop that crosses itself (a bow tie) or encloses nothing was taken
  // without a word (an outside check): which region it means is not clear.
  const std::size_t n = out.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // neighbours through the loop's closing edge
      if (exact::segments_meet_2d(out[i], out[(i + 1) % n], out[j], out[(j + 1) % n]))
        throw ConfigError(std::string(what) + ": the loop crosses itself (its edge from point " + std::to_string(i + 1) +
                          " and its edge from point " + std::to_string(j + 1) + "): give the corners in order around the region");
    }
  if (!(std::abs(signed_area(out)) > 1e-12))
    throw ConfigError(std::string(what) + ": the loop encloses no area (its points lie on a line or on one spot)");
  return out;
}

}  // namespace drape::geometry
