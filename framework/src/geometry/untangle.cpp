#include <drape/geometry/untangle.hpp>

#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include "height_field_nodes.hpp"
#include "triangle_bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace drape::geometry {
namespace {

// (edge, face) pairs as self_edge_crossings (self_intersection.hpp) lists them.
using Crossings = std::vector<std::pair<std::pair<int, int>, int>>;

// Edge (a, b) against face f: recorded in `hits` when it passes through the
// face (touching counts) and shares no vertex with it.
void test_edge(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, int a, int b, int f, Crossings& hits) {
  const auto ring = faces.row(f).array();
  if ((ring == a).any() || (ring == b).any()) return;
  if (segment_pierces_triangle(x.row(a), x.row(b), x.row(faces(f, 0)), x.row(faces(f, 1)), x.row(faces(f, 2))))
    hits.push_back({{a, b}, f});
}

// Edge (a, b) against every face whose box meets its box, but those under
// node `skip` of the tree (-1: none).
void search_edge(const TriangleBvh& faces_tree, const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, int a, int b,
                 int skip, std::vector<int>& near, Crossings& hits) {
  const Eigen::Vector3d p = x.row(a), q = x.row(b);
  near.clear();
  faces_tree.overlapping(p.cwiseMin(q), p.cwiseMax(q), near, skip);
  for (const int f : near) test_edge(x, faces, a, b, f, hits);
}

// The garment's edges through its own faces that share no vertex with them
// (touching counts), sorted: the pairs self_edge_crossings finds, through the
// garment's own hierarchy of faces refitted to x, one descent an edge.
// Measured on the coarse shirt (one core): self_edge_crossings's grid 2.8 ms
// (28,711 edge-face box pairs, all but 323 an edge and a face of its own
// ring), one descent an edge 0.7 ms; the hierarchy against itself (face pairs)
// 1.3 ms and one descent a face 1.8 ms, as each face's box meets more faces.
// Most of an edge's descent is into the cloth around it, which cannot cross
// it where it is a height field (height_field_nodes.hpp): each edge's
// descent passes over the largest such node holding its faces.
Crossings find_crossings(TriangleBvh& faces_tree, HeightFieldNodes& height_fields, const Eigen::MatrixX3d& x,
                         const Eigen::MatrixX3i& faces, const std::vector<std::array<int, 2>>& edges, int* culled) {
  faces_tree.refit(x);
  height_fields.certify(x);
  Crossings hits;
  std::vector<int> near;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const int skip = height_fields.cover(static_cast<int>(e));
    if (culled && skip >= 0) ++*culled;
    search_edge(faces_tree, x, faces, edges[e][0], edges[e][1], skip, near, hits);
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

// A crumple: a crossing edge within kCrumpleRings edges of its face (an
// end of the edge that many steps from a corner of the face), a fold
// narrower than a few of the mesh's rings. Cutting it separates a sliver or
// nothing, and pulling the edge off the face only hands the crossing on to
// the next edge of the fold (a pinch). Each of its five vertices moves
// kCrumpleSmoothing of the way to the mean of its neighbours instead (along
// the border for a border vertex, so a hem or a cuff is not pulled in),
// which flattens the fold over the rounds. Measured on the shipped models'
// test predictions that cross themselves (9 of the human rig's 99 test
// bodies, 3 of the posed model's 39; docs/bodies.md): the pulls alone left
// 3 of the 12 (a heavy body's underarm and cuffs); within one ring a
// posed body whose fold spans three was left; with three rings none is
// left. A share of 0.15 undoes them in at most 4 rounds, moving no vertex
// more than 16 mm (0.25-0.5: 1-2 rounds, up to 21 mm). A garment the three
// rings leave crossed is tried again with four (Untangler::run): a closer
// posed model (docs/poses.md, "The crumples' reach") left two edges of a
// BMI 64 woman's right underarm interlocked four rings apart, which three
// rings cut as two sheets and hand on. Four rings for every garment is not
// better: on a folded strip with a bump pushed through beside the fold it
// left more crossings than three in two cases of 24, and fewer in one.
constexpr double kCrumpleSmoothing = 0.15;
constexpr int kCrumpleRings = 3;

// A crossing within the crumples' reach is two layers when, at rest, both
// ends of its edge lie this far or more on one side of the face's plane:
// the sleeve's two layers at the underarm of a BMI 30 body (sample 1962 of
// the A-pose human model's expanded set; docs/bodies.md) are 18-67 mm
// apart there, 2-3 rings from each other across the seam; a fold of one
// sheet, flat at rest, is within a few millimetres of its own plane.
constexpr double kLayerDepth = 0.01;

// A patch whose cut edges ask for directions more than about 75 degrees off
// its mean direction still moves along the mean, but no further than four
// times the largest depth (the mean of opposed pulls is short).
constexpr double kLeastAlignment = 0.25;

// The components of the vertex graph (each vertex's root) with the edges in
// `cut` (sorted) left out.
std::vector<int> components(const std::vector<std::array<int, 2>>& edges, int n, const std::vector<std::array<int, 2>>& cut) {
  std::vector<int> parent(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) parent[static_cast<std::size_t>(v)] = v;
  const auto root = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (const auto& e : edges) {
    if (std::binary_search(cut.begin(), cut.end(), e)) continue;
    const int ra = root(e[0]), rb = root(e[1]);
    if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }
  for (int v = 0; v < n; ++v) parent[static_cast<std::size_t>(v)] = root(v);
  return parent;
}

// The crossings again after a round that moved only the vertices flagged in
// `moved`: a pair whose edge and face kept their vertices stays as it was;
// the edges at a moved vertex are searched again, and so is each face with
// a moved vertex against the edges of the faces near it. A round moves a
// few dozen vertices, so this costs a fraction of a full search.
void update_crossings(TriangleBvh& faces_tree, HeightFieldNodes& height_fields, const Eigen::MatrixX3d& x,
                      const Eigen::MatrixX3i& faces, const std::vector<std::array<int, 2>>& edges,
                      const std::vector<std::vector<int>>& vertex_edges, const std::vector<std::vector<int>>& vertex_faces,
                      const std::vector<char>& moved, Crossings& hits) {
  faces_tree.refit(x);
  height_fields.certify(x);
  const auto face_moved = [&](int f) { return moved[faces(f, 0)] || moved[faces(f, 1)] || moved[faces(f, 2)]; };
  std::erase_if(hits, [&](const auto& hit) { return moved[hit.first.first] || moved[hit.first.second] || face_moved(hit.second); });
  std::vector<char> edge_done(edges.size(), 0), face_done(static_cast<std::size_t>(faces.rows()), 0);
  std::vector<int> near;
  for (std::size_t v = 0; v < moved.size(); ++v) {
    if (!moved[v]) continue;
    for (const int e : vertex_edges[v]) {  // a moved edge against every face near it
      if (edge_done[static_cast<std::size_t>(e)]) continue;
      edge_done[static_cast<std::size_t>(e)] = 1;
      const auto [a, b] = edges[static_cast<std::size_t>(e)];
      search_edge(faces_tree, x, faces, a, b, height_fields.cover(e), near, hits);
    }
    for (const int f : vertex_faces[v]) {  // a moved face against the unmoved edges near it
      if (face_done[static_cast<std::size_t>(f)]) continue;
      face_done[static_cast<std::size_t>(f)] = 1;
      const Eigen::Vector3d p0 = x.row(faces(f, 0)), p1 = x.row(faces(f, 1)), p2 = x.row(faces(f, 2));
      near.clear();
      faces_tree.overlapping(p0.cwiseMin(p1).cwiseMin(p2), p0.cwiseMax(p1).cwiseMax(p2), near);
      for (const int g : near)
        for (int k = 0; k < 3; ++k) {
          const int a = std::min(faces(g, k), faces(g, (k + 1) % 3)), b = std::max(faces(g, k), faces(g, (k + 1) % 3));
          if (!moved[a] && !moved[b]) test_edge(x, faces, a, b, f, hits);
        }
    }
  }
  std::sort(hits.begin(), hits.end());
  hits.erase(std::unique(hits.begin(), hits.end()), hits.end());  // an unmoved edge of two faces near a moved one
}

// Where one vertex of a crossing edge must go: along `direction` by `amount`.
struct Pull {
  Eigen::Vector3d direction;
  double amount;
};

// Face f's unit normal and a corner; false for a face without a plane.
bool face_plane(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, int f, Eigen::Vector3d& normal, Eigen::Vector3d& corner) {
  corner = x.row(faces(f, 0));
  normal = (x.row(faces(f, 1)).transpose() - corner).cross(x.row(faces(f, 2)).transpose() - corner);
  if (!(normal.norm() > 0)) return false;
  normal.normalize();
  return true;
}

// Vertex v's height over face f's plane; 0 for a face without a plane.
double signed_height(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, int f, int v) {
  Eigen::Vector3d n, p0;
  return face_plane(x, faces, f, n, p0) ? n.dot(x.row(v).transpose() - p0) : 0.0;
}

// Vertex v of a crossing edge (v, u) back across face f's plane, to the side
// its edge's other end u is on (the side of the rest of its sheet), `gap`
// beyond it. False when neither end is off the plane (no side to go to) or
// the face has no plane.
bool pull_across(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, int f, int v, int u, double gap, Pull& pull) {
  Eigen::Vector3d n, p0;
  if (!face_plane(x, faces, f, n, p0)) return false;
  const double sv = n.dot(x.row(v).transpose() - p0), su = n.dot(x.row(u).transpose() - p0);
  const double target = su > 0 ? 1.0 : su < 0 ? -1.0 : sv > 0 ? -1.0 : sv < 0 ? 1.0 : 0.0;
  if (target == 0) return false;
  pull.direction = target * n;
  pull.amount = std::max(0.0, gap - target * sv);
  return true;
}

// The side (+1 or -1) of face f's plane that both ends of edge (a, b) are
// on at rest, kLayerDepth or more off it; 0 when they are not.
int side_at_rest(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3i& faces, int f, int a, int b) {
  const double ha = signed_height(rest, faces, f, a), hb = signed_height(rest, faces, f, b);
  if (ha >= kLayerDepth && hb >= kLayerDepth) return 1;
  if (ha <= -kLayerDepth && hb <= -kLayerDepth) return -1;
  return 0;
}

}  // namespace

// What a garment's topology fixes: its edges, its connected pieces, and the
// hierarchy of its faces (built at the first run, refitted after).
struct Untangler::Topology {
  Eigen::MatrixX3i faces;
  int num_vertices;
  std::vector<std::array<int, 2>> edges;
  std::vector<int> piece, piece_size;
  std::vector<std::vector<int>> vertex_edges, vertex_faces;  // the edges and faces at each vertex
  // Each vertex's neighbours for the crumples' smoothing: along the border
  // for a border vertex (the mean of all its neighbours would pull a hem or
  // a cuff in; an edge of more than two faces counts as border, as
  // face_neighbours has it), all of them otherwise.
  std::vector<std::vector<int>> smoothing_neighbours;
  std::optional<TriangleBvh> faces_tree;
  std::optional<HeightFieldNodes> height_fields;  // of faces_tree's nodes
};

Untangler::Untangler(const Eigen::MatrixX3i& faces, int num_vertices) : topology_(std::make_unique<Topology>()) {
  if (faces.size() > 0 && (faces.minCoeff() < 0 || faces.maxCoeff() >= num_vertices))
    throw Error("untangle: a face indexes a vertex outside the garment's " + std::to_string(num_vertices));
  Topology& t = *topology_;
  t.faces = faces;
  t.num_vertices = num_vertices;
  t.edges = edge_list(faces);
  t.piece = components(t.edges, num_vertices, {});
  t.piece_size.assign(static_cast<std::size_t>(num_vertices), 0);
  for (const int r : t.piece) ++t.piece_size[static_cast<std::size_t>(r)];
  t.vertex_edges.resize(static_cast<std::size_t>(num_vertices));
  t.vertex_faces.resize(static_cast<std::size_t>(num_vertices));
  for (std::size_t e = 0; e < t.edges.size(); ++e)
    for (const int v : t.edges[e]) t.vertex_edges[static_cast<std::size_t>(v)].push_back(static_cast<int>(e));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) t.vertex_faces[static_cast<std::size_t>(faces(f, k))].push_back(static_cast<int>(f));
  // A vertex on the border (an edge with no face across it) keeps only its
  // border neighbours.
  t.smoothing_neighbours = vertex_neighbours(faces, num_vertices);
  std::vector<std::vector<int>> along_border(static_cast<std::size_t>(num_vertices));
  const std::vector<std::array<int, 3>> across = face_neighbours(faces);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (across[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)] < 0) {
        const int a = faces(f, k), b = faces(f, (k + 1) % 3);
        along_border[static_cast<std::size_t>(a)].push_back(b);
        along_border[static_cast<std::size_t>(b)].push_back(a);
      }
  for (std::size_t v = 0; v < along_border.size(); ++v)
    if (!along_border[v].empty()) t.smoothing_neighbours[v] = std::move(along_border[v]);
}

Untangler::~Untangler() = default;

UntangleReport untangle(Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, const UntangleOptions& options) {
  return Untangler(faces, static_cast<int>(vertices.rows())).run(vertices, options);
}

UntangleReport Untangler::run(Eigen::MatrixX3d& vertices, const UntangleOptions& options) {
  const Eigen::MatrixX3d start = vertices;  // (the one copy: every run below starts from it)
  const UntangleReport narrow = run_with_reach(start, vertices, options, kCrumpleRings);
  if (narrow.crossings_after == 0) return narrow;  // (the usual case: also when nothing crossed)
  Eigen::MatrixX3d widened = start;
  const UntangleReport wide = run_with_reach(start, widened, options, kCrumpleRings + 1);
  if (wide.crossings_after >= narrow.crossings_after) return narrow;
  vertices = widened;
  return wide;
}

UntangleReport Untangler::run_with_reach(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& vertices, const UntangleOptions& options,
                                         int crumple_rings) {
  if (!options.rest) return run_once(vertices, options, crumple_rings);
  const UntangleReport layers = run_once(vertices, options, crumple_rings);
  if (layers.crossings_before == 0) return layers;  // the usual case: nothing crossed, nothing moved
  Eigen::MatrixX3d smoothed = start;
  UntangleOptions without = options;
  without.rest = nullptr;
  const UntangleReport crumples = run_once(smoothed, without, crumple_rings);
  // Fewer crossings left, then the less moved (summed over the vertices:
  // the two layers a simulation presses flat at the underarm, pulled a
  // centimetre or more apart, are further from it than the smoothing leaves them).
  const double moved_layers = (vertices - start).rowwise().norm().sum();
  const double moved_crumples = (smoothed - start).rowwise().norm().sum();
  if (layers.crossings_after < crumples.crossings_after ||
      (layers.crossings_after == crumples.crossings_after && moved_layers <= moved_crumples))
    return layers;
  vertices = smoothed;
  return crumples;
}

UntangleReport Untangler::run_once(Eigen::MatrixX3d& vertices, const UntangleOptions& options, int crumple_rings) {
  Topology& topology = *topology_;
  const int n = topology.num_vertices;
  if (vertices.rows() != n)
    throw Error("untangle: the garment has " + std::to_string(vertices.rows()) + " vertices, its faces " + std::to_string(n));
  if (!(options.gap >= 0) || !std::isfinite(options.gap)) throw Error("untangle: the gap must be finite and >= 0");
  if (options.max_rounds < 1) throw Error("untangle: at least one round");
  if (options.patience < 1) throw Error("untangle: a patience of at least one round");
  if (!vertices.allFinite()) throw Error("untangle: the garment has a non-finite vertex");
  if (options.rest && (options.rest->rows() != n || !options.rest->allFinite()))
    throw Error("untangle: the garment at rest must have the garment's " + std::to_string(n) + " vertices, all finite");

  UntangleReport report;
  const Eigen::MatrixX3i& faces = topology.faces;
  const std::vector<std::array<int, 2>>& edges = topology.edges;
  const std::vector<int>& piece = topology.piece;
  const std::vector<int>& piece_size = topology.piece_size;
  if (!topology.faces_tree) {
    topology.faces_tree.emplace(vertices, faces);
    topology.height_fields.emplace(*topology.faces_tree, faces, edges, topology.vertex_faces);
  }
  TriangleBvh& faces_tree = *topology.faces_tree;
  HeightFieldNodes& height_fields = *topology.height_fields;
  Crossings hits = find_crossings(faces_tree, height_fields, vertices, faces, edges, &report.edges_culled);
  report.crossings_before = static_cast<int>(hits.size());
  if (hits.empty()) return report;  // the usual case: one search, nothing copied
  // Whether edge (a, b) is within crumple_rings edges of a corner of face f:
  // one breadth-first search from both its ends.
  std::vector<int> ring_mark(static_cast<std::size_t>(n), -1), frontier, next;
  int ring_query = 0;
  const auto is_crumple = [&](int a, int b, int f) {
    ++ring_query;
    frontier = {a, b};
    ring_mark[static_cast<std::size_t>(a)] = ring_mark[static_cast<std::size_t>(b)] = ring_query;
    for (int ring = 0; ring < crumple_rings; ++ring) {
      next.clear();
      for (const int w : frontier)
        for (const int e : topology.vertex_edges[static_cast<std::size_t>(w)]) {
          const auto& [e0, e1] = edges[static_cast<std::size_t>(e)];
          const int u = e0 == w ? e1 : e0;
          if (u == faces(f, 0) || u == faces(f, 1) || u == faces(f, 2)) return true;
          if (ring_mark[static_cast<std::size_t>(u)] != ring_query) ring_mark[static_cast<std::size_t>(u)] = ring_query, next.push_back(u);
        }
      frontier.swap(next);
    }
    return false;
  };
  const Eigen::MatrixX3d start = vertices;
  // The moves of an open curve can hand a crossing on instead of undoing it
  // (two edges through each other's faces, a pinch): the fewest crossings
  // seen are what is returned, so a round never leaves the cloth worse.
  Eigen::MatrixX3d best = vertices;
  std::size_t fewest = hits.size();
  int rounds_to_best = 0, patches_to_best = 0, crumples_to_best = 0, layers_to_best = 0, idle = 0;
  for (int round = 0; round < options.max_rounds && !hits.empty() && idle < options.patience; ++round) {
    std::vector<std::array<int, 2>> cut;
    std::vector<char> smooth(static_cast<std::size_t>(n), 0), crumple(hits.size(), 0);
    std::vector<signed char> layered(hits.size(), 0);  // per crossing: its edge's side at rest (+1 or -1), 0: none
    for (std::size_t h = 0; h < hits.size(); ++h) {
      const auto& [edge, f] = hits[h];
      crumple[h] = is_crumple(edge.first, edge.second, f);
      if (crumple[h] && options.rest) layered[h] = static_cast<signed char>(side_at_rest(*options.rest, faces, f, edge.first, edge.second));
      if (layered[h] != 0) {
        crumple[h] = 0;  // pulled to its side, below
        continue;
      }
      if (crumple[h]) {  // smoothed, not cut
        ++report.crumples_smoothed;
        for (const int v : {edge.first, edge.second, faces(f, 0), faces(f, 1), faces(f, 2)}) smooth[static_cast<std::size_t>(v)] = 1;
        continue;
      }
      cut.push_back({edge.first, edge.second});
    }
    cut.erase(std::unique(cut.begin(), cut.end()), cut.end());  // (hits are sorted by edge)
    const std::vector<int> region = components(edges, n, cut);
    std::vector<int> region_size(static_cast<std::size_t>(n), 0), largest(static_cast<std::size_t>(n), -1);
    for (const int r : region) ++region_size[static_cast<std::size_t>(r)];
    for (int v = 0; v < n; ++v) {
      const int r = region[static_cast<std::size_t>(v)], p = piece[static_cast<std::size_t>(v)];
      int& l = largest[static_cast<std::size_t>(p)];
      if (l < 0 || region_size[static_cast<std::size_t>(r)] > region_size[static_cast<std::size_t>(l)]) l = r;
    }
    // A patch: a region split off its piece by the cut, not the piece's
    // largest, and small enough that the curve round it is a closed one.
    const auto is_patch = [&](int v) {
      const int r = region[static_cast<std::size_t>(v)], p = piece[static_cast<std::size_t>(v)];
      return r != largest[static_cast<std::size_t>(p)] &&
             region_size[static_cast<std::size_t>(r)] <= options.largest_patch * piece_size[static_cast<std::size_t>(p)];
    };

    std::vector<std::vector<Pull>> patch_pulls(static_cast<std::size_t>(n));  // by region root
    std::vector<char> partner_moves(static_cast<std::size_t>(n), 0);
    std::vector<Pull> vertex_pull(static_cast<std::size_t>(n), Pull{Eigen::Vector3d::Zero(), 0.0});
    const auto ask = [&](int v, const Eigen::Vector3d& direction, double amount) {
      Pull& slot = vertex_pull[static_cast<std::size_t>(v)];
      if (amount > slot.amount) slot = Pull{direction, amount};
    };
    for (std::size_t h = 0; h < hits.size(); ++h) {
      if (crumple[h]) continue;
      const auto& [edge, f] = hits[h];
      const int a = edge.first, b = edge.second;
      if (layered[h] != 0) {
        // Two layers: the edge to its side at rest, the face away from it,
        // half the way each, until the edge's end on the wrong side is `gap` beyond.
        Eigen::Vector3d normal, corner;
        if (!face_plane(vertices, faces, f, normal, corner)) continue;
        const double side = layered[h];
        const double depth = std::max(options.gap - side * normal.dot(vertices.row(a).transpose() - corner),
                                      options.gap - side * normal.dot(vertices.row(b).transpose() - corner));
        if (!(depth > 0)) continue;
        ++report.layers_pulled;
        ask(a, side * normal, 0.5 * depth);
        ask(b, side * normal, 0.5 * depth);
        for (int k = 0; k < 3; ++k) ask(faces(f, k), -side * normal, 0.5 * depth);
        continue;
      }
      bool in_patch = false;
      for (const auto& [v, u] : {std::pair{a, b}, std::pair{b, a}}) {
        const int rv = region[static_cast<std::size_t>(v)];
        if (!is_patch(v) || rv == region[static_cast<std::size_t>(u)]) continue;
        in_patch = true;
        Pull pull;
        if (!pull_across(vertices, faces, f, v, u, options.gap, pull)) continue;
        patch_pulls[static_cast<std::size_t>(rv)].push_back(pull);
        for (int k = 0; k < 3; ++k) {
          const int w = faces(f, k);
          if (is_patch(w) && region[static_cast<std::size_t>(w)] != rv) partner_moves[static_cast<std::size_t>(rv)] = 1;
        }
      }
      // A face a patch goes back through is left to the patch's move.
      for (int k = 0; k < 3; ++k) in_patch = in_patch || is_patch(faces(f, k));
      if (in_patch) continue;
      // An open curve (the cut separates nothing here): the edge and the
      // face pulled apart along the face's normal, half the way each, until
      // the edge's nearer end is on its farther end's side (moving that end
      // alone only hands the crossing on to its next edge).
      Pull pull;
      const bool a_nearer = std::abs(signed_height(vertices, faces, f, a)) <= std::abs(signed_height(vertices, faces, f, b));
      if (!pull_across(vertices, faces, f, a_nearer ? a : b, a_nearer ? b : a, options.gap, pull)) continue;
      ask(a, pull.direction, 0.5 * pull.amount);
      ask(b, pull.direction, 0.5 * pull.amount);
      for (int k = 0; k < 3; ++k) ask(faces(f, k), -pull.direction, 0.5 * pull.amount);
    }

    // Each patch moved as one, along the mean of its pulls, far enough for
    // the deepest (half as far when the other sheet's patch moves too).
    std::vector<Eigen::Vector3d> patch_step(static_cast<std::size_t>(n), Eigen::Vector3d::Zero());
    bool moved = false;
    for (int r = 0; r < n; ++r) {
      const auto& pulls = patch_pulls[static_cast<std::size_t>(r)];
      if (pulls.empty()) continue;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const Pull& p : pulls) mean += p.direction;
      if (!(mean.norm() > 1e-9)) continue;
      const Eigen::Vector3d d = mean.normalized();
      double t = 0;
      for (const Pull& p : pulls) t = std::max(t, p.amount / std::max(d.dot(p.direction), kLeastAlignment));
      if (partner_moves[static_cast<std::size_t>(r)]) t *= 0.5;
      if (!(t > 0)) continue;
      patch_step[static_cast<std::size_t>(r)] = t * d;
      ++report.patches_moved;
      moved = true;
    }
    // The crumples' smoothing, from the positions before this round's moves.
    std::vector<std::pair<int, Eigen::Vector3d>> smoothing;
    for (int v = 0; v < n; ++v) {
      const auto& around = topology.smoothing_neighbours[static_cast<std::size_t>(v)];
      if (!smooth[static_cast<std::size_t>(v)] || around.empty()) continue;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const int u : around) mean += vertices.row(u).transpose();
      smoothing.emplace_back(v, kCrumpleSmoothing * (mean / static_cast<double>(around.size()) - vertices.row(v).transpose()));
    }
    std::vector<char> moved_now(static_cast<std::size_t>(n), 0);
    for (const auto& [v, step] : smoothing)
      if (step.squaredNorm() > 0) vertices.row(v) += step.transpose(), moved = true, moved_now[static_cast<std::size_t>(v)] = 1;
    for (int v = 0; v < n; ++v) {
      const Eigen::Vector3d& step = patch_step[static_cast<std::size_t>(region[static_cast<std::size_t>(v)])];
      if (step.squaredNorm() > 0) vertices.row(v) += step.transpose(), moved_now[static_cast<std::size_t>(v)] = 1;
      const Pull& pull = vertex_pull[static_cast<std::size_t>(v)];
      if (pull.amount > 0)
        vertices.row(v) += pull.amount * pull.direction.transpose(), moved = true, moved_now[static_cast<std::size_t>(v)] = 1;
    }
    if (!moved) break;
    ++report.rounds;
    if (options.after_round) options.after_round(vertices, moved_now);
    update_crossings(faces_tree, height_fields, vertices, faces, edges, topology.vertex_edges, topology.vertex_faces, moved_now, hits);
    if (hits.size() < fewest) {
      best = vertices, fewest = hits.size(), rounds_to_best = report.rounds, patches_to_best = report.patches_moved,
      crumples_to_best = report.crumples_smoothed, layers_to_best = report.layers_pulled, idle = 0;
    } else if (!cut.empty() || std::any_of(layered.begin(), layered.end(), [](signed char side) { return side != 0; })) {
      ++idle;  // pulls or cuts that left as many: a pinch handed on
    }
    // (A round of crumples only is not idle: the smoothing flattens the
    // fold a share at a time, and the count may hold for a few rounds before
    // it falls; max_rounds bounds it.)
  }
  if (hits.size() > fewest || (hits.size() == fewest && rounds_to_best < report.rounds)) {
    vertices = best;
    report.rounds = rounds_to_best;
    report.patches_moved = patches_to_best;
    report.crumples_smoothed = crumples_to_best;
    report.layers_pulled = layers_to_best;
  }
  report.crossings_after = static_cast<int>(fewest);
  const Eigen::VectorXd moves = (vertices - start).rowwise().norm();  // (n > 0: there were crossings)
  report.largest_move = moves.maxCoeff();
  report.vertices_moved = static_cast<int>((moves.array() > 0).count());
  return report;
}

}  // namespace drape::geometry
