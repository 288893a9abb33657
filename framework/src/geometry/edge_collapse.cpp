// Half-edge collapses ordered by quadric error (Garland & Heckbert 1997) plus a
// length term, with the checks that keep a garment a garment: manifold (link
// condition), boundaries and UV seams slide only along themselves, seam corners
// stay, no face flips in 3D or in UV, no sliver triangles.
#include "edge_collapse.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace drape::geometry::detail {
namespace {

constexpr double kSqrt3 = 1.7320508075688772;

Eigen::Matrix4d plane_quadric(const Eigen::Vector3d& normal, const Eigen::Vector3d& point, double weight) {
  Eigen::Vector4d p;
  p << normal, -normal.dot(point);
  return weight * p * p.transpose();
}

// 4 sqrt(3) area / sum of squared edge lengths: 1 for equilateral, 0 for slivers.
double triangle_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double area2 = (b - a).cross(c - a).norm();
  const double sum = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return sum > 0 ? 2 * kSqrt3 * area2 / sum : 0.0;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

EdgeCollapser::EdgeCollapser(const Mesh& mesh, const HierarchyOptions& options)
    : opt_(options), pos_(mesh.vertices), uv_(mesh.uv) {
  const int n = mesh.num_vertices();
  const int nf = mesh.num_faces();
  fv_.resize(nf);
  fuv_.resize(nf);
  face_alive_.assign(nf, 1);
  vf_.assign(n, {});
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      fv_[f][k] = mesh.faces(f, k);
      fuv_[f][k] = mesh.uv_faces(f, k);
      vf_[fv_[f][k]].push_back(f);
    }
  int num_charts = 0;
  const Eigen::VectorXi chart = uv_charts(mesh, num_charts);
  chart_.assign(chart.data(), chart.data() + chart.size());
  vertex_alive_.assign(n, 1);
  alive_count_ = n;
  stamp_.assign(n, 0);
  cos_max_turn_ = std::cos(opt_.max_normal_turn_deg * M_PI / 180.0);

  // A vertex whose faces do not form one fan (or that sits on an edge with more
  // than two faces) is pinned: collapsing it could only make things worse.
  fixed_.assign(n, 0);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (int a = 0; a < n; ++a) {
    if (vf_[a].empty()) {
      fixed_[a] = 1;
      continue;
    }
    std::vector<int> spokes;
    for (int f : vf_[a]) {
      const int k = corner(f, a);
      const int b = fv_[f][(k + 1) % 3], c = fv_[f][(k + 2) % 3];
      spokes.push_back(b);
      spokes.push_back(c);
      parent[find_root(parent, b)] = find_root(parent, c);
    }
    std::sort(spokes.begin(), spokes.end());
    int roots = 0;
    for (std::size_t i = 0; i < spokes.size(); ++i) {
      const bool first = i == 0 || spokes[i] != spokes[i - 1];
      if (first && find_root(parent, spokes[i]) == spokes[i]) ++roots;
      if (i >= 2 && spokes[i] == spokes[i - 2]) fixed_[a] = 1;  // edge with > 2 faces
    }
    if (roots != 1) fixed_[a] = 1;
    for (int s : spokes) parent[s] = s;
  }

  // Quadrics: face planes weighted by area; boundary and seam edges add a plane
  // through the edge, perpendicular to the face, so their curves keep their shape.
  quadric_.assign(n, Eigen::Matrix4d::Zero());
  quadric_area_.assign(n, 0.0);
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d a = pos_.row(fv_[f][0]), b = pos_.row(fv_[f][1]), c = pos_.row(fv_[f][2]);
    Eigen::Vector3d normal = (b - a).cross(c - a);
    const double area = 0.5 * normal.norm();
    if (area <= 0) continue;
    normal.normalize();
    const Eigen::Matrix4d q = plane_quadric(normal, a, area);
    for (int k = 0; k < 3; ++k) {
      quadric_[fv_[f][k]] += q;
      quadric_area_[fv_[f][k]] += area;
    }
    for (int k = 0; k < 3; ++k) {
      const int i = fv_[f][k], j = fv_[f][(k + 1) % 3];
      if (!is_feature_edge(i, j)) continue;
      const Eigen::Vector3d pi = pos_.row(i), pj = pos_.row(j);
      const Eigen::Vector3d side = (pj - pi).cross(normal);
      if (side.norm() <= 0) continue;
      const Eigen::Matrix4d qe = plane_quadric(side.normalized(), pi, opt_.feature_weight * (pj - pi).squaredNorm());
      quadric_[i] += qe;
      quadric_[j] += qe;
    }
  }

  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = fv_[f][k], b = fv_[f][(k + 1) % 3];
      push(a, b);
      push(b, a);
    }
}

int EdgeCollapser::corner(int f, int a) const {
  return fv_[f][0] == a ? 0 : fv_[f][1] == a ? 1 : 2;
}

std::vector<int> EdgeCollapser::neighbours(int a) const {
  std::vector<int> out;
  for (int f : vf_[a])
    for (int k = 0; k < 3; ++k)
      if (fv_[f][k] != a) out.push_back(fv_[f][k]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<int> EdgeCollapser::edge_faces(int a, int b) const {
  std::vector<int> out;
  for (int f : vf_[a])
    if (fv_[f][0] == b || fv_[f][1] == b || fv_[f][2] == b) out.push_back(f);
  return out;
}

// Boundary, seam (the two faces disagree on a UV index or come from different
// charts of the input) or non-manifold. The chart test matters when two charts
// share UV indices at isolated points (MakeHuman's T-shirt has such flaps):
// an edge between two shared points would otherwise glue the charts.
bool EdgeCollapser::is_feature_edge(int a, int b) const {
  const std::vector<int> ef = edge_faces(a, b);
  if (ef.size() != 2) return true;
  const int f = ef[0], g = ef[1];
  return chart_[f] != chart_[g] || fuv_[f][corner(f, a)] != fuv_[g][corner(g, a)] ||
         fuv_[f][corner(f, b)] != fuv_[g][corner(g, b)];
}

std::vector<int> EdgeCollapser::feature_neighbours(int a) const {
  std::vector<int> out;
  for (int b : neighbours(a))
    if (is_feature_edge(a, b)) out.push_back(b);
  return out;
}

// Mean squared distance of v to the planes u and v stand for, plus the length term.
double EdgeCollapser::cost(int u, int v) const {
  Eigen::Vector4d p;
  p << pos_.row(v).transpose(), 1.0;
  const double area = std::max(quadric_area_[u] + quadric_area_[v], 1e-300);
  const double qem = std::max(0.0, p.dot((quadric_[u] + quadric_[v]) * p)) / area;
  return qem + opt_.length_weight * (pos_.row(u) - pos_.row(v)).squaredNorm();
}

void EdgeCollapser::push(int u, int v) {
  if (fixed_[u] || !vertex_alive_[u] || !vertex_alive_[v]) return;
  heap_.push({cost(u, v), u, v, stamp_[u], stamp_[v]});
}

void EdgeCollapser::push_around(int v) {
  std::vector<int> ring = neighbours(v);
  ring.push_back(v);
  for (int a : ring) ++stamp_[a];
  for (int a : ring)
    for (int b : neighbours(a)) {
      push(a, b);
      push(b, a);
    }
}

bool EdgeCollapser::plan(int u, int v, UvMap& map) const {
  if (!vertex_alive_[u] || !vertex_alive_[v] || fixed_[u]) return false;
  const std::vector<int> ef = edge_faces(u, v);
  if (ef.empty() || ef.size() > 2) return false;

  // A vertex on a boundary or seam may only slide along it, and only when it is
  // a regular point of that curve (exactly two feature edges; corners stay).
  const std::vector<int> feat = feature_neighbours(u);
  if (!feat.empty() && (feat.size() != 2 || !std::binary_search(feat.begin(), feat.end(), v))) return false;

  // Link condition: the only common neighbours are the edge's opposite corners.
  const std::vector<int> nu = neighbours(u), nv = neighbours(v);
  std::vector<int> common;
  std::set_intersection(nu.begin(), nu.end(), nv.begin(), nv.end(), std::back_inserter(common));
  if (common.size() != ef.size()) return false;
  if (nu.size() <= 2 || (nu.size() + nv.size() - common.size() - 2) < 3) return false;

  // The link condition misses a triangle that is its own seam/boundary loop (a
  // one-face UV chart, or the last face of one): deleting it would kill the chart.
  for (int f : ef) {
    const int w = fv_[f][0] != u && fv_[f][0] != v ? fv_[f][0] : fv_[f][1] != u && fv_[f][1] != v ? fv_[f][1] : fv_[f][2];
    if (is_feature_edge(u, v) && is_feature_edge(u, w) && is_feature_edge(v, w)) return false;
  }

  // Each UV wedge of u (its faces between two seam/boundary edges) takes the UV
  // v has in the face of the collapsed edge that lies in the same wedge. Walking
  // the fan, rather than matching UV indices, stays right when two charts share
  // a UV index at a point.
  const std::vector<int>& fan = vf_[u];
  map.assign(fan.size(), {-1, -1});
  std::vector<int> queue;
  for (std::size_t i = 0; i < fan.size(); ++i)
    if (std::find(ef.begin(), ef.end(), fan[i]) != ef.end()) {
      map[i] = {fan[i], fuv_[fan[i]][corner(fan[i], v)]};
      queue.push_back(static_cast<int>(i));
    }
  while (!queue.empty()) {
    const int i = queue.back();
    queue.pop_back();
    const int g = fan[i], k = corner(g, u);
    for (int x : {fv_[g][(k + 1) % 3], fv_[g][(k + 2) % 3]}) {
      if (is_feature_edge(u, x)) continue;
      for (std::size_t j = 0; j < fan.size(); ++j) {
        const int h = fan[j];
        if (h == g || (fv_[h][0] != x && fv_[h][1] != x && fv_[h][2] != x)) continue;
        if (map[j].first < 0) {
          map[j] = {h, map[i].second};
          queue.push_back(static_cast<int>(j));
        } else if (map[j].second != map[i].second) {
          return false;  // one wedge, two UVs for v: not a clean seam
        }
      }
    }
  }
  for (const auto& entry : map)
    if (entry.first < 0) return false;  // a wedge of u that does not touch the edge

  double worst_before = 1.0;
  for (int f : vf_[u])
    worst_before = std::min(worst_before, triangle_quality(pos_.row(fv_[f][0]), pos_.row(fv_[f][1]), pos_.row(fv_[f][2])));
  const double min_quality = std::min(opt_.min_quality, worst_before);

  for (int f : vf_[u]) {
    if (std::find(ef.begin(), ef.end(), f) != ef.end()) continue;
    const int k = corner(f, u);
    Eigen::Vector3d p[3];
    for (int i = 0; i < 3; ++i) p[i] = pos_.row(fv_[f][i]);
    const Eigen::Vector3d n_old = (p[1] - p[0]).cross(p[2] - p[0]);
    p[k] = pos_.row(v);
    const Eigen::Vector3d n_new = (p[1] - p[0]).cross(p[2] - p[0]);
    if (!(n_new.norm() > 0) || n_old.dot(n_new) < cos_max_turn_ * n_old.norm() * n_new.norm()) return false;
    if (triangle_quality(p[0], p[1], p[2]) < min_quality) return false;

    int tv = -1;
    for (const auto& [face, t] : map)
      if (face == f) tv = t;
    Eigen::Vector2d q[3];
    for (int i = 0; i < 3; ++i) q[i] = uv_.row(fuv_[f][i]);
    const double s_old = cross2(q[1] - q[0], q[2] - q[0]);
    q[k] = uv_.row(tv);
    const double s_new = cross2(q[1] - q[0], q[2] - q[0]);
    if (s_old != 0 && !(s_new * s_old > 0)) return false;  // flipped or degenerate in UV
  }
  return true;
}

void EdgeCollapser::collapse(int u, int v, const UvMap& map) {
  for (int f : vf_[u]) {
    const int k = corner(f, u);
    const bool on_edge = fv_[f][0] == v || fv_[f][1] == v || fv_[f][2] == v;
    if (on_edge) {
      face_alive_[f] = 0;
      for (int i = 0; i < 3; ++i) {
        const int w = fv_[f][i];
        if (w == u) continue;
        auto& list = vf_[w];
        list.erase(std::find(list.begin(), list.end(), f));
      }
      continue;
    }
    for (const auto& [face, t] : map)
      if (face == f) {
        fuv_[f][k] = t;
        break;
      }
    fv_[f][k] = v;
    vf_[v].push_back(f);
  }
  vf_[u].clear();
  vertex_alive_[u] = 0;
  --alive_count_;
  quadric_[v] += quadric_[u];
  quadric_area_[v] += quadric_area_[u];
  ++stamp_[u];
  push_around(v);
}

int EdgeCollapser::collapse_until(int target) {
  UvMap map;
  while (alive_count_ > target && !heap_.empty()) {
    const Candidate c = heap_.top();
    heap_.pop();
    if (c.su != stamp_[c.u] || c.sv != stamp_[c.v]) continue;
    if (!plan(c.u, c.v, map)) continue;
    collapse(c.u, c.v, map);
  }
  return alive_count_;
}

void EdgeCollapser::extract(Mesh& out, Eigen::VectorXi& vertex_index, Eigen::VectorXi& uv_index,
                            Eigen::VectorXi& face_chart) const {
  const int n = static_cast<int>(vertex_alive_.size());
  std::vector<int> new_vertex(n, -1), new_uv(uv_.rows(), -1);
  std::vector<int> keep_v, keep_uv;
  for (int a = 0; a < n; ++a)
    if (vertex_alive_[a]) {
      new_vertex[a] = static_cast<int>(keep_v.size());
      keep_v.push_back(a);
    }
  std::vector<char> uv_used(uv_.rows(), 0);
  int faces = 0;
  for (std::size_t f = 0; f < fv_.size(); ++f)
    if (face_alive_[f]) {
      ++faces;
      for (int t : fuv_[f]) uv_used[t] = 1;
    }
  for (int t = 0; t < uv_.rows(); ++t)
    if (uv_used[t]) {
      new_uv[t] = static_cast<int>(keep_uv.size());
      keep_uv.push_back(t);
    }
  vertex_index = Eigen::Map<const Eigen::VectorXi>(keep_v.data(), static_cast<Eigen::Index>(keep_v.size()));
  uv_index = Eigen::Map<const Eigen::VectorXi>(keep_uv.data(), static_cast<Eigen::Index>(keep_uv.size()));
  out.vertices.resize(keep_v.size(), 3);
  for (std::size_t i = 0; i < keep_v.size(); ++i) out.vertices.row(i) = pos_.row(keep_v[i]);
  out.uv.resize(keep_uv.size(), 2);
  for (std::size_t i = 0; i < keep_uv.size(); ++i) out.uv.row(i) = uv_.row(keep_uv[i]);
  out.faces.resize(faces, 3);
  out.uv_faces.resize(faces, 3);
  face_chart.resize(faces);
  int r = 0;
  for (std::size_t f = 0; f < fv_.size(); ++f) {
    if (!face_alive_[f]) continue;
    face_chart[r] = chart_[f];
    for (int k = 0; k < 3; ++k) {
      out.faces(r, k) = new_vertex[fv_[f][k]];
      out.uv_faces(r, k) = new_uv[fuv_[f][k]];
    }
    ++r;
  }
}

}  // namespace drape::geometry::detail
