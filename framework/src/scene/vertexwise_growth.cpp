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

namespace {

using geometry::Box;

// Boxes of each primitive (vertex lists of any length) over the move from -> to,
// grown by `pad` on every side.
template <class Primitives>
std::vector<Box> swept_boxes(const Eigen::MatrixX3d& from, const Eigen::MatrixX3d& to, const Primitives& primitives,
                             double pad = 0) {
  std::vector<Box> boxes;
  boxes.reserve(primitives.size());
  for (const auto& corners : primitives) {
    Box b{Eigen::Vector3d::Constant(1e300), Eigen::Vector3d::Constant(-1e300)};
    for (int v : corners) {
      b.lo = b.lo.cwiseMin(from.row(v).transpose()).cwiseMin(to.row(v).transpose());
      b.hi = b.hi.cwiseMax(from.row(v).transpose()).cwiseMax(to.row(v).transpose());
    }
    b.lo.array() -= pad;
    b.hi.array() += pad;
    boxes.push_back(b);
  }
  return boxes;
}

std::vector<std::array<int, 3>> face_list(const Eigen::MatrixX3i& faces) {
  std::vector<std::array<int, 3>> out(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) out[static_cast<std::size_t>(f)] = {faces(f, 0), faces(f, 1), faces(f, 2)};
  return out;
}

std::vector<std::array<int, 1>> point_list(Eigen::Index n) {
  std::vector<std::array<int, 1>> out(static_cast<std::size_t>(n));
  for (Eigen::Index v = 0; v < n; ++v) out[static_cast<std::size_t>(v)] = {static_cast<int>(v)};
  return out;
}

}  // namespace

Eigen::MatrixX3d grow_vertexwise(const Eigen::MatrixX3d& now, const Eigen::MatrixX3d& target,
                                 const Eigen::MatrixX3i& body_faces, const Eigen::MatrixX3d& x,
                                 const Eigen::MatrixX3i& garment_faces, double floor, double min_separation) {
  const Eigen::MatrixX3d move = target - now;
  const auto body_tris = face_list(body_faces), garment_tris = face_list(garment_faces);
  const auto body_points = point_list(now.rows()), garment_points = point_list(x.rows());
  const auto body_edges = geometry::edge_list(body_faces), garment_edges = geometry::edge_list(garment_faces);

  // The body's boxes grown by the floor: a pair that would end closer than it
  // must be seen even when it cannot touch.
  const auto pt = geometry::overlapping_boxes(swept_boxes(x, x, garment_points), swept_boxes(now, target, body_tris, floor));
  const auto tp = geometry::overlapping_boxes(swept_boxes(x, x, garment_tris), swept_boxes(now, target, body_points, floor));
  const auto ee = geometry::overlapping_boxes(swept_boxes(x, x, garment_edges), swept_boxes(now, target, body_edges, floor));

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
    const auto& c = body_tris[static_cast<std::size_t>(f)];
    const double t = pair_share(geometry::point_triangle_distance2(g(v), b(c[0]), b(c[1]), b(c[2])),
                                std::max({way[c[0]], way[c[1]], way[c[2]]}), [&](double ratio) {
                                  return geometry::point_triangle_ccd(g(v), still, b(c[0]), d(c[0]), b(c[1]), d(c[1]),
                                                                      b(c[2]), d(c[2]), ratio);
                                });
    for (int k : c) share[k] = std::min(share[k], t);
  }
  for (const auto& [f, v] : tp) {
    const auto& c = garment_tris[static_cast<std::size_t>(f)];
    const double t = pair_share(geometry::point_triangle_distance2(b(v), g(c[0]), g(c[1]), g(c[2])), way[v], [&](double ratio) {
      return geometry::point_triangle_ccd(b(v), d(v), g(c[0]), still, g(c[1]), still, g(c[2]), still, ratio);
    });
    share[v] = std::min(share[v], t);
  }
  for (const auto& [eg, eb] : ee) {
    const auto& a = garment_edges[static_cast<std::size_t>(eg)];
    const auto& e = body_edges[static_cast<std::size_t>(eb)];
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
