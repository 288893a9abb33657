#include "vertex_order.hpp"

#include <deque>

namespace drape::parametric {

std::vector<int> locality_order(const std::vector<std::vector<int>>& neighbours, const Eigen::MatrixX3d& vertices) {
  const int n = static_cast<int>(neighbours.size());
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(n));
  std::vector<char> visited(static_cast<std::size_t>(n), 0);
  std::vector<int> free_nbrs(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) free_nbrs[static_cast<std::size_t>(v)] = static_cast<int>(neighbours[static_cast<std::size_t>(v)].size());
  auto nb = [&](int v) -> const std::vector<int>& { return neighbours[static_cast<std::size_t>(v)]; };

  int cur = 0;
  for (int v = 1; v < n; ++v)
    if (vertices(v, 1) > vertices(cur, 1)) cur = v;
  std::vector<int> seen_at(static_cast<std::size_t>(n), -1);
  while (true) {
    visited[static_cast<std::size_t>(cur)] = 1;
    order.push_back(cur);
    for (int u : nb(cur)) --free_nbrs[static_cast<std::size_t>(u)];
    if (static_cast<int>(order.size()) == n) break;
    int next = -1;
    for (int u : nb(cur)) {
      if (visited[static_cast<std::size_t>(u)]) continue;
      // Fewest free neighbours first; ties go to the higher vertex so the walk sweeps downwards.
      if (next < 0 || free_nbrs[static_cast<std::size_t>(u)] < free_nbrs[static_cast<std::size_t>(next)] ||
          (free_nbrs[static_cast<std::size_t>(u)] == free_nbrs[static_cast<std::size_t>(next)] && vertices(u, 1) > vertices(next, 1)))
        next = u;
    }
    if (next < 0) {
      // Stuck: breadth-first search for the nearest unvisited vertex.
      std::deque<int> queue{cur};
      seen_at[static_cast<std::size_t>(cur)] = static_cast<int>(order.size());
      while (!queue.empty() && next < 0) {
        const int v = queue.front();
        queue.pop_front();
        for (int u : nb(v)) {
          if (seen_at[static_cast<std::size_t>(u)] == static_cast<int>(order.size())) continue;
          seen_at[static_cast<std::size_t>(u)] = static_cast<int>(order.size());
          if (!visited[static_cast<std::size_t>(u)]) {
            next = u;
            break;
          }
          queue.push_back(u);
        }
      }
      if (next < 0)  // another connected component: take its first vertex
        for (int v = 0; v < n && next < 0; ++v)
          if (!visited[static_cast<std::size_t>(v)]) next = v;
    }
    cur = next;
  }
  return order;
}

}  // namespace drape::parametric
