// BodyResampling (geometry/body_resampling.hpp).
#include <drape/errors.hpp>
#include <drape/geometry/body_resampling.hpp>

#include <vector>

namespace drape::geometry {

Eigen::MatrixX3d BodyResampling::apply(const Eigen::MatrixX3d& source_body, const std::string& what) const {
  if (source_body.rows() != source_vertices)
    throw ConfigError(what + ": has " + std::to_string(source_body.rows()) + " vertices; the resampling reads bodies of " +
                      std::to_string(source_vertices));
  return attached_points(source_body, source_faces, attachment);
}

Eigen::SparseMatrix<double, Eigen::RowMajor, int> BodyResampling::matrix() const {
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(static_cast<std::size_t>(3 * size()));
  for (int i = 0; i < size(); ++i)
    for (int k = 0; k < 3; ++k)
      entries.emplace_back(i, source_faces(attachment.face[i], k), attachment.barycentric(i, k));
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> r(size(), source_vertices);
  r.setFromTriplets(entries.begin(), entries.end());
  return r;
}

BodyResampling body_resampling(const Mesh& source_template, const Eigen::MatrixX3d& target_template) {
  BodyResampling r;
  r.attachment = attach_to_surface(source_template, target_template);
  r.source_faces = source_template.faces;
  r.source_vertices = static_cast<int>(source_template.vertices.rows());
  r.resampled_template = r.apply(source_template.vertices, "the source template");
  return r;
}

}  // namespace drape::geometry
