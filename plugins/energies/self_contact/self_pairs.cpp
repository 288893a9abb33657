// The self contact's primitives and pairs (self_pairs.hpp).
#include "self_pairs.hpp"

#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/box_pairs.hpp>
#include <drape/geometry/ccd.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/vertex_areas.hpp>

#include <algorithm>
#include <cmath>

namespace drape::self_contact {

namespace {

bool contains(const std::vector<int>& sorted, int v) { return std::binary_search(sorted.begin(), sorted.end(), v); }

bool share_one(const std::vector<int>& a, const std::vector<int>& b) {
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i == *j) return true;
    *i < *j ? ++i : ++j;
  }
  return false;
}

// True when some vertex of the first `na` of v and some of the rest are joined
// by a path of at most two mesh edges: neighbours in the fabric.
bool fabric_neighbours(const SelfTopology& t, const std::array<int, 4>& v, int na) {
  for (int i = 0; i < na; ++i)
    for (int j = na; j < 4; ++j) {
      const auto& ni = t.neighbours[static_cast<std::size_t>(v[i])];
      if (contains(ni, v[j]) || share_one(ni, t.neighbours[static_cast<std::size_t>(v[j])])) return true;
    }
  return false;
}

double pair_distance2(PairKind kind, const std::array<Eigen::Vector3d, 4>& p) {
  return kind == PairKind::EdgeEdge ? geometry::edge_edge_distance2(p[0], p[1], p[2], p[3])
                                    : geometry::point_triangle_distance2(p[0], p[1], p[2], p[3]);
}

std::array<Eigen::Vector3d, 4> points(const Eigen::MatrixX3d& x, const std::array<int, 4>& v) {
  return {x.row(v[0]).transpose(), x.row(v[1]).transpose(), x.row(v[2]).transpose(), x.row(v[3]).transpose()};
}

}  // namespace

std::uint64_t pair_key(PairKind kind, int a, int b) {
  return (static_cast<std::uint64_t>(kind) << 62) | (static_cast<std::uint64_t>(a) << 31) | static_cast<std::uint64_t>(b);
}

std::array<int, 4> SelfTopology::vertices_of(PairKind kind, int a, int b) const {
  if (kind == PairKind::VertexFace) return {a, faces(b, 0), faces(b, 1), faces(b, 2)};
  const auto& ea = edges[static_cast<std::size_t>(a)];
  const auto& eb = edges[static_cast<std::size_t>(b)];
  return {ea[0], ea[1], eb[0], eb[1]};
}

bool SelfTopology::skipped(PairKind kind, int a, int b) const {
  const std::array<int, 4> v = vertices_of(kind, a, b);
  const int na = kind == PairKind::VertexFace ? 1 : 2;
  for (int i = 0; i < na; ++i)
    for (int j = na; j < 4; ++j)
      if (v[i] == v[j]) return true;
  if (tangled_faces > 0) {
    bool first = false, second = false;
    for (int i = 0; i < 4; ++i) (i < na ? first : second) |= tangled[static_cast<std::size_t>(v[i])] != 0;
    if (first && second) return true;
  }
  return std::binary_search(excluded.begin(), excluded.end(), pair_key(kind, a, b));
}

double SelfTopology::thin_dhat(PairKind kind, int a, int b) const {
  if (thin.empty()) return 0;
  const std::uint64_t key = pair_key(kind, a, b);
  const auto it = std::lower_bound(thin.begin(), thin.end(), key, [](const auto& e, std::uint64_t k) { return e.first < k; });
  return it != thin.end() && it->first == key ? it->second : 0;
}

namespace {

// Marks the vertices of the rest mesh's faces that meet another face (a
// crossing or a touch the barrier cannot start from) and one ring around them.
void mark_tangles(const Mesh& mesh, SelfTopology& t) {
  const auto meeting = geometry::self_intersections(mesh.vertices, mesh.faces, static_cast<std::size_t>(mesh.num_faces()) * 4);
  std::vector<char> face_met(static_cast<std::size_t>(mesh.num_faces()), 0);
  for (auto [f, g] : meeting) face_met[static_cast<std::size_t>(f)] = face_met[static_cast<std::size_t>(g)] = 1;
  t.tangled.assign(static_cast<std::size_t>(t.vertices), 0);
  t.tangled_faces = static_cast<int>(std::count(face_met.begin(), face_met.end(), 1));
  std::vector<char> core(t.tangled.size(), 0);
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (face_met[static_cast<std::size_t>(f)])
      for (int k = 0; k < 3; ++k) core[static_cast<std::size_t>(mesh.faces(f, k))] = 1;
  for (std::size_t v = 0; v < core.size(); ++v)
    if (core[v]) {
      t.tangled[v] = 1;
      for (int w : t.neighbours[v]) t.tangled[static_cast<std::size_t>(w)] = 1;
    }
}

}  // namespace

SelfTopology make_topology(const Garment& garment, double exclusion, double thin_limit) {
  SelfTopology t;
  const Mesh& mesh = garment.mesh;
  t.faces = mesh.faces;
  t.vertices = mesh.num_vertices();
  t.edges = geometry::edge_list(t.faces);
  t.neighbours = geometry::vertex_neighbours(t.faces, t.vertices);
  t.vertex_area = geometry::vertex_areas(garment);
  geometry::EdgeWeights edges = geometry::edge_weights(garment, t.edges);
  t.edge_area = std::move(edges.area);
  t.edge_rest2 = std::move(edges.length2);
  mark_tangles(mesh, t);
  // Excluded: fabric neighbours closer than `exclusion` in the rest mesh as
  // cut (Garment::as_cut: before dressing pushed vertices together onto the
  // body). Boxes grown by half of it overlap for every pair that close (and more).
  const Eigen::MatrixX3d& cut = garment.as_cut();
  for (const SelfPair& c : candidate_pairs(t, cut, nullptr, 0.5 * exclusion)) {
    const std::array<int, 4> v = t.vertices_of(c.kind, c.a, c.b);
    if (!fabric_neighbours(t, v, c.kind == PairKind::VertexFace ? 1 : 2)) continue;
    const double d2 = pair_distance2(c.kind, points(cut, v));
    if (!(d2 < exclusion * exclusion)) continue;
    // A pair touching at rest (a nanometre) cannot be kept off itself: left out.
    // One at least twice the usual d_hat apart keeps the usual barrier (which
    // does not reach it at rest): no pair's barrier changes with distance.
    if (thin_limit > 0 && d2 > 1e-18)
      t.thin.emplace_back(pair_key(c.kind, c.a, c.b), std::min(thin_limit, 0.5 * std::sqrt(d2)));
    else
      t.excluded.push_back(pair_key(c.kind, c.a, c.b));
  }
  std::sort(t.excluded.begin(), t.excluded.end());
  std::sort(t.thin.begin(), t.thin.end());
  return t;
}

std::vector<SelfPair> candidate_pairs(const SelfTopology& t, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d* x_end,
                                      double inflate) {
  const geometry::MeshBoxes boxes = geometry::mesh_boxes(x, x_end, t.faces, t.edges, inflate);
  std::vector<SelfPair> out;
  for (auto [v, f] : geometry::overlapping_boxes(boxes.points, boxes.faces))
    if (!t.skipped(PairKind::VertexFace, v, f))
      out.push_back({PairKind::VertexFace, v, f, {}, 0, t.thin_dhat(PairKind::VertexFace, v, f)});
  for (auto [a, b] : geometry::overlapping_boxes(boxes.edges, boxes.edges))
    if (a < b && !t.skipped(PairKind::EdgeEdge, a, b))
      out.push_back({PairKind::EdgeEdge, a, b, {}, 0, t.thin_dhat(PairKind::EdgeEdge, a, b)});
  return out;
}

std::vector<SelfPair> close_pairs(const SelfTopology& t, const Eigen::MatrixX3d& x, std::vector<SelfPair> candidates,
                                  double below2) {
  const int n = static_cast<int>(candidates.size());
  std::vector<char> keep(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (int i = 0; i < n; ++i) {
    SelfPair& c = candidates[static_cast<std::size_t>(i)];
    const std::array<Eigen::Vector3d, 4> p = points(x, t.vertices_of(c.kind, c.a, c.b));
    c.distance2 = pair_distance2(c.kind, p);
    const double limit2 = c.dhat > 0 ? std::min(below2, c.dhat * c.dhat) : below2;
    if (c.distance2 < limit2)
      c.type = c.kind == PairKind::EdgeEdge ? geometry::edge_edge_type(p[0], p[1], p[2], p[3])
                                            : geometry::point_triangle_type(p[0], p[1], p[2], p[3]);
    keep[static_cast<std::size_t>(i)] = c.distance2 < limit2;
  }
  std::vector<SelfPair> out;
  for (int i = 0; i < n; ++i)
    if (keep[static_cast<std::size_t>(i)]) out.push_back(candidates[static_cast<std::size_t>(i)]);
  return out;
}

}  // namespace drape::self_contact
