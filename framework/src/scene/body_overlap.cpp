// The check of a body mesh for self-intersection under the garment (body_overlap.hpp).
#include "body_overlap.hpp"

#include <drape/scene/body_overlap.hpp>

#include <drape/geometry/self_intersection.hpp>

#include <algorithm>
#include <vector>

#include "garment_region.hpp"

namespace drape {

std::string describe_self_intersections(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces,
                                        const std::vector<char>* considered) {
  std::size_t pairs = 0;
  std::vector<int> vertices;
  for (const auto& [f, g] : geometry::self_intersections(body, faces, 100000))
    if (!considered || (*considered)[static_cast<std::size_t>(f)] || (*considered)[static_cast<std::size_t>(g)]) {
      ++pairs;
      for (int face : {f, g})
        for (int k = 0; k < 3; ++k) vertices.push_back(faces(face, k));
    }
  if (pairs == 0) return {};
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return std::to_string(pairs) + " pairs of its faces cross (" + scene_detail::describe_region(body, vertices, "body") + ")";
}

}  // namespace drape

namespace drape::scene_detail {

std::string body_overlap_near_garment(const geometry::BodySurface& dressed_on, const Eigen::MatrixX3d& target,
                                      const Eigen::MatrixX3d& garment, double reach) {
  // Faces under the garment on the body it was dressed on, then, through the
  // fixed topology, the same faces of the target.
  const Eigen::MatrixX3i& faces = dressed_on.faces();
  std::vector<char> under(static_cast<std::size_t>(faces.rows()), 0);
  for (const geometry::SurfacePoint& hit : dressed_on.locate_all(garment, reach))
    if (hit.face >= 0) under[static_cast<std::size_t>(hit.face)] = 1;
  // Faces a few centimetres around those the garment is closest to lie
  // under it too (the closest face of a vertex is one of several beneath it).
  for (int ring = 0; ring < 2; ++ring) {
    std::vector<char> grown = under;
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
      if (under[static_cast<std::size_t>(f)])
        for (int n : dressed_on.face_neighbours()[static_cast<std::size_t>(f)])
          if (n >= 0) grown[static_cast<std::size_t>(n)] = 1;
    under.swap(grown);
  }
  // And a crossing whose faces lie within reach of the cloth: under a shirt
  // the heavy short human rig's arm passes through its side at the armpit
  // (faces 2.6-3.1 cm from the sleeve on the mean body, two rings past the
  // faces closest to it), drape body warned of it and simulate went on (an
  // outside check). Only the crossing faces are measured, against every
  // garment vertex.
  const Eigen::MatrixX3d& dressed = dressed_on.vertices();
  const double reach2 = reach * reach;
  for (const auto& pair : geometry::self_intersections(target, faces, 100000))
    for (int face : {pair.first, pair.second}) {
      if (under[static_cast<std::size_t>(face)]) continue;
      for (int k = 0; k < 3; ++k)
        if ((garment.rowwise() - dressed.row(faces(face, k))).rowwise().squaredNorm().minCoeff() <= reach2)
          under[static_cast<std::size_t>(face)] = 1;
    }
  const std::string where = describe_self_intersections(target, faces, &under);
  if (where.empty()) return {};
  return "the body intersects itself where the garment lies: " + where +
         "; its inside is not defined there, so neither the contact nor p would be right";
}

}  // namespace drape::scene_detail
