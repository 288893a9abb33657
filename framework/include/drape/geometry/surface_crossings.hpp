#pragma once
// Where a garment surface and a body surface cross: a measurement beside the
// penetration metric p. p counts garment vertices inside the body and misses
// crossings with no vertex inside (an arm through a sleeve's large triangles);
// an edge of one mesh through a triangle of the other is seen here. Shares no
// code with the contact energies, so it can check them.
#include <Eigen/Core>

#include <vector>

namespace drape::geometry {

struct SurfaceCrossings {
  int garment_edges_through_body = 0;  // garment edges (each undirected edge once) that pierce a body triangle
  int body_edges_through_garment = 0;  // body edges that pierce a garment triangle
  std::vector<int> garment_vertices;   // vertices of the crossing garment edges and of the crossed garment faces (sorted, unique)
  int total() const { return garment_edges_through_body + body_edges_through_garment; }
};

// True when the closed segment (p, q) and the closed triangle (a, b, c) share
// a point: touching counts. Decided by exact orientation signs, so an edge
// through the common edge or vertex of neighbouring triangles is never missed.
// A segment in the triangle's plane counts when it meets the closed triangle
// (an exact 2D test in a projection). A zero-area triangle (collinear corners)
// is never pierced: it has no inside, and a segment through it touches its
// neighbours' closed triangles, which count.
bool segment_pierces_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// Garment edges through body triangles and body edges through garment
// triangles (segment_pierces_triangle). Candidates come from a uniform grid
// over each mesh's triangle boxes, so the cost is about linear in the mesh
// sizes. Neither mesh needs to be closed or oriented. Throws Error naming the
// mesh, face or vertex when a face index is out of range or a vertex is not finite.
SurfaceCrossings surface_crossings(const Eigen::MatrixX3d& garment_vertices, const Eigen::MatrixX3i& garment_faces,
                                   const Eigen::MatrixX3d& body_vertices, const Eigen::MatrixX3i& body_faces);

}  // namespace drape::geometry
