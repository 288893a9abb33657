#pragma once
// Plane polygons and polylines (sewing patterns, UV regions). A polygon is a
// closed loop of points without the first point repeated at the end.
#include <Eigen/Core>

#include <vector>

namespace drape::geometry {

using Polygon2 = std::vector<Eigen::Vector2d>;

// Shoelace area: positive for a counter-clockwise loop.
double signed_area(const Polygon2& polygon);

// Even-odd rule; points exactly on the boundary may fall either way.
bool point_in_polygon(const Polygon2& polygon, const Eigen::Vector2d& p);

// Distance from p to the closest point of the segment [a, b].
double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// Distance from p to the polygon's boundary (not signed).
double distance_to_boundary(const Polygon2& polygon, const Eigen::Vector2d& p);

double polyline_length(const Polygon2& polyline);

// `segments` + 1 points at equal arc length along an open polyline, both ends
// included exactly (so two pieces built from one polyline share their ends bit for bit).
Polygon2 resample_polyline(const Polygon2& polyline, int segments);

// A flat [x0, y0, x1, y1, ...] list as points; throws ConfigError naming
// `what` when the count is odd or gives fewer than three points.
Polygon2 polygon_from_flat(const std::vector<double>& flat, const char* what);

}  // namespace drape::geometry
