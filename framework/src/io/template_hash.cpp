// The template hash that ties a dataset to its garment template and body topology.
#include <drape/io/dataset.hpp>

#include <iomanip>
#include <sstream>

namespace drape {

std::string template_hash(const Mesh& garment, const Eigen::MatrixX3i& body_faces) {
  std::uint64_t h = 1469598103934665603ull;
  auto bytes = [&](const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  bytes(garment.vertices.data(), sizeof(double) * static_cast<std::size_t>(garment.vertices.size()));
  bytes(garment.faces.data(), sizeof(int) * static_cast<std::size_t>(garment.faces.size()));
  bytes(garment.uv.data(), sizeof(double) * static_cast<std::size_t>(garment.uv.size()));
  bytes(body_faces.data(), sizeof(int) * static_cast<std::size_t>(body_faces.size()));
  std::ostringstream o;
  o << std::hex << std::setw(16) << std::setfill('0') << h;
  return o.str();
}

}  // namespace drape
