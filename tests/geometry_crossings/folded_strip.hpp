#pragma once
// A strip folded over itself (the untangle's and the garment clearance's
// tests), a bump of its upper layer pushed through the lower one, and a
// count of crossings of this file's own: a brute-force segment-triangle test
// (Moller-Trumbore), not the code under test.
#include <drape/geometry/adjacency.hpp>

#include <Eigen/Core>

#include <cmath>

namespace drape::test {

using V = Eigen::Vector3d;

// Edges (each once, geometry::edge_list) through faces that share no vertex with them, every pair tried.
inline int brute_force_crossings(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces) {
  int count = 0;
  for (const auto& [a, b] : drape::geometry::edge_list(faces))
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      if ((faces.row(f).array() == a).any() || (faces.row(f).array() == b).any()) continue;
      const V p = x.row(a), q = x.row(b), v0 = x.row(faces(f, 0)), v1 = x.row(faces(f, 1)), v2 = x.row(faces(f, 2));
      // Moller-Trumbore on the segment p + t (q - p), t in [0, 1].
      const V d = q - p, e1 = v1 - v0, e2 = v2 - v0, h = d.cross(e2);
      const double det = e1.dot(h);
      if (std::abs(det) < 1e-14) continue;
      const V s = p - v0;
      const double u = s.dot(h) / det;
      const V qv = s.cross(e1);
      const double v = d.dot(qv) / det, t = e2.dot(qv) / det;
      if (u >= 0 && v >= 0 && u + v <= 1 && t >= 0 && t <= 1) ++count;
    }
  return count;
}

// A strip of cols x rows vertices, parameter u in [0, 2] along its length:
// the lower layer (u <= 1) at z = 0 from x = 0 to 1, folded at x = 1 into
// the upper layer (u > 1) at z = height running back to x = upper_end, shifted
// 1.37 mm along y. Vertex (i, j)
// is i + cols * j.
struct Strip {
  Eigen::MatrixX3d x;
  Eigen::MatrixX3i faces;
  int cols, rows;
  int at(int i, int j) const { return i + cols * j; }
};

// Two triangles a grid cell, turning to +z where the grid runs along +x and +y.
inline void grid_faces(Strip& s) {
  int f = 0;
  for (int j = 0; j + 1 < s.rows; ++j)
    for (int i = 0; i + 1 < s.cols; ++i) {
      s.faces.row(f++) << s.at(i, j), s.at(i + 1, j), s.at(i + 1, j + 1);
      s.faces.row(f++) << s.at(i, j), s.at(i + 1, j + 1), s.at(i, j + 1);
    }
}

inline Strip folded_strip(int cols, int rows, double height, double upper_end = 0.0) {
  Strip s{Eigen::MatrixX3d(cols * rows, 3), Eigen::MatrixX3i(2 * (cols - 1) * (rows - 1), 3), cols, rows};
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const double u = 2.0 * i / (cols - 1), y = static_cast<double>(j) / (rows - 1);
      // (The upper layer a little off the lower one's grid lines, so that no
      // edge passes exactly through another's: a touch each count may read its own way.)
      const double x = u <= 1 ? u : 1 - (u - 1) * (1 - upper_end);
      s.x.row(s.at(i, j)) << x, (u <= 1 ? y : y + 0.0137), (u <= 1 ? 0.0 : height);
    }
  grid_faces(s);
  return s;
}

// The upper layer pushed down round (cx, cy) to `depth` below z = 0 within
// radius r, easing back to its height over another r.
inline void push_bump(Strip& s, double cx, double cy, double r, double depth, double height) {
  for (int v = 0; v < s.x.rows(); ++v) {
    if (s.x(v, 2) <= 0) continue;  // the lower layer
    const double d = std::hypot(s.x(v, 0) - cx, s.x(v, 1) - cy);
    const double w = d <= r ? 1.0 : d >= 2 * r ? 0.0 : 0.5 * (1 + std::cos(M_PI * (d - r) / r));
    s.x(v, 2) = height - w * (height + depth);
  }
}

}  // namespace drape::test
