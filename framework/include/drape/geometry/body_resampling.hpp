#pragma once
// One body topology read at another's vertices (docs/bodies.md, "One encoder
// for both rigs"): each vertex of a target template attached to its closest
// point on a source template's surface (a face and barycentric weights, fixed
// once), so that any body of the source topology can be read at those points.
// `drape dataset resample` carries datasets with it, and the assets' encoder
// body (Assets::encoder_resampling) feeds an encoder trained on the target.
#include <drape/geometry/body_correspondence.hpp>
#include <drape/mesh.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <string>

namespace drape::geometry {

struct BodyResampling {
  SurfaceAttachment attachment;       // per target vertex: source face and barycentric weights
  Eigen::MatrixX3i source_faces;      // the source template's triangles (the faces indexed above)
  int source_vertices = 0;
  Eigen::MatrixX3d resampled_template;  // the source template read at the points [target vertices, 3]

  int size() const { return attachment.size(); }  // target vertices; 0: no resampling
  // The target-topology body of one source body [source_vertices, 3].
  // ConfigError naming `what` for another vertex count.
  Eigen::MatrixX3d apply(const Eigen::MatrixX3d& source_body, const std::string& what) const;
  // The same map as a matrix R [target vertices, source_vertices], three
  // weights a row: apply(x) = R x.
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> matrix() const;
};

// Target template vertices attached to the source template's surface.
BodyResampling body_resampling(const Mesh& source_template, const Eigen::MatrixX3d& target_template);

}  // namespace drape::geometry
