// Self-intersections of a mesh: each face is tested against the faces whose
// bounding boxes overlap its own (triangle_grid.hpp), each pair once.
#include <drape/geometry/self_intersection.hpp>

#include "triangle_grid.hpp"

#include <drape/geometry/surface_crossings.hpp>

#include <algorithm>

namespace drape::geometry {

std::vector<std::pair<int, int>> self_intersections(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                                    std::size_t max_pairs) {
  std::vector<std::pair<int, int>> hits;
  const int nf = static_cast<int>(faces.rows());
  if (nf < 2) return hits;
  auto shares_vertex = [&](int f, int g) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (faces(f, i) == faces(g, j)) return true;
    return false;
  };
  const TriangleGrid grid(vertices, faces);
  for (int f = 0; f < nf && hits.size() < max_pairs; ++f)
    grid.find(grid.lo(f), grid.hi(f), [&](int g) {
      if (g <= f || shares_vertex(f, g)) return false;
      if (!triangles_intersect(vertices.row(faces(f, 0)), vertices.row(faces(f, 1)), vertices.row(faces(f, 2)),
                               vertices.row(faces(g, 0)), vertices.row(faces(g, 1)), vertices.row(faces(g, 2))))
        return false;
      hits.emplace_back(f, g);
      return hits.size() >= max_pairs;
    });
  std::sort(hits.begin(), hits.end());
  return hits;
}

std::vector<std::pair<std::pair<int, int>, int>> self_edge_crossings(const Eigen::MatrixX3d& vertices,
                                                                     const Eigen::MatrixX3i& faces, std::size_t max_pairs) {
  std::vector<std::pair<std::pair<int, int>, int>> hits;
  if (faces.rows() == 0) return hits;
  std::vector<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const TriangleGrid grid(vertices, faces);
  for (const auto& [a, b] : edges) {
    if (hits.size() >= max_pairs) break;
    const Eigen::Vector3d p = vertices.row(a), q = vertices.row(b);
    grid.find(p.cwiseMin(q), p.cwiseMax(q), [&](int f) {
      for (int k = 0; k < 3; ++k)
        if (faces(f, k) == a || faces(f, k) == b) return false;
      if (!segment_pierces_triangle(p, q, vertices.row(faces(f, 0)), vertices.row(faces(f, 1)), vertices.row(faces(f, 2))))
        return false;
      hits.push_back({{a, b}, f});
      return hits.size() >= max_pairs;
    });
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

}  // namespace drape::geometry
