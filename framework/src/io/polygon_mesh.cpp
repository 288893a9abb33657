// From the polygons of an OBJ file to the triangle mesh the rest of drape uses.
#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>

#include <Eigen/Geometry>

#include <algorithm>

namespace drape {

namespace {

// The apex corner (an offset into the polygon's corners) of polygon f's fan:
// its first corner, as ever, unless that fan has a triangle of no area in
// space or in the UVs (a hexagon whose first three corners lie on one UV
// row was refused as "face 0 is degenerate": an outside check); then the
// corner whose fan's smallest triangle is the largest, each triangle's area
// measured against the polygon's own extent. A fan keeps the corner order,
// so the triangles keep the polygon's orientation whatever the apex.
int fan_apex(const PolygonMesh& polygons, int f, bool with_uv) {
  const int c0 = polygons.face_start[f], n = polygons.face_size(f);
  if (n <= 3) return 0;
  const auto corner = [&](int k, bool uv) -> Eigen::Vector3d {
    const int c = c0 + (k % n);
    if (!uv) return polygons.vertices.row(polygons.corner_vertex[c]).transpose();
    const Eigen::RowVector2d t = polygons.uv.row(polygons.corner_uv[c]);
    return {t.x(), t.y(), 0.0};
  };
  // The polygon's extent squared, in space and in the UVs.
  double extent2[2] = {1e-300, 1e-300};
  for (const bool uv : {false, true}) {
    if (uv && !with_uv) continue;
    Eigen::Vector3d lo = corner(0, uv), hi = lo;
    for (int k = 1; k < n; ++k) lo = lo.cwiseMin(corner(k, uv)), hi = hi.cwiseMax(corner(k, uv));
    extent2[uv] = std::max((hi - lo).squaredNorm(), 1e-300);
  }
  // The smallest triangle of the fan from `apex`, as a share of that extent (in space, and in the UVs).
  const auto smallest = [&](int apex) {
    double least = 1e300;
    for (const bool uv : {false, true}) {
      if (uv && !with_uv) continue;
      for (int k = 1; k + 1 < n; ++k) {
        const Eigen::Vector3d a = corner(apex, uv), b = corner(apex + k, uv), c = corner(apex + k + 1, uv);
        least = std::min(least, 0.5 * (b - a).cross(c - a).norm() / extent2[uv]);
      }
    }
    return least;
  };
  constexpr double kNoArea = 1e-6;
  int best = 0;
  double best_area = smallest(0);
  if (best_area > kNoArea) return 0;
  for (int apex = 1; apex < n; ++apex)
    if (const double a = smallest(apex); a > best_area) best = apex, best_area = a;
  return best;
}

}  // namespace

Mesh triangulate(const PolygonMesh& polygons) {
  Mesh mesh;
  mesh.vertices = polygons.vertices;
  const int faces = polygons.num_faces();
  int triangles = 0;
  for (int f = 0; f < faces; ++f) triangles += polygons.face_size(f) - 2;
  const bool with_uv = polygons.uv.rows() > 0 && !polygons.corner_uv.empty();
  mesh.faces.resize(triangles, 3);
  if (with_uv) {
    mesh.uv = polygons.uv;
    mesh.uv_faces.resize(triangles, 3);
  }
  // A fan keeps the corner order (and so the orientation), and gives the
  // same triangles for the same polygon every time: from the first corner,
  // or another where that fan has a triangle of no area (fan_apex).
  int t = 0;
  for (int f = 0; f < faces; ++f) {
    const int c0 = polygons.face_start[f], n = polygons.face_size(f), apex = fan_apex(polygons, f, with_uv);
    const auto at = [&](int k) { return c0 + (apex + k) % n; };
    for (int k = 1; k + 1 < n; ++k, ++t) {
      mesh.faces.row(t) << polygons.corner_vertex[at(0)], polygons.corner_vertex[at(k)], polygons.corner_vertex[at(k + 1)];
      if (with_uv) mesh.uv_faces.row(t) << polygons.corner_uv[at(0)], polygons.corner_uv[at(k)], polygons.corner_uv[at(k + 1)];
    }
  }
  return mesh;
}

std::vector<int> group_vertices(const PolygonMesh& polygons, const std::string& group, const std::string& what) {
  const auto found = std::find(polygons.group_names.begin(), polygons.group_names.end(), group);
  if (found == polygons.group_names.end())
    throw ConfigError(what + ": no group '" + group + "'" + did_you_mean(group, polygons.group_names));
  const int id = static_cast<int>(found - polygons.group_names.begin());
  std::vector<char> used(static_cast<std::size_t>(polygons.num_vertices()), 0);
  for (int f = 0; f < polygons.num_faces(); ++f) {
    if (polygons.face_group[f] != id) continue;
    for (int c = polygons.face_start[f]; c < polygons.face_start[f + 1]; ++c) used[polygons.corner_vertex[c]] = 1;
  }
  std::vector<int> vertices;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (used[v]) vertices.push_back(static_cast<int>(v));
  return vertices;
}

}  // namespace drape
