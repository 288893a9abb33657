#pragma once
// Degenerate and inverted faces.
#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::geometry {

// Faces with area below `min_area` or a corner angle below `min_angle` (radians).
std::vector<int> degenerate_faces(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                  double min_area, double min_angle);

// Faces whose normal points against `reference` (one direction per face, e.g. the
// outward gradient of an implicit surface at the face centre, or the normals of
// the same faces on a rest mesh).
std::vector<int> inverted_faces(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                const Eigen::MatrixX3d& reference);

// Interior edges whose two faces turn by more than `max_angle` (radians): a
// folded-over triangle shows up as a turn near pi at its edges, even when the
// fold shares vertices with its neighbours and so escapes self_intersections().
std::vector<std::array<int, 2>> folded_edges(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                             double max_angle);

// Unnormalised face normals (cross product of two edges; length = 2 * area).
Eigen::MatrixX3d face_normals(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

}  // namespace drape::geometry
