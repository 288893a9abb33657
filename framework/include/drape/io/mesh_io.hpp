#pragma once
// Reading and writing triangle meshes without ever changing vertex order or
// count, because the vertex order is the identity of a fixed-topology mesh
// (a body model, a garment template). (A PLY or glTF of a mesh with UV seams
// holds more rows than the mesh: one UV a row, so a seam vertex gets a copy
// per other UV, appended after all the mesh's own vertices, which keep their
// order; read_mesh merges the copies back. docs/formats.md, "Meshes".)
//
// Formats: .obj is parsed and written by our own code (assimp reorders OBJ
// vertices per face corner). Everything else assimp reads (.ply, .gltf, .glb,
// .stl, ...) is read through assimp; .ply, .gltf and .glb are written through
// assimp's exporter. See framework/src/io/assimp_mesh_reader.cpp for what
// assimp does to vertex order and how it is undone.
//
// Every problem with an input file is a ConfigError naming the file (and the
// line for OBJ). Outputs are written atomically.
#include <drape/mesh.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace drape {

// Triangle mesh by extension. Polygons are split into a fan (0,i,i+1) that keeps
// the corner order, so polygon f with n corners becomes n-2 consecutive triangles.
Mesh read_mesh(const std::filesystem::path& file);

// A triangle mesh with the material of every triangle: an OBJ's `usemtl`
// names; through assimp the material of each of the file's meshes (glTF/GLB:
// each primitive's material, by its name). Triangles without one are in
// "default". read_mesh's mesh, the same vertices and triangles.
struct MaterialMesh {
  Mesh mesh;
  std::vector<std::string> material_names;  // in order of first use by a triangle
  std::vector<int> face_material;           // per triangle, index into material_names
};
MaterialMesh read_mesh_with_materials(const std::filesystem::path& file);

// .obj (v, vt, f v/vt), .ply (binary), .gltf (one file, buffer embedded) or .glb.
// Throws ConfigError for an unknown extension or a missing folder; an invalid
// mesh (index out of range, non-finite value) is an Error. Nothing is left
// behind when writing fails.
void write_mesh(const std::filesystem::path& file, const Mesh& mesh);
// What write_mesh checks of `file` before writing (its format, its folder),
// for a command to call before it computes the mesh: ConfigError when it fails.
void check_mesh_output(const std::filesystem::path& file);

// An OBJ file as written: polygons with their corners in file order, and the
// group (`g` or `o`, the later one wins) of every face.
struct PolygonMesh {
  Eigen::MatrixX3d vertices;            // [V, 3], every `v` line in order, used or not
  Eigen::MatrixX2d uv;                  // [T, 2], every `vt` line (empty if faces have no vt)
  std::vector<int> face_start{0};       // face f has corners face_start[f] .. face_start[f+1]-1
  std::vector<int> corner_vertex;       // 0-based vertex per corner
  std::vector<int> corner_uv;           // 0-based uv per corner (empty if faces have no vt)
  std::vector<std::string> group_names; // distinct names, in order of first use by a face;
                                        // faces before any g/o are in group "default"
  std::vector<int> face_group;          // per face, index into group_names
  std::vector<std::string> material_names; // `usemtl` names in order of first use by a face;
                                           // faces before any usemtl are in material "default"
  std::vector<int> face_material;       // per face, index into material_names

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_faces() const { return static_cast<int>(face_start.size()) - 1; }
  int face_size(int f) const { return face_start[f + 1] - face_start[f]; }
};

PolygonMesh read_obj_polygons(const std::filesystem::path& file);

// Fan triangulation as in read_mesh; keeps every vertex (used or not) in order.
Mesh triangulate(const PolygonMesh& polygons);

// Sorted distinct vertices used by the faces of `group`; ConfigError naming
// `what` (e.g. the file) if there is no such group.
std::vector<int> group_vertices(const PolygonMesh& polygons, const std::string& group,
                                const std::string& what);

// Throws ConfigError "<what_file> has N vertices, expected M (<why>)".
void require_vertex_count(const Mesh& mesh, int expected, const std::string& what_file,
                          const std::string& why);
// Short form for the common case: "<what> has N vertices, expected M".
void require_vertex_count(const Mesh& mesh, int expected, const std::string& what);

}  // namespace drape
