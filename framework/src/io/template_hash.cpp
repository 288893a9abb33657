// The template hash that ties a dataset to its garment template and body topology.
#include <drape/io/dataset.hpp>

#include <drape/fnv1a.hpp>

namespace drape {

std::string template_hash(const Mesh& garment, const Eigen::MatrixX3i& body_faces) {
  return Fnv1a().matrix(garment.vertices).matrix(garment.faces).matrix(garment.uv).matrix(body_faces).hex();
}

}  // namespace drape
