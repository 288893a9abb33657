// A region of garment (or body) vertices in words (garment_region.hpp).
#include "garment_region.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

namespace drape::scene_detail {
namespace {

// Vertices closer than this (m) are one place: a hand is one, both hands two.
constexpr double kPlaceGap = 0.05;
constexpr std::size_t kPlacesShown = 3;

// The vertices split into places: groups joined by chains of vertices within
// kPlaceGap of each other (union-find over a grid of kPlaceGap cells), the
// largest first; within a place, the vertices keep their given order.
std::vector<std::vector<int>> places(const Eigen::MatrixX3d& x, const std::vector<int>& vertices) {
  const std::size_t n = vertices.size();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::array<long, 3>, std::vector<std::size_t>> grid;
  auto cell = [&](std::size_t i) {
    const int v = vertices[i];
    return std::array<long, 3>{std::lround(std::floor(x(v, 0) / kPlaceGap)), std::lround(std::floor(x(v, 1) / kPlaceGap)),
                               std::lround(std::floor(x(v, 2) / kPlaceGap))};
  };
  for (std::size_t i = 0; i < n; ++i) grid[cell(i)].push_back(i);
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<long, 3> c = cell(i);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (std::size_t j : it->second)
            if ((x.row(vertices[i]) - x.row(vertices[j])).norm() < kPlaceGap) parent[find(i)] = find(j);
        }
  }
  std::map<std::size_t, std::vector<int>> groups;
  for (std::size_t i = 0; i < n; ++i) groups[find(i)].push_back(vertices[i]);
  std::vector<std::vector<int>> out;
  for (auto& [root, members] : groups) out.push_back(std::move(members));
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return out;
}

Eigen::RowVector3d centre_of(const Eigen::MatrixX3d& x, const std::vector<int>& vertices) {
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  for (int v : vertices) centre += x.row(v);
  return centre / static_cast<double>(vertices.size());
}

}  // namespace

std::string describe_region(const Eigen::MatrixX3d& x, const std::vector<int>& vertices, const char* surface) {
  if (vertices.empty()) return std::string("no ") + surface + " vertices";
  // Several places apart (both hands, both armpits) are named each: the centre
  // of all of them would be a point in the air between them.
  const std::vector<std::vector<int>> split = places(x, vertices);
  const std::vector<int>& first = split.front();
  double low = x(first.front(), 1), high = low;
  for (int v : first) low = std::min(low, x(v, 1)), high = std::max(high, x(v, 1));
  const Eigen::RowVector3d centre = centre_of(x, first);
  char text[200];
  std::snprintf(text, sizeof text, "%zu %s vertices around (%.3f, %.3f, %.3f) m, heights %.3f-%.3f m (vertex %d",
                first.size(), surface, centre[0], centre[1], centre[2], low, high, first.front());
  std::string out = text;
  for (std::size_t i = 1; i < std::min<std::size_t>(first.size(), 5); ++i) out += ", " + std::to_string(first[i]);
  out += first.size() > 5 ? ", ...)" : ")";
  for (std::size_t p = 1; p < std::min(split.size(), kPlacesShown); ++p) {
    const Eigen::RowVector3d c = centre_of(x, split[p]);
    std::snprintf(text, sizeof text, ", %zu more around (%.3f, %.3f, %.3f) m (vertex %d)", split[p].size(), c[0], c[1], c[2],
                  split[p].front());
    out += text;
  }
  if (split.size() > kPlacesShown) {
    std::size_t rest = 0;
    for (std::size_t p = kPlacesShown; p < split.size(); ++p) rest += split[p].size();
    out += ", " + std::to_string(rest) + " more in " + std::to_string(split.size() - kPlacesShown) + " other places";
  }
  return out;
}

}  // namespace drape::scene_detail
