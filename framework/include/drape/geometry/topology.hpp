#pragma once
// Manifoldness, watertightness and orientation of triangle meshes.
#include <Eigen/Core>

#include <array>
#include <string>

namespace drape::geometry {

struct TopologyReport {
  int num_vertices = 0;
  int num_faces = 0;
  int num_edges = 0;
  int boundary_edges = 0;         // edges with one face
  int nonmanifold_edges = 0;      // edges with more than two faces
  int misoriented_edges = 0;      // interior edges whose two faces run it the same way
  int nonmanifold_vertices = 0;   // vertices whose faces do not form a single fan
  int unreferenced_vertices = 0;  // vertices used by no face
  int boundary_loops = 0;         // closed chains of boundary edges
  int euler_characteristic = 0;   // V - E + F (2 for a closed genus-0 surface)
  std::array<int, 2> first_nonmanifold_edge{-1, -1};  // its vertices (lower first), for messages; -1 when none

  bool manifold() const { return nonmanifold_edges == 0 && nonmanifold_vertices == 0; }
  bool watertight() const { return boundary_edges == 0; }
  bool oriented() const { return misoriented_edges == 0; }
  // A closed, consistently oriented 2-manifold with every vertex used.
  bool closed_manifold() const { return manifold() && watertight() && oriented() && unreferenced_vertices == 0; }
  std::string str() const;
};

TopologyReport check_topology(const Eigen::MatrixX3i& faces, int num_vertices);

}  // namespace drape::geometry
