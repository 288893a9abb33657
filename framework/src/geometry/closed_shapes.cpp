#include <drape/geometry/closed_shapes.hpp>

#include <drape/errors.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace drape::geometry {

Mesh icosphere(int level, double radius) {
  if (level < 0 || level > 8) throw Error("icosphere: level " + std::to_string(level) + " outside [0, 8]");
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<Eigen::Vector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<Eigen::Vector3i> next;
    next.reserve(4 * f.size());
    for (const auto& tri : f) {
      const int ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
      next.insert(next.end(), {{tri[0], ab, ca}, {tri[1], bc, ab}, {tri[2], ca, bc}, {ab, bc, ca}});
    }
    f = std::move(next);
  }
  Mesh m;
  m.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.vertices.row(static_cast<Eigen::Index>(i)) = radius * v[i];
  m.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.faces.row(static_cast<Eigen::Index>(i)) = f[i];
  return m;
}

Mesh torus(double major, double minor, int ring_segments, int tube_segments) {
  if (ring_segments < 3 || tube_segments < 3 || !(minor > 0) || !(major > minor))
    throw Error("torus: needs 3+ segments each way and major > minor > 0");
  const int nu = ring_segments, nv = tube_segments;
  Mesh m;
  m.vertices.resize(nu * nv, 3);
  m.faces.resize(2 * nu * nv, 3);
  const double two_pi = 2 * std::numbers::pi;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = two_pi * i / nu, w = two_pi * j / nv;
      const double r = major + minor * std::cos(w);
      m.vertices.row(i * nv + j) << r * std::cos(u), minor * std::sin(w), -r * std::sin(u);
    }
  // With u turning from +X towards -Z about +Y and w turning outward-then-up,
  // (d/du) x (d/dw) points out of the tube; each quad is split along one diagonal.
  int k = 0;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const int a = i * nv + j, b = ((i + 1) % nu) * nv + j, c = ((i + 1) % nu) * nv + (j + 1) % nv,
                d = i * nv + (j + 1) % nv;
      m.faces.row(k++) << a, b, c;
      m.faces.row(k++) << a, c, d;
    }
  return m;
}

}  // namespace drape::geometry
