#include "triangle_bvh.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace drape::geometry {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The next float towards -infinity / +infinity, inline (std::nextafter is a
// library call, and refitting a body's boxes makes ~100,000 of these a sample).
float float_below(float f) {
  if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
  if (!std::isfinite(f)) return f < 0 ? f : std::numeric_limits<float>::max();
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  u = f > 0 ? u - 1 : u + 1;
  std::memcpy(&f, &u, sizeof u);
  return f;
}
float float_above(float f) { return -float_below(-f); }

// Float bounds that contain the double value: a box rounded outwards only grows.
float round_down(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? float_below(f) : f;
}
float round_up(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? float_above(f) : f;
}

// The float threshold a box's float distance must exceed to be passed over.
// The margin (1e-5 relative) is far above the few float roundings of the
// distance itself (~1e-7 relative), so a box is only skipped when it is
// farther than `best` in exact arithmetic.
float prune_bound(double best) {
  if (!(best < kInfinity)) return std::numeric_limits<float>::infinity();
  return round_up(best * (1 + 1e-5));
}

}  // namespace

TriangleBvh::TriangleBvh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) : faces_(faces) {
  const int nf = static_cast<int>(faces.rows());
  std::vector<Eigen::Vector3d> centroids(nf);
  for (int f = 0; f < nf; ++f)
    centroids[f] = (vertices.row(faces(f, 0)) + vertices.row(faces(f, 1)) + vertices.row(faces(f, 2))).transpose() / 3;
  std::vector<int> order(nf);
  for (int f = 0; f < nf; ++f) order[f] = f;
  nodes_.reserve(static_cast<std::size_t>(nf / 2 + 1));
  spans_.reserve(static_cast<std::size_t>(nf / 2 + 1));
  if (nf > 0) build(order, centroids, 0, nf, 0, -1);
  face_of_ = std::move(order);
  slot_of_face_.assign(nf, -1);
  for (int t = 0; t < nf; ++t) slot_of_face_[face_of_[t]] = t;
  refit(vertices);
}

int TriangleBvh::build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& centroids, int begin, int end,
                       int depth, int parent) {
  assert(depth < kMaxDepth);
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  spans_.push_back({begin, end, parent});
  if (end - begin <= kWidth) {
    Node& leaf = nodes_[index];
    leaf.leaf = true;
    leaf.count = end - begin;
    for (int s = 0; s < leaf.count; ++s) leaf.child[s] = begin + s;
    return index;
  }
  // Median on the longest centroid axis; splitting by count keeps the tree balanced.
  auto split = [&](int b, int e) {
    Eigen::Vector3d lo = centroids[order[b]], hi = lo;
    for (int i = b + 1; i < e; ++i) lo = lo.cwiseMin(centroids[order[i]]), hi = hi.cwiseMax(centroids[order[i]]);
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const int mid = b + (e - b) / 2;
    std::nth_element(order.begin() + b, order.begin() + mid, order.begin() + e,
                     [&](int x, int y) { return centroids[x][axis] < centroids[y][axis]; });
    return mid;
  };
  // Two levels of the binary split give the four children (each non-empty: end - begin >= 5).
  const int mid = split(begin, end);
  const int bounds[kWidth + 1] = {begin, split(begin, mid), mid, split(mid, end), end};
  for (int s = 0; s < kWidth; ++s) {
    const int child = build(order, centroids, bounds[s], bounds[s + 1], depth + 1, index);
    nodes_[index].child[s] = child;  // by index: building the child may have moved the vector
  }
  nodes_[index].count = kWidth;
  return index;
}

void TriangleBvh::gather_corners(const Eigen::MatrixX3d& vertices) {
  corners_.resize(3 * face_of_.size());
  for (std::size_t t = 0; t < face_of_.size(); ++t)
    for (int k = 0; k < 3; ++k) corners_[3 * t + k] = vertices.row(faces_(face_of_[t], k)).transpose();
}

void TriangleBvh::refit(const Eigen::MatrixX3d& vertices) {
  gather_corners(vertices);
  // Each vertex rounded outwards once: rounding is monotonic, so the float
  // bounds of a box are the min / max of its corners' rounded coordinates,
  // the same bits as rounding the box's exact double bounds, and every box
  // above the leaves is the min / max of its child's four lanes (an empty
  // lane is +inf / -inf and changes nothing). A vertex is rounded once
  // instead of once for every box it is a corner of, on all levels.
  const auto nv = static_cast<std::size_t>(vertices.rows());
  vertex_lo_.resize(3 * nv);
  vertex_hi_.resize(3 * nv);
  for (std::size_t v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = vertices(static_cast<Eigen::Index>(v), k);
      vertex_lo_[3 * v + static_cast<std::size_t>(k)] = round_down(x);
      vertex_hi_[3 * v + static_cast<std::size_t>(k)] = round_up(x);
    }
  constexpr float kEmpty = std::numeric_limits<float>::infinity();
  // Children come after their parent, so a backward sweep sees them first.
  for (int i = num_nodes() - 1; i >= 0; --i) {
    Node& n = nodes_[static_cast<std::size_t>(i)];
    for (int s = 0; s < kWidth; ++s) {
      float lo[3] = {kEmpty, kEmpty, kEmpty}, hi[3] = {-kEmpty, -kEmpty, -kEmpty};  // an empty box: every gap is infinite
      if (s < n.count && n.leaf) {
        const int face = face_of_[static_cast<std::size_t>(n.child[s])];
        for (int c = 0; c < 3; ++c) {
          const std::size_t v = 3 * static_cast<std::size_t>(faces_(face, c));
          for (int k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], vertex_lo_[v + static_cast<std::size_t>(k)]),
            hi[k] = std::max(hi[k], vertex_hi_[v + static_cast<std::size_t>(k)]);
        }
      } else if (s < n.count) {
        const Node& child = nodes_[static_cast<std::size_t>(n.child[s])];
        for (int k = 0; k < 3; ++k) {
          const Lanes l = child.lo[k], h = child.hi[k];
          lo[k] = std::min(std::min(l[0], l[1]), std::min(l[2], l[3]));
          hi[k] = std::max(std::max(h[0], h[1]), std::max(h[2], h[3]));
        }
      }
      for (int k = 0; k < 3; ++k) n.lo[k][s] = lo[k], n.hi[k][s] = hi[k];
    }
  }
}

TriangleBvh::FloatQuery::FloatQuery(const Eigen::Vector3d& p) {
  for (int k = 0; k < 3; ++k) {
    const float pk = static_cast<float>(p[k]);
    const float ek = round_up(std::abs(p[k] - static_cast<double>(pk)));
    point[k] = Lanes{pk, pk, pk, pk};
    moved[k] = Lanes{ek, ek, ek, ek};
  }
}

TriangleBvh::Lanes TriangleBvh::FloatQuery::distance2(const Node& n) const {
  const Lanes zero = {0, 0, 0, 0};
  Lanes d2 = zero;
  for (int k = 0; k < 3; ++k) {
    const Lanes below = n.lo[k] - point[k], above = point[k] - n.hi[k];
    Lanes gap = (below > above ? below : above) - moved[k];
    gap = gap > zero ? gap : zero;
    d2 += gap * gap;
  }
  return d2;
}

int TriangleBvh::nearest(const Eigen::Vector3d& p, double max_squared_distance, TrianglePoint& hit,
                         const int* face_labels, int excluded, int hint) const {
  if (nodes_.empty() || !p.allFinite()) return -1;
  double best = max_squared_distance;
  int best_triangle = -1;
  if (hint >= 0 && hint < static_cast<int>(slot_of_face_.size()) && !(face_labels && face_labels[hint] == excluded)) {
    const int t = slot_of_face_[hint];
    const TrianglePoint q = closest_point_on_triangle(p, corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]);
    const double d2 = (q.point - p).squaredNorm();
    if (d2 < best) best = d2, best_triangle = t, hit = q;
  }
  // Of faces at the same computed distance the lowest index wins, and a box is
  // passed over only when it is provably farther than the best: the answer is
  // the argmin of (distance, face) over all faces, whatever the hint and the
  // order of the search (so a training step that warm-starts from other faces,
  // or a resumed run that has none, finds the same bits).
  auto better = [&](double d2, int t) {
    return d2 < best || (best_triangle >= 0 && d2 == best && face_of_[t] < face_of_[best_triangle]);
  };
  float bound = prune_bound(best);

  const FloatQuery query(p);
  auto distance2 = [&](const Node& n) { return query.distance2(n); };

  struct Pending {
    int node;
    float distance2;
  };
  Pending stack[(kWidth - 1) * kMaxDepth + 1];  // a level pushes at most three siblings
  int top = 0;
  int node = 0;
  for (;;) {
    const Node& n = nodes_[static_cast<std::size_t>(node)];
    const Lanes d2 = distance2(n);
    if (n.leaf) {
      for (int s = 0; s < n.count; ++s) {
        const int t = n.child[s];
        // The triangle's own box first: no triangle is nearer than its box.
        if (d2[s] > bound || t == best_triangle || (face_labels && face_labels[face_of_[t]] == excluded)) continue;
        const TrianglePoint q = closest_point_on_triangle(p, corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]);
        const double dq = (q.point - p).squaredNorm();
        if (better(dq, t)) best = dq, best_triangle = t, hit = q, bound = prune_bound(best);
      }
    } else {
      // The children that can still hold something closer: the nearest is
      // visited next (it tightens `best` and prunes the others), the rest wait
      // on the stack with their distances. Unused slots have infinite boxes.
      unsigned open = 0;
      for (int s = 0; s < kWidth; ++s) open |= static_cast<unsigned>(d2[s] <= bound) << s;
      open &= (1u << n.count) - 1;
      if (open != 0) {
        int nearest_slot = __builtin_ctz(open);
        for (unsigned rest = open & (open - 1); rest != 0; rest &= rest - 1) {
          const int s = __builtin_ctz(rest);
          if (d2[s] < d2[nearest_slot]) {
            stack[top++] = {n.child[nearest_slot], d2[nearest_slot]};
            nearest_slot = s;
          } else {
            stack[top++] = {n.child[s], d2[s]};
          }
        }
        node = n.child[nearest_slot];
        continue;
      }
    }
    // Pop the next subtree that can still hold something closer.
    for (;;) {
      if (top == 0) return best_triangle < 0 ? -1 : face_of_[best_triangle];
      const Pending next = stack[--top];
      if (next.distance2 <= bound) {
        node = next.node;
        break;
      }
    }
  }
}

void TriangleBvh::within(const Eigen::Vector3d& p, double max_squared_distance,
                         std::vector<std::pair<double, int>>& out) const {
  out.clear();
  if (nodes_.empty() || !p.allFinite() || !(max_squared_distance >= 0)) return;
  const float bound = prune_bound(max_squared_distance);
  const FloatQuery query(p);
  int stack[(kWidth - 1) * kMaxDepth + kWidth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    const Lanes d2 = query.distance2(n);
    for (int s = 0; s < n.count; ++s) {
      if (d2[s] > bound) continue;
      if (!n.leaf) {
        stack[top++] = n.child[s];
        continue;
      }
      const int t = n.child[s];
      const TrianglePoint q = closest_point_on_triangle(p, corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]);
      const double dq = (q.point - p).squaredNorm();
      if (dq <= max_squared_distance) out.emplace_back(dq, face_of_[t]);
    }
  }
}

void TriangleBvh::overlapping(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<int>& out,
                              int skip_node) const {
  if (nodes_.empty() || skip_node == 0 || !lo.allFinite() || !hi.allFinite()) return;
  Lanes query_lo[3], query_hi[3];
  for (int k = 0; k < 3; ++k) {
    const float l = round_down(lo[k]), h = round_up(hi[k]);
    query_lo[k] = Lanes{l, l, l, l};
    query_hi[k] = Lanes{h, h, h, h};
  }
  int stack[(kWidth - 1) * kMaxDepth + kWidth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    auto meets = (n.lo[0] <= query_hi[0]) & (n.hi[0] >= query_lo[0]);  // lanes of -1 (true) and 0
    for (int k = 1; k < 3; ++k) meets &= (n.lo[k] <= query_hi[k]) & (n.hi[k] >= query_lo[k]);
    for (int s = 0; s < n.count; ++s) {
      if (!meets[s]) continue;
      if (n.leaf) out.push_back(face_of_[static_cast<std::size_t>(n.child[s])]);
      else if (n.child[s] != skip_node) stack[top++] = n.child[s];
    }
  }
}

void TriangleBvh::along_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::vector<int>& out) const {
  if (nodes_.empty() || !p.allFinite() || !q.allFinite()) return;
  // The slab test in float on boxes grown by a slack far above its
  // roundings (each ~1e-7 of the coordinates): where the segment enters and
  // leaves each box along each axis, as parameters t of p + t (q - p). An
  // axis the segment hardly moves along gets a tiny step of its sign, so
  // the parameters stay finite: a box that does not span p there is then
  // entered or left at |t| >> 1.
  const double scale = std::max({1.0, p.cwiseAbs().maxCoeff(), q.cwiseAbs().maxCoeff()});
  const auto slack = static_cast<float>(1e-5 * scale);
  Lanes origin[3], inverse[3];
  for (int k = 0; k < 3; ++k) {
    double d = q[k] - p[k];
    if (std::abs(d) < 1e-12) d = std::copysign(1e-12, d);
    const auto o = static_cast<float>(p[k]), i = static_cast<float>(1.0 / d);
    origin[k] = Lanes{o, o, o, o};
    inverse[k] = Lanes{i, i, i, i};
  }
  const Lanes zero{0, 0, 0, 0}, one{1, 1, 1, 1};
  int stack[(kWidth - 1) * kMaxDepth + kWidth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    Lanes enter = zero, leave = one;
    auto filled = n.lo[0] <= n.hi[0];  // (an empty slot's box is lo = +inf, hi = -inf)
    for (int k = 0; k < 3; ++k) {
      const Lanes t1 = (n.lo[k] - slack - origin[k]) * inverse[k], t2 = (n.hi[k] + slack - origin[k]) * inverse[k];
      const Lanes nearer = t1 < t2 ? t1 : t2, farther = t1 < t2 ? t2 : t1;
      enter = enter > nearer ? enter : nearer;
      leave = leave < farther ? leave : farther;
    }
    const auto meets = filled & (enter <= leave);
    for (int s = 0; s < n.count; ++s) {
      if (!meets[s]) continue;
      if (n.leaf) out.push_back(face_of_[static_cast<std::size_t>(n.child[s])]);
      else stack[top++] = n.child[s];
    }
  }
}

TrianglePoint TriangleBvh::face_point(const Eigen::Vector3d& p, int face) const {
  const int t = slot_of_face_.at(static_cast<std::size_t>(face));
  return closest_point_on_triangle(p, corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]);
}

}  // namespace drape::geometry
