#include <drape/energy.hpp>
#include <drape/geometry/vertex_areas.hpp>

#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace drape::geometry {

namespace {

// A third of each face's UV area times weight(face) to each corner.
template <class FaceWeight>
Eigen::VectorXd lumped(const Garment& garment, FaceWeight weight) {
  const Mesh& mesh = garment.mesh;
  if (!mesh.has_uv())
    throw ConfigError("vertex areas: the garment has no material-space UVs (uv and uv_faces, one UV face per face)");
  const int nv = mesh.num_vertices();
  const Eigen::Index nuv = mesh.uv.rows();
  Eigen::VectorXd area = Eigen::VectorXd::Zero(nv);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.faces(f, k) < 0 || mesh.faces(f, k) >= nv)
        throw Error("vertex areas: face " + std::to_string(f) + " uses vertex " + std::to_string(mesh.faces(f, k)) +
                    ", outside [0, " + std::to_string(nv) + ")");
      if (mesh.uv_faces(f, k) < 0 || mesh.uv_faces(f, k) >= nuv)
        throw Error("vertex areas: face " + std::to_string(f) + " uses UV " + std::to_string(mesh.uv_faces(f, k)) +
                    ", outside [0, " + std::to_string(nuv) + ")");
    }
    const Eigen::Vector2d a = mesh.uv.row(mesh.uv_faces(f, 0)), b = mesh.uv.row(mesh.uv_faces(f, 1)),
                          c = mesh.uv.row(mesh.uv_faces(f, 2));
    const Eigen::Vector2d e1 = b - a, e2 = c - a;
    const double third = std::abs(e1.x() * e2.y() - e1.y() * e2.x()) / 6.0 * weight(f);
    for (int k = 0; k < 3; ++k) area[mesh.faces(f, k)] += third;
  }
  return area;
}

}  // namespace

Eigen::VectorXd vertex_areas(const Garment& garment) {
  return lumped(garment, [](int) { return 1.0; });
}

Eigen::VectorXd vertex_masses(const Garment& garment) {
  const int materials = static_cast<int>(garment.materials.size());
  if (materials == 0) throw ConfigError("vertex masses: the garment has no materials");
  return lumped(garment, [&](int f) {
    const int m = garment.material_of(f);
    if (m < 0 || m >= materials)
      throw ConfigError("vertex masses: face " + std::to_string(f) + " names material " + std::to_string(m) + " of " +
                        std::to_string(materials));
    return garment.materials[static_cast<std::size_t>(m)].density;
  });
}

EdgeWeights edge_weights(const Garment& garment, const std::vector<std::array<int, 2>>& edges) {
  const Mesh& mesh = garment.mesh;
  if (!mesh.has_uv())
    throw ConfigError("edge weights: the garment has no material-space UVs (uv and uv_faces, one UV face per face)");
  EdgeWeights w;
  w.area = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(edges.size()));
  w.length2 = Eigen::VectorXd::Zero(w.area.size());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector2d uv[3] = {mesh.uv.row(mesh.uv_faces(f, 0)), mesh.uv.row(mesh.uv_faces(f, 1)),
                                   mesh.uv.row(mesh.uv_faces(f, 2))};
    const Eigen::Vector2d e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
    const double third = std::abs(e1.x() * e2.y() - e1.y() * e2.x()) / 6.0;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      const std::array<int, 2> key{std::min(a, b), std::max(a, b)};
      const auto e = std::lower_bound(edges.begin(), edges.end(), key);
      if (e == edges.end() || *e != key)
        throw Error("edge weights: face " + std::to_string(f) + "'s edge is not in the edge list");
      w.area[e - edges.begin()] += third;
      w.length2[e - edges.begin()] = (uv[(k + 1) % 3] - uv[k]).squaredNorm();
    }
  }
  return w;
}

}  // namespace drape::geometry
