// The self contact's continuous collision check (self_contact.hpp, max_step).
#include "self_contact.hpp"
#include "self_pairs.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/box_pairs.hpp>
#include <drape/geometry/ccd.hpp>

#include <algorithm>

namespace drape::self_contact {

double SelfContact::max_step(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, const Eigen::MatrixX3d* /*body_from*/,
                             const Eigen::MatrixX3d* /*body_to*/) const {
  check(x);
  if (dx.rows() != x.rows()) throw Error("max_step's move has the wrong vertex count");
  if (!dx.allFinite()) throw ConfigError("max_step's move has a non-finite coordinate");
  const SelfTopology& t = *topology_;
  const Eigen::MatrixX3d x1 = x + dx;
  // Candidates: the pairs whose swept boxes overlap (boxes that never meet
  // hold primitives that cannot touch), less those that never count.
  // Within the Verlet list's reach its candidates, filtered by the same box
  // test, are those pairs (in the same order): no grid to build.
  std::vector<SelfPair> pairs;
  if (std::optional<std::vector<SelfPair>> listed = candidates_covering(x, dx)) {
    const geometry::MeshBoxes boxes = geometry::mesh_boxes(x, &x1, t.faces, t.edges, 0.0);
    for (const SelfPair& p : *listed) {
      const auto a = static_cast<std::size_t>(p.a), b = static_cast<std::size_t>(p.b);
      if (p.kind == PairKind::VertexFace ? geometry::boxes_overlap(boxes.points[a], boxes.faces[b])
                                         : geometry::boxes_overlap(boxes.edges[a], boxes.edges[b]))
        pairs.push_back(p);
    }
  } else {
    pairs = candidate_pairs(t, x, &x1, 0.0);
  }
  const double s = settings_.min_separation;
  auto p0 = [&](int v) -> Eigen::Vector3d { return x.row(v).transpose(); };
  auto pd = [&](int v) -> Eigen::Vector3d { return dx.row(v).transpose(); };
  double alpha = 1.0;
  const int n = static_cast<int>(pairs.size());
#pragma omp parallel for schedule(dynamic, 256) reduction(min : alpha)
  for (int i = 0; i < n; ++i) {
    const SelfPair& p = pairs[static_cast<std::size_t>(i)];
    const std::array<int, 4> v = t.vertices_of(p.kind, p.a, p.b);
    const double a = p.kind == PairKind::VertexFace
                         ? geometry::point_triangle_ccd(p0(v[0]), pd(v[0]), p0(v[1]), pd(v[1]), p0(v[2]), pd(v[2]), p0(v[3]), pd(v[3]), s)
                         : geometry::edge_edge_ccd(p0(v[0]), pd(v[0]), p0(v[1]), pd(v[1]), p0(v[2]), pd(v[2]), p0(v[3]), pd(v[3]), s);
    alpha = std::min(alpha, a);
  }
  return alpha;
}

}  // namespace drape::self_contact
