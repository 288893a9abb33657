// Self-intersections of a mesh: a uniform grid of cells about twice the mean
// face size; each face is listed in the cells its bounding box covers and only
// faces sharing a cell are tested, each pair once (in the first cell they share).
#include <drape/geometry/self_intersection.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace drape::geometry {

std::vector<std::pair<int, int>> self_intersections(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                                    std::size_t max_pairs) {
  std::vector<std::pair<int, int>> hits;
  const Eigen::Index nf = faces.rows();
  if (nf < 2) return hits;
  std::vector<Eigen::Vector3d> lo(static_cast<std::size_t>(nf)), hi(static_cast<std::size_t>(nf));
  Eigen::Vector3d box_lo = Eigen::Vector3d::Constant(INFINITY), box_hi = -box_lo;
  double mean_extent = 0;
  for (Eigen::Index f = 0; f < nf; ++f) {
    Eigen::Vector3d l = vertices.row(faces(f, 0)), h = l;
    for (int k = 1; k < 3; ++k) {
      l = l.cwiseMin(vertices.row(faces(f, k)).transpose());
      h = h.cwiseMax(vertices.row(faces(f, k)).transpose());
    }
    lo[static_cast<std::size_t>(f)] = l, hi[static_cast<std::size_t>(f)] = h;
    box_lo = box_lo.cwiseMin(l), box_hi = box_hi.cwiseMax(h);
    mean_extent += (h - l).maxCoeff();
  }
  mean_extent /= static_cast<double>(nf);
  // Cells of twice the mean face extent, but never more than ~256 per axis.
  const double cell = std::max({2 * mean_extent, (box_hi - box_lo).maxCoeff() / 256, 1e-12});
  auto cell_of = [&](const Eigen::Vector3d& p) {
    std::array<std::int64_t, 3> c;
    for (int k = 0; k < 3; ++k) c[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(std::floor((p[k] - box_lo[k]) / cell));
    return c;
  };
  const std::array<std::int64_t, 3> dims = cell_of(box_hi);
  auto key = [&](std::int64_t x, std::int64_t y, std::int64_t z) { return (x * (dims[1] + 1) + y) * (dims[2] + 1) + z; };

  std::vector<std::pair<std::int64_t, int>> entries;
  for (Eigen::Index f = 0; f < nf; ++f) {
    const auto a = cell_of(lo[static_cast<std::size_t>(f)]), b = cell_of(hi[static_cast<std::size_t>(f)]);
    for (auto x = a[0]; x <= b[0]; ++x)
      for (auto y = a[1]; y <= b[1]; ++y)
        for (auto z = a[2]; z <= b[2]; ++z) entries.emplace_back(key(x, y, z), static_cast<int>(f));
  }
  std::sort(entries.begin(), entries.end());

  auto shares_vertex = [&](int f, int g) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (faces(f, i) == faces(g, j)) return true;
    return false;
  };
  for (std::size_t i = 0; i < entries.size();) {
    std::size_t j = i;
    while (j < entries.size() && entries[j].first == entries[i].first) ++j;
    for (std::size_t s = i; s < j; ++s)
      for (std::size_t t = s + 1; t < j; ++t) {
        const int f = entries[s].second, g = entries[t].second;
        const auto fs = static_cast<std::size_t>(f), gs = static_cast<std::size_t>(g);
        if ((hi[fs].array() < lo[gs].array()).any() || (hi[gs].array() < lo[fs].array()).any()) continue;
        // Test the pair only in the first cell both boxes cover.
        const auto first = cell_of(lo[fs].cwiseMax(lo[gs]));
        if (key(first[0], first[1], first[2]) != entries[i].first) continue;
        if (shares_vertex(f, g)) continue;
        if (triangles_intersect(vertices.row(faces(f, 0)), vertices.row(faces(f, 1)), vertices.row(faces(f, 2)),
                                vertices.row(faces(g, 0)), vertices.row(faces(g, 1)), vertices.row(faces(g, 2)))) {
          hits.emplace_back(std::min(f, g), std::max(f, g));
          if (hits.size() >= max_pairs) {
            std::sort(hits.begin(), hits.end());
            return hits;
          }
        }
      }
    i = j;
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

}  // namespace drape::geometry
