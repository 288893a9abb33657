#pragma once
// Reverse-mode derivatives of a closest point on a triangle mesh, for losses
// that split a garment into "closest body point + displacement" (the seed's
// eq. 6.6-6.8) and need gradients through that split.
//
// The closest point c(p, V) of a query p on the mesh with vertices V lies on a
// feature: a face interior, an edge or a vertex (SurfacePoint::feature). With
// that feature held fixed, c is the orthogonal projection of p onto the
// feature's affine span, a smooth function of p and of the feature's 1-3
// corners; the feature only changes on a set of measure zero, so this is the
// derivative almost everywhere (the medial axis, where c jumps, excepted).
//
//   interior (a, a + e1, a + e2): c = a + u e1 + v e2 with G [u v]' = [e1.(p-a), e2.(p-a)],
//     G the Gram matrix of e1, e2. dc/dp = the tangent projector of the face.
//   edge (a, a + e):              c = a + t e, t = e.(p-a) / e.e. dc/dp = e e' / e.e.
//   vertex v:                     c = v. dc/dp = 0.
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::geometry {

struct ClosestPointGradient {
  Eigen::Vector3d query = Eigen::Vector3d::Zero();  // dL/dp
  int count = 0;                                    // corners c depends on (1, 2 or 3)
  std::array<int, 3> vertex{-1, -1, -1};            // their mesh vertex indices
  std::array<Eigen::Vector3d, 3> corner{};          // dL/dV[vertex[k]] (zero beyond count)
};

// Given grad = dL/dc of the closest point `hit` of p (found on the mesh with
// `vertices` and `faces`, e.g. by BodySurface::locate), returns dL/dp and dL/dV.
// The corner gradients and dL/dp sum to grad (translating everything moves c
// with it). A degenerate feature (zero-area face, zero-length edge) passes the
// whole gradient to the corners by their barycentric weights and none to p.
ClosestPointGradient closest_point_backward(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                            const Eigen::Vector3d& p, const SurfacePoint& hit,
                                            const Eigen::Vector3d& grad);

// The same for many points: for every row i, dL/dc_i = grad_c.row(i) adds
// dL/dp_i to grad_points.row(i) and dL/dV to grad_vertices (both accumulated).
void closest_points_backward(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                             const Eigen::MatrixX3d& points, const std::vector<SurfacePoint>& hits,
                             const Eigen::MatrixX3d& grad_c, Eigen::MatrixX3d& grad_points,
                             Eigen::MatrixX3d& grad_vertices);

}  // namespace drape::geometry
