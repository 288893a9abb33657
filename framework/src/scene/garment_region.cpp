// A region of garment (or body) vertices in words (garment_region.hpp).
#include "garment_region.hpp"

#include <algorithm>
#include <cstdio>

namespace drape::scene_detail {

std::string describe_region(const Eigen::MatrixX3d& x, const std::vector<int>& vertices, const char* surface) {
  if (vertices.empty()) return std::string("no ") + surface + " vertices";
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  double low = x(vertices.front(), 1), high = low;
  for (int v : vertices) {
    centre += x.row(v);
    low = std::min(low, x(v, 1));
    high = std::max(high, x(v, 1));
  }
  centre /= static_cast<double>(vertices.size());
  char text[200];
  std::snprintf(text, sizeof text, "%zu %s vertices around (%.3f, %.3f, %.3f) m, heights %.3f-%.3f m (vertex %d",
                vertices.size(), surface, centre[0], centre[1], centre[2], low, high, vertices.front());
  std::string out = text;
  for (std::size_t i = 1; i < std::min<std::size_t>(vertices.size(), 5); ++i) out += ", " + std::to_string(vertices[i]);
  return out + (vertices.size() > 5 ? ", ...)" : ")");
}

}  // namespace drape::scene_detail
