#pragma once
// Per-vertex areas of a garment in material space (its UV layout, in meters).
#include <drape/energy.hpp>

#include <Eigen/Core>

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

}  // namespace drape::geometry
