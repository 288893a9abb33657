// Winding numbers by signed ray crossings (drape/geometry/winding.hpp).
#include <drape/errors.hpp>
#include <drape/geometry/winding.hpp>

#include "exact_orientation.hpp"
#include "triangle_grid.hpp"

#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace drape::geometry {

namespace {

// Ray directions tried in turn: each nearly along an axis, so that the
// ray's box (the broad phase's query) is a thin prism, and tilted by
// irrational amounts, so that it does not run along the edges of meshes built
// on grids or symmetric about a plane.
const std::array<Eigen::Vector3d, 6> kDirections{
    Eigen::Vector3d(1.0, 1.414213562e-3, 1.732050807e-3), Eigen::Vector3d(-2.236067977e-3, 1.0, 2.645751311e-3),
    Eigen::Vector3d(3.162277660e-3, -1.618033988e-3, 1.0), Eigen::Vector3d(-1.0, 2.718281828e-3, -3.141592653e-3),
    Eigen::Vector3d(1.259921049e-3, -1.0, -2.449489742e-3), Eigen::Vector3d(-2.828427124e-3, 3.316624790e-3, -1.0)};

enum class Crossing { kNone, kOut, kIn, kDegenerate, kOnSurface };

// How the segment p -> q passes the triangle (a, b, c), whose normal
// (b - a) x (c - a) points out: out through its front, in through it, not at
// all, through an edge or vertex or along its plane (degenerate: cast again),
// or p lies on it.
Crossing classify(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const int sp = exact::orient3d(a, b, c, p), sq = exact::orient3d(a, b, c, q);
  if (sp == sq && sp != 0) return Crossing::kNone;  // both ends on one side
  const int e0 = exact::orient3d(p, q, a, b), e1 = exact::orient3d(p, q, b, c), e2 = exact::orient3d(p, q, c, a);
  const bool outside_an_edge = (e0 > 0 || e1 > 0 || e2 > 0) && (e0 < 0 || e1 < 0 || e2 < 0);
  if (outside_an_edge) return Crossing::kNone;  // the line passes beside the triangle
  if (sp == 0 && sq == 0) {
    // The ray lies in the triangle's plane, or the triangle has no plane:
    // collinear corners (zero area) enclose nothing and count for nothing.
    const bool collinear = exact::orient3d(a, b, c, a + Eigen::Vector3d::UnitX()) == 0 &&
                           exact::orient3d(a, b, c, a + Eigen::Vector3d::UnitY()) == 0 &&
                           exact::orient3d(a, b, c, a + Eigen::Vector3d::UnitZ()) == 0;
    return collinear ? Crossing::kNone : Crossing::kDegenerate;
  }
  // Otherwise the line meets the plane at one point and the closed triangle
  // there; if p is in the plane, that point is p, on the surface.
  if (sp == 0) return Crossing::kOnSurface;
  if (sq == 0) return Crossing::kDegenerate;  // q in the plane of a face: cast again
  if (e0 == 0 || e1 == 0 || e2 == 0) return Crossing::kDegenerate;  // through an edge or a vertex
  return sp < 0 ? Crossing::kOut : Crossing::kIn;
}

}  // namespace

std::vector<int> winding_numbers(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& vertices,
                                 const Eigen::MatrixX3i& faces) {
  const Eigen::Index nv = vertices.rows();
  if (!vertices.allFinite()) throw Error("winding numbers: a vertex of the surface is not finite");
  if (!points.allFinite()) throw Error("winding numbers: a query point is not finite");
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= nv)
        throw Error("winding numbers: face " + std::to_string(f) + " names vertex " + std::to_string(faces(f, k)) +
                    " of a surface with " + std::to_string(nv));
  std::vector<int> winding(static_cast<std::size_t>(points.rows()), 0);
  if (points.rows() == 0 || faces.rows() == 0) return winding;

  const TriangleGrid grid(vertices, faces);
  const Eigen::Vector3d lo = vertices.colwise().minCoeff().transpose(), hi = vertices.colwise().maxCoeff().transpose();

  // Points whose ray is still to be cast; each pass casts them along the next direction.
  std::vector<int> pending(static_cast<std::size_t>(points.rows()));
  for (std::size_t i = 0; i < pending.size(); ++i) pending[i] = static_cast<int>(i);
  for (const Eigen::Vector3d& direction : kDirections) {
    const Eigen::Vector3d unit = direction.normalized();
    std::vector<int> next;
    for (int i : pending) {
      const Eigen::Vector3d p = points.row(i).transpose();
      // Far enough to leave the mesh's box from anywhere: past every corner.
      const Eigen::Vector3d far = p + ((hi - lo).norm() + (p - 0.5 * (lo + hi)).norm() + 1e-3) * unit;
      int count = 0;
      Crossing stop = Crossing::kNone;  // a degenerate crossing or p on the surface ends the ray's count
      grid.find(p.cwiseMin(far), p.cwiseMax(far), [&](int f) {
        const Crossing c = classify(p, far, vertices.row(faces(f, 0)).transpose(), vertices.row(faces(f, 1)).transpose(),
                                    vertices.row(faces(f, 2)).transpose());
        if (c == Crossing::kOut) ++count;
        if (c == Crossing::kIn) --count;
        if (c == Crossing::kDegenerate || c == Crossing::kOnSurface) stop = c;
        return stop != Crossing::kNone;
      });
      if (stop == Crossing::kDegenerate) next.push_back(i);
      else winding[static_cast<std::size_t>(i)] = stop == Crossing::kOnSurface ? kOnSurface : count;
    }
    pending = std::move(next);
    if (pending.empty()) return winding;
  }
  throw Error("winding numbers: every ray from point " + std::to_string(pending.front()) +
              " met an edge or a vertex of the surface");
}

}  // namespace drape::geometry
