#include "surface_nets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace drape::parametric {
namespace {

// Bounding box of the body from its parts (generous: ellipsoids by their largest axis).
void body_bounds(const ImplicitBody& body, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const Primitive& p : body.parts) {
    if (p.kind == Primitive::Kind::Ellipsoid) {
      const double r = p.semi.maxCoeff();
      lo = lo.cwiseMin((p.a.array() - r).matrix()), hi = hi.cwiseMax((p.a.array() + r).matrix());
    } else {
      const double r = std::max(p.ra, p.rb);
      lo = lo.cwiseMin((p.a.cwiseMin(p.b).array() - r).matrix());
      hi = hi.cwiseMax((p.a.cwiseMax(p.b).array() + r).matrix());
    }
  }
}

}  // namespace

RawMesh surface_nets(const ImplicitBody& body, double cell, const Eigen::Vector2d& offset) {
  // With magnifiers the grid is uniform in the warped space (sampling_warp.hpp):
  // nodes are unwarped to evaluate the body, vertices to place them on it.
  const Magnifiers& warped = body.magnifiers;
  Eigen::Vector3d lo, hi;
  body_bounds(body, lo, hi);
  check_magnifiers(warped);  // each maps a ball onto itself: the bounds stay
  // Symmetric in x about 0 (nodes at +-(i + 1/2) cell), so the mesh is mirror-symmetric.
  const double half_x = std::max(std::abs(lo.x()), std::abs(hi.x())) + 2 * cell;
  const int nx = 2 * static_cast<int>(std::ceil(half_x / cell)) + 1;
  lo.x() = -0.5 * (nx - 1) * cell;
  lo.y() -= (2 + offset.x()) * cell, lo.z() -= (2 + offset.y()) * cell;
  const int ny = static_cast<int>(std::ceil((hi.y() + 2 * cell - lo.y()) / cell)) + 1;
  const int nz = static_cast<int>(std::ceil((hi.z() + 2 * cell - lo.z()) / cell)) + 1;
  auto node = [&](int i, int j, int k) { return (static_cast<std::size_t>(k) * ny + j) * nx + i; };
  auto pos = [&](int i, int j, int k) { return Eigen::Vector3d(lo.x() + i * cell, lo.y() + j * cell, lo.z() + k * cell); };

  std::vector<double> value(static_cast<std::size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        // Nodes surely more than three cells outside only need their sign.
        const Eigen::Vector3d p = warped.empty() ? pos(i, j, k) : unwarp(warped, pos(i, j, k));
        double bound = INFINITY;
        for (const Primitive& part : body.parts) bound = std::min(bound, part.lower_bound(p));
        value[node(i, j, k)] = bound > 3 * cell ? bound : body.eval(p);
      }

  // One vertex per crossed cell, at the mean of its edge crossings.
  std::vector<int> cell_vertex(value.size(), -1);
  std::vector<Eigen::Vector3d> verts;
  static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  static const int edge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        double v[8];
        int inside = 0;
        for (int c = 0; c < 8; ++c) {
          v[c] = value[node(i + corner[c][0], j + corner[c][1], k + corner[c][2])];
          inside += v[c] < 0;
        }
        if (inside == 0 || inside == 8) continue;
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        int n = 0;
        for (const auto& e : edge) {
          const double a = v[e[0]], b = v[e[1]];
          if ((a < 0) == (b < 0)) continue;
          const double t = a / (a - b);
          const Eigen::Vector3d pa = pos(i + corner[e[0]][0], j + corner[e[0]][1], k + corner[e[0]][2]);
          const Eigen::Vector3d pb = pos(i + corner[e[1]][0], j + corner[e[1]][1], k + corner[e[1]][2]);
          sum += pa + t * (pb - pa);
          ++n;
        }
        cell_vertex[node(i, j, k)] = static_cast<int>(verts.size());
        verts.push_back(sum / n);
      }

  std::vector<std::array<int, 3>> tris;
  auto quad = [&](int a, int b, int c, int d, bool flip) {
    if (flip) std::swap(b, d);
    // Split along the shorter diagonal: better-shaped triangles.
    if ((verts[static_cast<std::size_t>(a)] - verts[static_cast<std::size_t>(c)]).squaredNorm() <=
        (verts[static_cast<std::size_t>(b)] - verts[static_cast<std::size_t>(d)]).squaredNorm()) {
      tris.push_back({a, b, c});
      tris.push_back({a, c, d});
    } else {
      tris.push_back({a, b, d});
      tris.push_back({b, c, d});
    }
  };
  auto cv = [&](int i, int j, int k) { return cell_vertex[node(i, j, k)]; };
  for (int k = 1; k + 1 < nz; ++k)
    for (int j = 1; j + 1 < ny; ++j)
      for (int i = 1; i + 1 < nx; ++i) {
        const double v0 = value[node(i, j, k)];
        // Edge along +x: outward is +x when the lower node is inside.
        const double vx = value[node(i + 1, j, k)], vy = value[node(i, j + 1, k)], vz = value[node(i, j, k + 1)];
        if ((v0 < 0) != (vx < 0)) quad(cv(i, j - 1, k - 1), cv(i, j, k - 1), cv(i, j, k), cv(i, j - 1, k), !(v0 < 0));
        if ((v0 < 0) != (vy < 0)) quad(cv(i - 1, j, k - 1), cv(i - 1, j, k), cv(i, j, k), cv(i, j, k - 1), !(v0 < 0));
        if ((v0 < 0) != (vz < 0)) quad(cv(i - 1, j - 1, k), cv(i, j - 1, k), cv(i, j, k), cv(i - 1, j, k), !(v0 < 0));
      }

  RawMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(verts.size()), 3);
  for (std::size_t i = 0; i < verts.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = warped.empty() ? verts[i] : unwarp(warped, verts[i]);
  mesh.faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int c = 0; c < 3; ++c) mesh.faces(static_cast<Eigen::Index>(i), c) = tris[i][static_cast<std::size_t>(c)];
  return mesh;
}

}  // namespace drape::parametric
