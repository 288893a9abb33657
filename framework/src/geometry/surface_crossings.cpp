// Garment edges through body triangles and body edges through garment
// triangles. Each mesh's triangles are listed in a uniform grid over their
// bounding boxes; each edge of the other mesh tests only the triangles whose
// boxes overlap its own, with exact orientation signs (exact_orientation.hpp).
#include <drape/energy.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include "exact_orientation.hpp"
#include "triangle_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace drape::geometry {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// The projection along `axis`: the other two coordinates.
Vec2 dropping(const Vec3& p, int axis) { return {p[(axis + 1) % 3], p[(axis + 2) % 3]}; }

// p in the closed counter-clockwise triangle (a, b, c).
bool in_triangle_2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return exact::orient2d(a, b, p) >= 0 && exact::orient2d(b, c, p) >= 0 && exact::orient2d(c, a, p) >= 0;
}

// All five points in one plane. Dropping an axis along which the triangle
// keeps a non-zero area maps that plane one-to-one onto the other two, so the
// 2D answer is the 3D one. None exists for a zero-area triangle: not pierced.
bool coplanar_segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  for (int axis = 0; axis < 3; ++axis) {
    Vec2 a2 = dropping(a, axis), b2 = dropping(b, axis), c2 = dropping(c, axis);
    const int turn = exact::orient2d(a2, b2, c2);
    if (turn == 0) continue;
    if (turn < 0) std::swap(b2, c2);
    const Vec2 p2 = dropping(p, axis), q2 = dropping(q, axis);
    // A segment meeting a convex region either ends in it or crosses its boundary.
    return in_triangle_2d(p2, a2, b2, c2) || in_triangle_2d(q2, a2, b2, c2) || exact::segments_meet_2d(p2, q2, a2, b2) ||
           exact::segments_meet_2d(p2, q2, b2, c2) || exact::segments_meet_2d(p2, q2, c2, a2);
  }
  return false;
}

// Faces' vertex indices in range and vertices finite; the message names the mesh.
void check_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, const std::string& mesh) {
  for (Eigen::Index i = 0; i < vertices.rows(); ++i)
    if (!vertices.row(i).allFinite())
      throw Error("surface crossings: " + mesh + " vertex " + std::to_string(i) + " is not finite");
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= vertices.rows())
        throw Error("surface crossings: " + mesh + " face " + std::to_string(f) + " has vertex index " +
                    std::to_string(faces(f, k)) + ", but the " + mesh + " has " + std::to_string(vertices.rows()) +
                    " vertices");
}

Vec3 corner(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, int f, int k) {
  return vertices.row(faces(f, k)).transpose();
}

}  // namespace

bool segment_pierces_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int side_p = exact::orient3d(a, b, c, p), side_q = exact::orient3d(a, b, c, q);
  if (side_p * side_q > 0) return false;  // both strictly on one side of the plane
  if (side_p == 0 && side_q == 0) return coplanar_segment_meets_triangle(p, q, a, b, c);
  // The segment reaches the plane in one point (and the triangle has an area:
  // p or q is off its plane). There, the line meets the closed triangle iff it
  // passes no edge on the wrong side: the volumes (p, q, edge) never have
  // strictly opposite signs.
  const int s1 = exact::orient3d(p, q, a, b), s2 = exact::orient3d(p, q, b, c), s3 = exact::orient3d(p, q, c, a);
  const bool some_positive = s1 > 0 || s2 > 0 || s3 > 0, some_negative = s1 < 0 || s2 < 0 || s3 < 0;
  return !(some_positive && some_negative);
}

SurfaceCrossings surface_crossings(const Eigen::MatrixX3d& garment_vertices, const Eigen::MatrixX3i& garment_faces,
                                   const Eigen::MatrixX3d& body_vertices, const Eigen::MatrixX3i& body_faces) {
  check_mesh(garment_vertices, garment_faces, "garment");
  check_mesh(body_vertices, body_faces, "body");
  SurfaceCrossings out;
  std::vector<char> marked(static_cast<std::size_t>(garment_vertices.rows()), 0);

  const TriangleGrid body_grid(body_vertices, body_faces);
  for (const auto& [i, j] : edge_list(garment_faces)) {
    const Vec3 p = garment_vertices.row(i), q = garment_vertices.row(j);
    const bool pierces = body_grid.find(p.cwiseMin(q), p.cwiseMax(q), [&](int f) {
      return segment_pierces_triangle(p, q, corner(body_vertices, body_faces, f, 0), corner(body_vertices, body_faces, f, 1),
                                      corner(body_vertices, body_faces, f, 2));
    });
    if (!pierces) continue;
    ++out.garment_edges_through_body;
    marked[static_cast<std::size_t>(i)] = marked[static_cast<std::size_t>(j)] = 1;
  }

  // Every crossed garment face is wanted (for its vertices), so no early stop.
  const TriangleGrid garment_grid(garment_vertices, garment_faces);
  for (const auto& [i, j] : edge_list(body_faces)) {
    const Vec3 p = body_vertices.row(i), q = body_vertices.row(j);
    bool pierces = false;
    garment_grid.find(p.cwiseMin(q), p.cwiseMax(q), [&](int f) {
      if (segment_pierces_triangle(p, q, corner(garment_vertices, garment_faces, f, 0),
                                   corner(garment_vertices, garment_faces, f, 1), corner(garment_vertices, garment_faces, f, 2))) {
        pierces = true;
        for (int k = 0; k < 3; ++k) marked[static_cast<std::size_t>(garment_faces(f, k))] = 1;
      }
      return false;
    });
    if (pierces) ++out.body_edges_through_garment;
  }

  for (std::size_t v = 0; v < marked.size(); ++v)
    if (marked[v]) out.garment_vertices.push_back(static_cast<int>(v));
  return out;
}

}  // namespace drape::geometry
