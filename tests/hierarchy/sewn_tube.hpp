#pragma once
// A test garment: an open tube (a sleeve) sewn from two rectangular panels along
// two seams, with per-corner UVs. UV is material space (metres of unrolled
// cloth); each panel is its own UV chart, so the seam vertices have two UVs.
// Interior grid points are jittered (the same jitter in 3D and UV) so that the
// mesh is not a perfectly regular grid. Shared by tests/hierarchy and tests/spectral.
#include <drape/mesh.hpp>

#include <cmath>
#include <random>

namespace drape::test {

// `around` vertices per panel row (excluding the seam column it shares with
// the other panel), `rows` rows: 2 * around * rows vertices in all.
inline Mesh sewn_tube(int around, int rows, double jitter = 0.25, unsigned seed = 7) {
  const double radius = 0.1, length = 0.5;
  const double circumference = 2 * M_PI * radius;
  const int columns = 2 * around;  // vertices per ring
  const double du = circumference / columns, dv = length / (rows - 1);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-jitter, jitter);

  Mesh m;
  m.vertices.resize(columns * rows, 3);
  Eigen::MatrixX2d arc(columns * rows, 2);  // unrolled (arc length, height) per vertex
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const bool on_seam = c % around == 0;  // columns 0 and `around` are the seams
      const bool on_edge = r == 0 || r == rows - 1;
      const double s = (c + (on_seam ? 0.0 : uni(rng))) * du;
      const double h = (r + (on_edge ? 0.0 : uni(rng))) * dv;
      const double theta = s / radius;
      // A gentle bulge so the surface is not developable everywhere.
      const double rr = radius * (1.0 + 0.15 * std::sin(M_PI * h / length) * std::cos(2 * theta));
      const int i = r * columns + c;
      m.vertices.row(i) << rr * std::cos(theta), h, -rr * std::sin(theta);
      arc.row(i) << s, h;
    }
  // UVs: panel p holds columns p*around .. p*around + around (the last one is the
  // other seam), placed side by side with a gap.
  const int panel_cols = around + 1;
  m.uv.resize(2 * panel_cols * rows, 2);
  auto uv_index = [&](int panel, int local_col, int r) { return (panel * rows + r) * panel_cols + local_col; };
  for (int p = 0; p < 2; ++p)
    for (int r = 0; r < rows; ++r)
      for (int lc = 0; lc < panel_cols; ++lc) {
        const int c = (p * around + lc) % columns;
        const Eigen::Vector2d a = arc.row(r * columns + c);
        const double s_local = lc == around ? around * du : a.x() - p * around * du;
        m.uv.row(uv_index(p, lc, r)) << s_local + p * (around * du + 0.05), a.y();
      }
  const int quads = columns * (rows - 1);
  m.faces.resize(2 * quads, 3);
  m.uv_faces.resize(2 * quads, 3);
  int f = 0;
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const int p = c / around, lc = c % around;
      const int c1 = (c + 1) % columns;
      const int v00 = r * columns + c, v01 = r * columns + c1, v10 = (r + 1) * columns + c, v11 = (r + 1) * columns + c1;
      const int t00 = uv_index(p, lc, r), t01 = uv_index(p, lc + 1, r), t10 = uv_index(p, lc, r + 1),
                t11 = uv_index(p, lc + 1, r + 1);
      // Counter-clockwise in UV and seen from outside; alternate diagonals so
      // that no direction is preferred.
      if ((r + c) % 2 == 0) {
        m.faces.row(f) << v00, v11, v10;
        m.uv_faces.row(f++) << t00, t11, t10;
        m.faces.row(f) << v00, v01, v11;
        m.uv_faces.row(f++) << t00, t01, t11;
      } else {
        m.faces.row(f) << v00, v01, v10;
        m.uv_faces.row(f++) << t00, t01, t10;
        m.faces.row(f) << v01, v11, v10;
        m.uv_faces.row(f++) << t01, t11, t10;
      }
    }
  return m;
}

}  // namespace drape::test
