// build_hierarchy: repeated edge collapses, one level per target size.
#include <drape/errors.hpp>
#include <drape/geometry/hierarchy.hpp>

#include "edge_collapse.hpp"

#include <cmath>
#include <string>

namespace drape::geometry {
namespace {

void check_garment(const Mesh& m) {
  const std::string what = "build_hierarchy: ";
  if (m.num_faces() == 0) throw ConfigError(what + "the garment has no faces");
  if (!m.has_uv())
    throw ConfigError(what + "the garment has no per-corner UVs (uv_faces must have one row per face); the hierarchy is built in UV space");
  if (m.faces.minCoeff() < 0 || m.faces.maxCoeff() >= m.num_vertices())
    throw ConfigError(what + "a face refers to a vertex outside [0, " + std::to_string(m.num_vertices()) + ")");
  if (m.uv_faces.minCoeff() < 0 || m.uv_faces.maxCoeff() >= m.uv.rows())
    throw ConfigError(what + "a face corner refers to a UV outside [0, " + std::to_string(m.uv.rows()) + ")");
}

// Position of every level-0 index in `level_index` (which lists level-0 indices), -1 if absent.
std::vector<int> inverse(const Eigen::VectorXi& level_index, Eigen::Index size) {
  std::vector<int> inv(size, -1);
  for (int i = 0; i < level_index.size(); ++i) inv[level_index[i]] = i;
  return inv;
}

}  // namespace

Hierarchy build_hierarchy(const Mesh& garment, const HierarchyOptions& options) {
  check_garment(garment);
  if (options.levels < 1) throw ConfigError("build_hierarchy: levels must be at least 1, got " + std::to_string(options.levels));
  if (!(options.ratio > 1)) throw ConfigError("build_hierarchy: ratio must be above 1, got " + std::to_string(options.ratio));

  Hierarchy h;
  h.levels.resize(options.levels);
  HierarchyLevel& top = h.levels[0];
  top.mesh = garment;
  top.fine_index = Eigen::VectorXi::LinSpaced(garment.num_vertices(), 0, garment.num_vertices() - 1);
  top.uv_fine_index = Eigen::VectorXi::LinSpaced(garment.uv.rows(), 0, static_cast<int>(garment.uv.rows()) - 1);
  int num_charts = 0;
  top.face_chart = uv_charts(garment, num_charts);

  detail::EdgeCollapser collapser(garment, options);
  for (int l = 1; l < options.levels; ++l) {
    const HierarchyLevel& finer = h.levels[l - 1];
    const int target = static_cast<int>(std::ceil(finer.mesh.num_vertices() / options.ratio));
    collapser.collapse_until(target);
    HierarchyLevel& level = h.levels[l];
    collapser.extract(level.mesh, level.fine_index, level.uv_fine_index, level.face_chart);

    // Express the coarse level's vertices in the finer level's indices.
    const std::vector<int> v_inv = inverse(finer.fine_index, garment.num_vertices());
    Eigen::VectorXi in_finer(level.fine_index.size());
    for (int i = 0; i < in_finer.size(); ++i) in_finer[i] = v_inv[level.fine_index[i]];
    h.levels[l - 1].upsample = uv_upsampling(finer.mesh, finer.face_chart, level.mesh, level.face_chart, in_finer).cast<float>();
  }
  return h;
}

}  // namespace drape::geometry
