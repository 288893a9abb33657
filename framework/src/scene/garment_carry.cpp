// The garment carried along by a moving body (garment_carry.hpp).
#include "garment_carry.hpp"

#include <algorithm>

namespace drape::scene_detail {

Eigen::MatrixX3d carried_with_body(const Eigen::MatrixX3d& x, const geometry::BodySurface& body,
                                   const Eigen::MatrixX3d& body_next, double inner, double outer) {
  const std::vector<geometry::SurfacePoint> hits = body.locate_all(x, outer);
  const Eigen::MatrixX3d& from = body.vertices();
  const Eigen::MatrixX3i& faces = body.faces();
  Eigen::MatrixX3d carried = x;
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const geometry::SurfacePoint& hit = hits[static_cast<std::size_t>(v)];
    if (hit.face < 0) continue;
    const double d = std::abs(hit.signed_distance);
    const double weight = d <= inner ? 1.0 : std::max(0.0, (outer - d) / (outer - inner));
    Eigen::RowVector3d move = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int c = faces(hit.face, k);
      move += hit.barycentric[k] * (body_next.row(c) - from.row(c));
    }
    carried.row(v) += weight * move;
  }
  return carried;
}

}  // namespace drape::scene_detail
