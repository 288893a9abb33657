#include <drape/geometry/penetration.hpp>

#include <drape/errors.hpp>

#include <cmath>
#include <string>

namespace drape::geometry {

double penetration_ratio(const BodySurface& body, const Eigen::MatrixX3d& garment_vertices, double tolerance) {
  if (garment_vertices.rows() == 0) throw Error("penetration ratio: the garment has no vertices");
  if (!std::isfinite(tolerance) || tolerance < 0)
    throw Error("penetration ratio: the tolerance must be a finite length >= 0, got " + std::to_string(tolerance));
  for (Eigen::Index v = 0; v < garment_vertices.rows(); ++v)
    if (!garment_vertices.row(v).allFinite())
      throw Error("penetration ratio: garment vertex " + std::to_string(v) + " is not finite");
  const Eigen::VectorXd distance = body.signed_distances(garment_vertices);
  const Eigen::Index inside = (distance.array() < -tolerance).count();
  return static_cast<double>(inside) / static_cast<double>(garment_vertices.rows());
}

}  // namespace drape::geometry
