// The check of a body mesh for self-intersection under the garment (body_overlap.hpp).
#include "body_overlap.hpp"

#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/self_intersection.hpp>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace drape::scene_detail {

std::string body_overlap_near_garment(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& target,
                                      const Eigen::MatrixX3i& faces, const Eigen::MatrixX3d& garment, double reach) {
  // Faces under the garment on the start body, then, through the fixed
  // topology, the same faces of the target.
  const geometry::BodySurface surface(start, faces);
  std::vector<char> under(static_cast<std::size_t>(faces.rows()), 0);
  for (Eigen::Index v = 0; v < garment.rows(); ++v) {
    const geometry::SurfacePoint hit = surface.locate(garment.row(v).transpose(), reach);
    if (hit.face >= 0) under[static_cast<std::size_t>(hit.face)] = 1;
  }
  // Faces a few centimetres around those the garment is closest to lie
  // under it too (the closest face of a vertex is one of several beneath it).
  for (int ring = 0; ring < 2; ++ring) {
    std::vector<char> grown = under;
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
      if (under[static_cast<std::size_t>(f)])
        for (int n : surface.face_neighbours()[static_cast<std::size_t>(f)])
          if (n >= 0) grown[static_cast<std::size_t>(n)] = 1;
    under.swap(grown);
  }
  std::vector<std::pair<int, int>> pairs;
  for (const auto& [f, g] : geometry::self_intersections(target, faces, 100000))
    if (under[static_cast<std::size_t>(f)] || under[static_cast<std::size_t>(g)]) pairs.emplace_back(f, g);
  if (pairs.empty()) return {};
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  double low = 1e300, high = -1e300;
  for (const auto& [f, g] : pairs)
    for (int face : {f, g})
      for (int k = 0; k < 3; ++k) {
        const Eigen::RowVector3d p = target.row(faces(face, k));
        centre += p / (6.0 * static_cast<double>(pairs.size()));
        low = std::min(low, p.y());
        high = std::max(high, p.y());
      }
  char text[400];
  std::snprintf(text, sizeof text,
                "the body intersects itself where the garment lies: %zu pairs of its faces cross around (%.3f, %.3f, %.3f) m, "
                "heights %.3f-%.3f m (faces %d and %d first); its inside is not defined there, so neither the contact nor "
                "p would be right",
                pairs.size(), centre.x(), centre.y(), centre.z(), low, high, pairs.front().first, pairs.front().second);
  return text;
}

}  // namespace drape::scene_detail
