#pragma once
// Closed triangle meshes with known geometry, for tests and benchmarks of
// geometry code (signed distances have an analytic truth on them).
// Faces are counter-clockwise seen from outside.
#include <drape/mesh.hpp>

namespace drape::geometry {

// Subdivided icosahedron on a sphere of `radius` about the origin:
// 10 * 4^level + 2 vertices, 20 * 4^level faces.
Mesh icosphere(int level, double radius = 1.0);

// Torus about the Y axis: ring radius `major`, tube radius `minor`;
// `ring_segments` x `tube_segments` vertices, twice as many faces.
Mesh torus(double major, double minor, int ring_segments, int tube_segments);

}  // namespace drape::geometry
