#include <drape/geometry/closest_point_gradient.hpp>

#include <drape/errors.hpp>

#include <string>

namespace drape::geometry {
namespace {

// The corners (in face slot order 0..2) of the feature and which of them is the
// origin a of its affine span.
struct FeatureCorners {
  int count = 0;
  std::array<int, 3> slot{};
};

FeatureCorners corners_of(TriangleFeature feature) {
  using F = TriangleFeature;
  switch (feature) {
    case F::vertex_a: return {1, {0, 0, 0}};
    case F::vertex_b: return {1, {1, 0, 0}};
    case F::vertex_c: return {1, {2, 0, 0}};
    case F::edge_ab: return {2, {0, 1, 0}};
    case F::edge_bc: return {2, {1, 2, 0}};
    case F::edge_ca: return {2, {2, 0, 0}};
    default: return {3, {0, 1, 2}};
  }
}

}  // namespace

ClosestPointGradient closest_point_backward(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                            const Eigen::Vector3d& p, const SurfacePoint& hit,
                                            const Eigen::Vector3d& grad) {
  if (hit.face < 0 || hit.face >= faces.rows())
    throw Error("closest_point_backward: face " + std::to_string(hit.face) + " is not a face of the mesh");
  const FeatureCorners fc = corners_of(hit.feature);
  ClosestPointGradient r;
  r.corner.fill(Eigen::Vector3d::Zero());
  r.count = fc.count;
  for (int k = 0; k < fc.count; ++k) r.vertex[k] = faces(hit.face, fc.slot[k]);
  const Eigen::Vector3d a = vertices.row(r.vertex[0]);
  // Where the span degenerates c does not follow p; the corners carry c by their weights.
  auto degenerate = [&]() {
    for (int k = 0; k < fc.count; ++k) r.corner[k] = hit.barycentric[fc.slot[k]] * grad;
    return r;
  };

  if (fc.count == 1) {
    r.corner[0] = grad;
    return r;
  }
  const Eigen::Vector3d to_p = p - hit.point;  // normal to the span at c
  if (fc.count == 2) {
    // c = a + t e: with q = g.e, dL/dp = m = q e / e.e (g along the edge) and
    // dL/de = t (g - m) + (q / e.e) (p - c); a gets the rest of g.
    const Eigen::Vector3d e = vertices.row(r.vertex[1]).transpose() - a;
    const double ee = e.squaredNorm();
    if (!(ee > 0)) return degenerate();
    const double t = hit.barycentric[fc.slot[1]];
    const double q = grad.dot(e) / ee;
    const Eigen::Vector3d m = q * e;
    r.query = m;
    r.corner[1] = t * (grad - m) + q * to_p;
    r.corner[0] = grad - m - r.corner[1];
    return r;
  }
  // c = a + u e1 + v e2 with G [u v]' = [e1.(p-a), e2.(p-a)]. With lambda = G^-1 [g.e1, g.e2],
  // m = lambda1 e1 + lambda2 e2 (g projected onto the face): dL/dp = m and
  // dL/de_i = w_i (g - m) + lambda_i (p - c), w = (u, v); a gets the rest.
  const Eigen::Vector3d e1 = vertices.row(r.vertex[1]).transpose() - a;
  const Eigen::Vector3d e2 = vertices.row(r.vertex[2]).transpose() - a;
  const double g11 = e1.squaredNorm(), g12 = e1.dot(e2), g22 = e2.squaredNorm();
  const double det = g11 * g22 - g12 * g12;
  if (!(det > 1e-24 * g11 * g22)) return degenerate();
  const double q1 = grad.dot(e1), q2 = grad.dot(e2);
  const double l1 = (g22 * q1 - g12 * q2) / det, l2 = (g11 * q2 - g12 * q1) / det;
  const Eigen::Vector3d m = l1 * e1 + l2 * e2;
  r.query = m;
  r.corner[1] = hit.barycentric[1] * (grad - m) + l1 * to_p;
  r.corner[2] = hit.barycentric[2] * (grad - m) + l2 * to_p;
  r.corner[0] = grad - m - r.corner[1] - r.corner[2];
  return r;
}

void closest_points_backward(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                             const Eigen::MatrixX3d& points, const std::vector<SurfacePoint>& hits,
                             const Eigen::MatrixX3d& grad_c, Eigen::MatrixX3d& grad_points,
                             Eigen::MatrixX3d& grad_vertices) {
  if (static_cast<Eigen::Index>(hits.size()) != points.rows() || grad_c.rows() != points.rows() ||
      grad_points.rows() != points.rows() || grad_vertices.rows() != vertices.rows())
    throw Error("closest_points_backward: " + std::to_string(points.rows()) + " points, " +
                std::to_string(hits.size()) + " hits, " + std::to_string(grad_c.rows()) + " gradients, " +
                std::to_string(grad_points.rows()) + " point gradients, " + std::to_string(grad_vertices.rows()) +
                " vertex gradients for " + std::to_string(vertices.rows()) + " vertices");
  // Sequential: corners are shared between points, and this is a few hundred
  // flops per point (well under a millisecond for a garment).
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d g = grad_c.row(i);
    if (g.isZero(0.0)) continue;
    const ClosestPointGradient r = closest_point_backward(vertices, faces, points.row(i).transpose(), hits[i], g);
    grad_points.row(i) += r.query.transpose();
    for (int k = 0; k < r.count; ++k) grad_vertices.row(r.vertex[k]) += r.corner[k].transpose();
  }
}

}  // namespace drape::geometry
