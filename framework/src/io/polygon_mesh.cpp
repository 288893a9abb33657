// From the polygons of an OBJ file to the triangle mesh the rest of drape uses.
#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>

#include <algorithm>

namespace drape {

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
  // A fan from the first corner keeps the corner order (and so the orientation),
  // and gives the same triangles for the same polygon every time.
  int t = 0;
  for (int f = 0; f < faces; ++f) {
    const int c0 = polygons.face_start[f];
    for (int c = c0 + 1; c + 1 < polygons.face_start[f + 1]; ++c, ++t) {
      mesh.faces.row(t) << polygons.corner_vertex[c0], polygons.corner_vertex[c], polygons.corner_vertex[c + 1];
      if (with_uv) mesh.uv_faces.row(t) << polygons.corner_uv[c0], polygons.corner_uv[c], polygons.corner_uv[c + 1];
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
