#pragma once
// Garment vertices attached to the body they are dressed on.
//
// The seed's decoder gathers the encoded body features onto the garment: each
// garment vertex reads the features of one body vertex. Its V2V and direction
// losses need c, the closest body point of each garment vertex; stored as a face
// and barycentric weights, c can be re-evaluated on any body of the same
// topology (another shape, the same attachment).
#include <drape/geometry/closest_point.hpp>
#include <drape/mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::geometry {

// Where each query point meets the body surface.
struct SurfaceAttachment {
  Eigen::VectorXi face;         // [N] body face of the closest point
  Eigen::MatrixX3d barycentric; // [N, 3] weights of that face's corners
  int size() const { return static_cast<int>(face.size()); }
};

SurfaceAttachment attach_to_surface(const BodySurface& body, const Eigen::MatrixX3d& points);
SurfaceAttachment attach_to_surface(const Mesh& body, const Eigen::MatrixX3d& points);

// The attached points on body vertices of the same topology ([N, 3]).
// Throws Error when a face index is outside `faces`.
Eigen::MatrixX3d attached_points(const Eigen::MatrixX3d& body_vertices, const Eigen::MatrixX3i& body_faces,
                                 const SurfaceAttachment& attachment);

// For each garment vertex, the body vertex nearest to the garment vertex's
// closest body-surface point (nearest over all body vertices, not just the
// corners of that face: on obtuse faces a neighbour's vertex can be nearer).
// Both meshes in the same space, normally the garment dressed on the mean body.
std::vector<int> body_to_garment_correspondence(const Mesh& body, const Mesh& garment);

}  // namespace drape::geometry
