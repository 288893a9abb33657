#include <drape/geometry/strain_limit.hpp>

#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace drape::geometry {
namespace {

// The edges at each vertex, flat: vertex v's are at[start[v] .. start[v + 1]).
struct EdgesAtVertices {
  std::vector<int> start, at;
};

EdgesAtVertices edges_at_vertices(const std::vector<std::array<int, 2>>& edges, int vertices) {
  EdgesAtVertices out;
  out.start.assign(static_cast<std::size_t>(vertices) + 1, 0);
  for (const auto& [a, b] : edges) ++out.start[static_cast<std::size_t>(a) + 1], ++out.start[static_cast<std::size_t>(b) + 1];
  for (std::size_t v = 0; v < static_cast<std::size_t>(vertices); ++v) out.start[v + 1] += out.start[v];
  out.at.resize(2 * edges.size());
  std::vector<int> fill(out.start.begin(), out.start.end() - 1);
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (const int v : edges[e]) out.at[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<int>(e);
  return out;
}


}  // namespace

double worst_strain(const Eigen::MatrixX3d& x, const std::vector<std::array<int, 2>>& edges, const std::vector<double>& rest) {
  double worst = -1.0;
  for (std::size_t e = 0; e < edges.size(); ++e)
    worst = std::max(worst, (x.row(edges[e][1]) - x.row(edges[e][0])).norm() / rest[e] - 1.0);
  return worst;
}

StrainLimitReport limit_strain(Eigen::MatrixX3d& x, const std::vector<std::array<int, 2>>& edges,
                               const std::vector<double>& rest, double limit, int max_sweeps, double slack,
                               std::vector<char>* moved) {
  if (rest.size() != edges.size())
    throw Error("limit_strain: " + std::to_string(rest.size()) + " rest lengths for " + std::to_string(edges.size()) + " edges");
  if (!(limit >= 0.0) || max_sweeps < 1 || !(slack >= 0.0))
    throw Error("limit_strain: the limit and the slack must be >= 0 and the sweeps >= 1");
  const auto n = static_cast<int>(x.rows());
  if (moved && moved->size() != static_cast<std::size_t>(n))
    throw Error("limit_strain: " + std::to_string(moved->size()) + " moved flags for " + std::to_string(n) + " vertices");
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!(rest[e] > 0.0)) throw Error("limit_strain: edge " + std::to_string(e) + " has rest length " + std::to_string(rest[e]));
    for (const int v : edges[e])
      if (v < 0 || v >= n) throw Error("limit_strain: edge " + std::to_string(e) + " names vertex " + std::to_string(v));
  }
  StrainLimitReport report;
  report.worst_before = worst_strain(x, edges, rest);
  if (report.worst_before <= limit + slack) {
    report.sweeps = 1, report.worst_after = report.worst_before;
    return report;
  }
  const EdgesAtVertices incident = edges_at_vertices(edges, n);
  // A length a rounding error above the limit is at it: without the slack a
  // shortened edge could come back 1 ulp long and be taken again forever.
  constexpr double kSlack = 1e-12;  // (relative)
  std::vector<int> todo(edges.size()), next;
  for (std::size_t e = 0; e < edges.size(); ++e) todo[e] = static_cast<int>(e);
  std::vector<char> queued(edges.size(), 0);
  while (!todo.empty() && report.sweeps < max_sweeps) {
    ++report.sweeps;
    next.clear();
    for (const int e : todo) {
      const auto [a, b] = edges[static_cast<std::size_t>(e)];
      const Eigen::RowVector3d d = x.row(b) - x.row(a);
      const double length = d.norm(), longest = (1.0 + limit) * rest[static_cast<std::size_t>(e)];
      if (!(length > (1.0 + limit + slack) * rest[static_cast<std::size_t>(e)] * (1.0 + kSlack))) continue;
      // Half the excess off each end, along the edge.
      const Eigen::RowVector3d half = 0.5 * (length - longest) / length * d;
      x.row(a) += half;
      x.row(b) -= half;
      if (moved) (*moved)[static_cast<std::size_t>(a)] = (*moved)[static_cast<std::size_t>(b)] = 1;
      ++report.shortened;
      // Every edge at either end may now be too long: the next sweep looks.
      for (const int v : {a, b})
        for (int k = incident.start[static_cast<std::size_t>(v)]; k < incident.start[static_cast<std::size_t>(v) + 1]; ++k) {
          const int f = incident.at[static_cast<std::size_t>(k)];
          if (!queued[static_cast<std::size_t>(f)]) queued[static_cast<std::size_t>(f)] = 1, next.push_back(f);
        }
    }
    for (const int f : next) queued[static_cast<std::size_t>(f)] = 0;
    std::sort(next.begin(), next.end());  // edge order every sweep: the result does not depend on the path
    std::swap(todo, next);
  }
  report.worst_after = worst_strain(x, edges, rest);
  return report;
}

std::vector<double> material_edge_lengths(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges) {
  if (!mesh.has_uv()) throw ConfigError("material edge lengths need the garment's material space (UVs), but it has none");
  std::vector<double> sum(edges.size(), 0.0);
  std::vector<int> sides(edges.size(), 0);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      int a = mesh.faces(f, j), b = mesh.faces(f, (j + 1) % 3);
      if (a > b) std::swap(a, b);
      const auto it = std::lower_bound(edges.begin(), edges.end(), std::array<int, 2>{a, b});
      if (it == edges.end() || *it != std::array<int, 2>{a, b}) continue;  // an edge the caller left out
      const auto e = static_cast<std::size_t>(it - edges.begin());
      sum[e] += (mesh.uv.row(mesh.uv_faces(f, (j + 1) % 3)) - mesh.uv.row(mesh.uv_faces(f, j))).norm();
      ++sides[e];
    }
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (sides[e] == 0) throw Error("material_edge_lengths: no face holds edge (" + std::to_string(edges[e][0]) + ", " +
                                   std::to_string(edges[e][1]) + ")");
    sum[e] /= sides[e];
  }
  return sum;
}

}  // namespace drape::geometry
