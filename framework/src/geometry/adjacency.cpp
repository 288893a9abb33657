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

VertexAdjacency vertex_adjacency(const std::vector<std::array<int, 2>>& edges, int num_vertices) {
  VertexAdjacency adjacency;
  adjacency.start.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (const auto& [a, b] : edges) ++adjacency.start[static_cast<std::size_t>(a) + 1], ++adjacency.start[static_cast<std::size_t>(b) + 1];
  for (std::size_t v = 0; v + 1 < adjacency.start.size(); ++v) adjacency.start[v + 1] += adjacency.start[v];
  adjacency.neighbours.resize(2 * edges.size());
  std::vector<int> next(adjacency.start.begin(), adjacency.start.end() - 1);
  for (const auto& [a, b] : edges) {
    adjacency.neighbours[static_cast<std::size_t>(next[static_cast<std::size_t>(a)]++)] = b;
    adjacency.neighbours[static_cast<std::size_t>(next[static_cast<std::size_t>(b)]++)] = a;
  }
  return adjacency;
}

std::vector<std::array<int, 3>> face_neighbours(const Eigen::MatrixX3i& faces) {
  // (smaller vertex, larger vertex, face, slot) for every face's edge, sorted so
  // the sides of one edge are adjacent.
  struct Side {
    int u, v, face, slot;
  };
  std::vector<Side> sides;
  sides.reserve(static_cast<std::size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      sides.push_back({std::min(a, b), std::max(a, b), static_cast<int>(f), k});
    }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.u != y.u ? x.u < y.u : x.v != y.v ? x.v < y.v : x.face < y.face;
  });
  std::vector<std::array<int, 3>> out(static_cast<std::size_t>(faces.rows()), {-1, -1, -1});
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].u == sides[i].u && sides[j].v == sides[i].v) ++j;
    if (j - i == 2) {
      out[static_cast<std::size_t>(sides[i].face)][static_cast<std::size_t>(sides[i].slot)] = sides[i + 1].face;
      out[static_cast<std::size_t>(sides[i + 1].face)][static_cast<std::size_t>(sides[i + 1].slot)] = sides[i].face;
    }
    i = j;
  }
  return out;
}

}  // namespace drape::geometry
