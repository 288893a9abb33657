#include <drape/geometry/mirror_map.hpp>

#include <drape/errors.hpp>
#include <drape/geometry/nearest_triangles.hpp>

#include <string>

namespace drape::geometry {

MirrorMap mirror_map(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  if (faces.rows() == 0) throw Error("mirror_map: the mesh has no faces");
  const NearestTriangles surface(vertices, faces);
  MirrorMap map;
  const Eigen::Index n = vertices.rows();
  map.corners.resize(n, 3);
  map.weights.resize(n, 3);
  map.distance.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d reflected(-vertices(i, 0), vertices(i, 1), vertices(i, 2));
    const SurfacePoint s = surface.nearest(reflected);
    map.corners.row(i) = faces.row(s.face);
    map.weights.row(i) = s.barycentric.transpose();
    map.distance[i] = (s.point - reflected).norm();
  }
  return map;
}

Eigen::MatrixX3d mirrored(const MirrorMap& map, const Eigen::MatrixX3d& x) {
  if (map.corners.size() > 0 && map.corners.maxCoeff() >= x.rows())
    throw Error("mirrored: the map indexes " + std::to_string(map.corners.maxCoeff() + 1) + " vertices, the drape has " +
                std::to_string(x.rows()));
  Eigen::MatrixX3d out(map.corners.rows(), 3);
  for (Eigen::Index i = 0; i < map.corners.rows(); ++i) {
    Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) p += map.weights(i, k) * x.row(map.corners(i, k));
    out.row(i) << -p[0], p[1], p[2];
  }
  return out;
}

Eigen::MatrixX3d mirrored_adjoint(const MirrorMap& map, const Eigen::MatrixX3d& g, Eigen::Index n) {
  if (g.rows() != map.corners.rows())
    throw Error("mirrored_adjoint: a gradient of " + std::to_string(g.rows()) + " rows for a map of " +
                std::to_string(map.corners.rows()));
  if (map.corners.size() > 0 && map.corners.maxCoeff() >= n)
    throw Error("mirrored_adjoint: the map indexes " + std::to_string(map.corners.maxCoeff() + 1) + " vertices, asked for " +
                std::to_string(n));
  Eigen::MatrixX3d out = Eigen::MatrixX3d::Zero(n, 3);
  for (Eigen::Index i = 0; i < g.rows(); ++i) {
    const Eigen::RowVector3d reflected(-g(i, 0), g(i, 1), g(i, 2));
    for (int k = 0; k < 3; ++k) out.row(map.corners(i, k)) += map.weights(i, k) * reflected;
  }
  return out;
}

}  // namespace drape::geometry
