#include <drape/geometry/index_locality.hpp>

#include <drape/geometry/adjacency.hpp>

#include <algorithm>

namespace drape::geometry {

IndexLocality index_locality(const Eigen::MatrixX3i& faces, int num_vertices) {
  IndexLocality r;
  if (num_vertices < 2) return r;
  const auto nbrs = vertex_neighbours(faces, num_vertices);
  auto adjacent = [&](int a, int b) {
    const auto& n = nbrs[static_cast<std::size_t>(a)];
    return std::binary_search(n.begin(), n.end(), b);
  };
  int one = 0, two = 0;
  for (int i = 0; i + 1 < num_vertices; ++i) {
    if (adjacent(i, i + 1)) {
      ++one, ++two;
      continue;
    }
    const auto& n = nbrs[static_cast<std::size_t>(i)];
    if (std::any_of(n.begin(), n.end(), [&](int k) { return adjacent(k, i + 1); })) ++two;
  }
  r.one_hop = static_cast<double>(one) / (num_vertices - 1);
  r.two_hop = static_cast<double>(two) / (num_vertices - 1);
  return r;
}

}  // namespace drape::geometry
