#pragma once
// Triangle meshes in double precision. Vertex order is the identity of a
// fixed-topology mesh and is never changed by I/O. UVs are kept per face
// corner (uv + uv_faces) so that UV seams never duplicate vertices.
#include <Eigen/Core>
#include <string>

namespace drape {

struct Mesh {
  Eigen::MatrixX3d vertices;  // [V, 3], meters, Y up
  Eigen::MatrixX3i faces;     // [F, 3], counter-clockwise seen from outside
  Eigen::MatrixX2d uv;        // [T, 2] texture/material coordinates (may be empty)
  Eigen::MatrixX3i uv_faces;  // [F, 3] indices into uv, one per corner (empty if no uv)

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_faces() const { return static_cast<int>(faces.rows()); }
  bool has_uv() const { return uv.rows() > 0 && uv_faces.rows() == faces.rows(); }
};

}  // namespace drape
