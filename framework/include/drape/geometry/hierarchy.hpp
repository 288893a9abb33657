#pragma once
// The multi-resolution hierarchy of a garment for the seed's multi-scale GCN
// decoder (Sec. 6.3.2): level 0 is the garment, each next level has about
// `ratio` times fewer vertices, and features go from a coarse level to the next
// finer one through barycentric weights "in UV space".
//
// Levels come from quadric-error half-edge collapses (Garland-Heckbert), so the
// vertices of a coarse level are a subset of the finer level's vertices and keep
// their positions and UVs. Boundary loops and UV seams survive: a vertex on a
// boundary or seam only slides along it, seam corners never move, and collapses
// that break manifoldness or flip a face in 3D or in UV are refused.
#include <drape/mesh.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace drape::geometry {

struct HierarchyOptions {
  int levels = 4;       // including the garment itself
  double ratio = 4.0;   // vertices of level l over vertices of level l + 1
  // Weight of the squared edge length against the quadric error. Garment
  // panels are nearly flat, where the quadric error is ~0 and cannot rank
  // collapses; the length term then collapses short edges first, which keeps
  // coarse levels evenly sampled (what a GCN wants).
  double length_weight = 0.05;
  // Weight of the planes through boundary and seam edges (keeps their shape).
  double feature_weight = 10.0;
  // Refuse collapses that turn a face normal by more than this (degrees)...
  double max_normal_turn_deg = 60.0;
  // ...or produce a triangle of quality (4*sqrt(3)*area / sum of squared edges,
  // 1 for equilateral) below this, unless the ring was already that bad.
  double min_quality = 0.15;
};

struct HierarchyLevel {
  Mesh mesh;                    // vertices, faces, uv, uv_faces of this level
  Eigen::VectorXi fine_index;   // [n_l] index of each vertex in level 0
  Eigen::VectorXi uv_fine_index;  // [T_l] index of each UV in level 0's uv
  Eigen::VectorXi face_chart;     // [F_l] UV chart of each face, numbered as uv_charts(level 0)
  // Up-sampling from level l + 1 to this level: [n_l, n_{l+1}], row i holds the
  // UV-space barycentric weights of vertex i with respect to the coarse triangle
  // of its own UV chart that contains it (the closest one, with clamped weights,
  // when none does). Rows are non-negative and sum to 1; a vertex kept in the
  // coarse level has the single weight 1. Empty for the coarsest level.
  // Float and row-major: it multiplies row-major [vertices, channels] features.
  Eigen::SparseMatrix<float, Eigen::RowMajor> upsample;
};

struct Hierarchy {
  std::vector<HierarchyLevel> levels;  // [0] = the garment, finest first
  int num_levels() const { return static_cast<int>(levels.size()); }
};

// Throws ConfigError when the mesh has no per-corner UVs or bad indices.
// The coarsest levels may have fewer than n / ratio^l vertices' worth of
// reduction when every remaining collapse would break the rules above.
Hierarchy build_hierarchy(const Mesh& garment, const HierarchyOptions& options = {});

// UV charts: faces connected through edges whose two corners share UV indices.
// Returns the chart of every face and sets `num_charts`. Charts are per face
// because a UV index may be shared by two charts that touch at one point.
Eigen::VectorXi uv_charts(const Mesh& mesh, int& num_charts);

// The up-sampling matrix of `fine` from `coarse` (double, see HierarchyLevel::upsample).
// `coarse_in_fine[j]` is the fine vertex that coarse vertex j is; the face charts
// say which faces of the two meshes belong to the same UV chart.
Eigen::SparseMatrix<double, Eigen::RowMajor> uv_upsampling(const Mesh& fine, const Eigen::VectorXi& fine_face_chart,
                                                           const Mesh& coarse, const Eigen::VectorXi& coarse_face_chart,
                                                           const Eigen::VectorXi& coarse_in_fine);

}  // namespace drape::geometry
