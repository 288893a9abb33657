#pragma once
// Triangulates a plane polygon with near-equilateral triangles: the boundary
// points are kept as given, the interior is a regular triangular lattice in rows,
// Delaunay-triangulated, then relaxed (Laplacian smoothing + Delaunay edge flips
// that never touch the boundary). Meant for sewing-pattern panels, whose seams
// must keep exactly the points the caller chose so that panels can share them.
#include <drape/geometry/polygon2d.hpp>

#include <array>
#include <vector>

namespace drape::geometry {

struct PlanarMesh {
  Polygon2 points;                          // boundary points first (caller's order), then interior
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise
  int num_boundary = 0;
};

// `boundary`: counter-clockwise loop whose consecutive points are at most about
// `spacing` apart. Throws Error when the result would not be a valid
// triangulation of the polygon (a boundary edge missing, a triangle inverted).
PlanarMesh mesh_polygon(const Polygon2& boundary, double spacing, int smoothing_iterations = 10);

// The smallest corner angle over all triangles, in degrees.
double min_angle_degrees(const Polygon2& points, const std::vector<std::array<int, 3>>& triangles);

}  // namespace drape::geometry
