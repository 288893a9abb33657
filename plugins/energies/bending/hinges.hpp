#pragma once
// The interior edges (hinges) of a triangle mesh, found from its 3D topology
// (mesh.faces): faces on either side of a UV seam share vertex indices and so
// form a hinge even though their UV corners differ.
#include <drape/mesh.hpp>

#include <vector>

namespace drape::bending {

struct HingeTopology {
  int vertex[4];  // x0 -> x1 the edge as it runs in face[0], x2 face[0]'s tip, x3 face[1]'s tip
  int face[2];
  int corner[2];  // the edge is face[i]'s corners (corner[i], corner[i] + 1 mod 3)
};

// Every edge shared by exactly two faces, in increasing order of (min, max)
// vertex index. Boundary edges (one face) are not hinges. Throws ConfigError
// when a face repeats a vertex or an edge is shared by more than two faces
// (the garment must be a manifold surface).
std::vector<HingeTopology> find_hinges(const Mesh& mesh);

}  // namespace drape::bending
