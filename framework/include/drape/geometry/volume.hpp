#pragma once
// Enclosed volume and surface area of closed triangle meshes.
#include <Eigen/Core>

namespace drape::geometry {

// Signed volume by the divergence theorem: sum over faces of det(a, b, c) / 6.
// Positive for a closed mesh whose faces are counter-clockwise seen from outside.
double mesh_volume(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

double mesh_area(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

// A body mesh's height (its y extent, m) and BMI as the project measures it
// from the mesh, as the seed does: enclosed volume * 985 kg/m^3 / height^2.
double body_height(const Eigen::MatrixX3d& vertices);
double body_bmi(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

}  // namespace drape::geometry
