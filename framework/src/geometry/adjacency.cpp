#include <drape/geometry/adjacency.hpp>

#include <algorithm>

namespace drape::geometry {

std::vector<std::array<int, 2>> edge_list(const Eigen::MatrixX3i& faces) {
  std::vector<std::array<int, 2>> edges;
  edges.reserve(static_cast<std::size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = faces(f, k), v = faces(f, (k + 1) % 3);
      edges.push_back({std::min(u, v), std::max(u, v)});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<std::vector<int>> vertex_neighbours(const Eigen::MatrixX3i& faces, int num_vertices) {
  std::vector<std::vector<int>> nbrs(static_cast<std::size_t>(num_vertices));
  for (const auto& e : edge_list(faces)) {
    nbrs[static_cast<std::size_t>(e[0])].push_back(e[1]);
    nbrs[static_cast<std::size_t>(e[1])].push_back(e[0]);
  }
  for (auto& n : nbrs) std::sort(n.begin(), n.end());
  return nbrs;
}

}  // namespace drape::geometry
