#pragma once
// Per-vertex areas of a garment in material space (its UV layout, in meters).
#include <drape/energy.hpp>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::geometry {

// Lumped (barycentric) material-space area of each garment vertex: a third of
// the UV area (m^2) of every face it is a corner of. The areas sum to the
// garment's material area and do not depend on the 3D state, so per-area
// quantities weighted by them (masses, contact pressures) are constant during
// a solve and converge as the mesh is refined. A vertex on no face gets 0.
// Throws ConfigError when the garment has no material-space UVs, Error when a
// face names a vertex or UV index out of range.
Eigen::VectorXd vertex_areas(const Garment& garment);

// Lumped masses (kg): the same thirds, each face's area times its material's
// density. What gravity and the solver's inertia use. ConfigError also when a
// face names a material the garment does not have.
Eigen::VectorXd vertex_masses(const Garment& garment);

// Per edge of `edges` (geometry::edge_list of the garment's faces: sorted),
// its material-space weights: a third of the UV area of each face it borders
// (m^2; what weights an edge's contact pressure, as vertex_areas a vertex's)
// and its squared UV length (m^2; the scale of IPC's edge-edge mollifier).
struct EdgeWeights {
  Eigen::VectorXd area, length2;
};
EdgeWeights edge_weights(const Garment& garment, const std::vector<std::array<int, 2>>& edges);

}  // namespace drape::geometry
