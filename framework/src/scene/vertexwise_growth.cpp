// A shrunk body grown back vertex by vertex, each as far as its own contact
// pairs' collision checks allow (vertexwise_growth.hpp).
#include "vertexwise_growth.hpp"

#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/box_pairs.hpp>
#include <drape/geometry/ccd.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace drape::scene_detail {

VertexwiseGrowth::VertexwiseGrowth(const Eigen::MatrixX3i& body_faces, const Eigen::MatrixX3i& garment_faces)
    : body_faces_(body_faces),
      garment_faces_(garment_faces),
      body_edges_(geometry::edge_list(body_faces)),
      garment_edges_(geometry::edge_list(garment_faces)) {}

Eigen::MatrixX3d VertexwiseGrowth::step(const Eigen::MatrixX3d& now, const Eigen::MatrixX3d& target,
                                        const Eigen::MatrixX3d& x, double floor, double min_separation) const {
  const Eigen::MatrixX3d move = target - now;
  // The body's boxes grown by the floor: a pair that would end closer than it
  // must be seen even when it cannot touch.
  const geometry::MeshBoxes garment = geometry::mesh_boxes(x, nullptr, garment_faces_, garment_edges_, 0.0);
  const geometry::MeshBoxes body = geometry::mesh_boxes(now, &target, body_faces_, body_edges_, floor);
  const auto pt = geometry::overlapping_boxes(garment.points, body.faces);
  const auto tp = geometry::overlapping_boxes(garment.faces, body.points);
  const auto ee = geometry::overlapping_boxes(garment.edges, body.edges);

  const Eigen::Vector3d still = Eigen::Vector3d::Zero();
  auto g = [&](int v) -> Eigen::Vector3d { return x.row(v).transpose(); };
  auto b = [&](int v) -> Eigen::Vector3d { return now.row(v).transpose(); };
  auto d = [&](int v) -> Eigen::Vector3d { return move.row(v).transpose(); };
  const Eigen::VectorXd way = move.rowwise().norm();
  Eigen::VectorXd share = Eigen::VectorXd::Ones(now.rows());
  // A pair may close to min_separation of its gap, but not below `floor`
  // while its body vertices still have farther than that to go: the barrier
  // must push the cloth out ahead of the body, and a gap squeezed to nothing
  // by repeated growth leaves it no room (its force grows without bound and
  // the next weight step cannot clear every such pair at once).
  auto pair_share = [&](double gap2, double still_to_go, auto&& ccd) {
    const double gap = std::sqrt(gap2), keep = std::min(floor, still_to_go);
    if (!(gap > keep)) return 0.0;
    return ccd(std::max(min_separation, keep / gap));
  };
  // Serial: the pairs are few while the body grows (only the close regions),
  // and the result must not depend on a thread count.
  for (const auto& [v, f] : pt) {
    const std::array<int, 3> c{body_faces_(f, 0), body_faces_(f, 1), body_faces_(f, 2)};
    const double t = pair_share(geometry::point_triangle_distance2(g(v), b(c[0]), b(c[1]), b(c[2])),
                                std::max({way[c[0]], way[c[1]], way[c[2]]}), [&](double ratio) {
                                  return geometry::point_triangle_ccd(g(v), still, b(c[0]), d(c[0]), b(c[1]), d(c[1]),
                                                                      b(c[2]), d(c[2]), ratio);
                                });
    for (int k : c) share[k] = std::min(share[k], t);
  }
  for (const auto& [f, v] : tp) {
    const std::array<int, 3> c{garment_faces_(f, 0), garment_faces_(f, 1), garment_faces_(f, 2)};
    const double t = pair_share(geometry::point_triangle_distance2(b(v), g(c[0]), g(c[1]), g(c[2])), way[v], [&](double ratio) {
      return geometry::point_triangle_ccd(b(v), d(v), g(c[0]), still, g(c[1]), still, g(c[2]), still, ratio);
    });
    share[v] = std::min(share[v], t);
  }
  for (const auto& [eg, eb] : ee) {
    const auto& a = garment_edges_[static_cast<std::size_t>(eg)];
    const auto& e = body_edges_[static_cast<std::size_t>(eb)];
    const double t = pair_share(geometry::edge_edge_distance2(g(a[0]), g(a[1]), b(e[0]), b(e[1])), std::max(way[e[0]], way[e[1]]),
                                [&](double ratio) {
                                  return geometry::edge_edge_ccd(g(a[0]), still, g(a[1]), still, b(e[0]), d(e[0]), b(e[1]),
                                                                 d(e[1]), ratio);
                                });
    share[e[0]] = std::min(share[e[0]], t);
    share[e[1]] = std::min(share[e[1]], t);
  }
  Eigen::MatrixX3d moved = now;
  for (Eigen::Index v = 0; v < now.rows(); ++v) {
    if (share[v] >= 1) moved.row(v) = target.row(v);  // exactly: the body is known grown when it equals its target
    else moved.row(v) += share[v] * move.row(v);
  }
  return moved;
}

}  // namespace drape::scene_detail
