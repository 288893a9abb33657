#include "height_field_nodes.hpp"

#include "exact_orientation.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace drape::geometry {
namespace {

// The border's edges as one cycle of vertices, or empty when they are not one
// cycle (two loops, a vertex where the border meets itself).
std::vector<int> single_loop(const std::vector<std::array<int, 2>>& border) {
  // Each border vertex with its two border neighbours, found by binary search.
  std::vector<std::pair<int, int>> ends;
  ends.reserve(2 * border.size());
  for (const auto& [a, b] : border) ends.emplace_back(a, b), ends.emplace_back(b, a);
  std::sort(ends.begin(), ends.end());
  for (std::size_t i = 0; i < ends.size(); i += 2)
    if (i + 1 >= ends.size() || ends[i].first != ends[i + 1].first || (i + 2 < ends.size() && ends[i + 2].first == ends[i].first))
      return {};
  const auto neighbours = [&](int v) {
    const auto it = std::lower_bound(ends.begin(), ends.end(), std::pair{v, -1});
    return std::pair{it->second, std::next(it)->second};
  };
  std::vector<int> loop{border.front()[0]};
  int previous = -1, current = border.front()[0];
  for (;;) {
    const auto [n0, n1] = neighbours(current);
    const int next = n0 != previous ? n0 : n1;
    if (next == loop.front()) break;
    if (loop.size() > border.size()) return {};  // (cannot happen with two neighbours each; a guard)
    loop.push_back(next);
    previous = current, current = next;
  }
  if (loop.size() != border.size()) return {};  // the walk closed before it met every border edge
  return loop;
}

// Collinear u, v, w with u and w on the same side of v: the loop turns back on itself at v.
bool folds_back(const Eigen::Vector2d& u, const Eigen::Vector2d& v, const Eigen::Vector2d& w) {
  // (The sign of a difference of doubles is exact, and so is that of their product here.)
  return (u.x() - v.x()) * (w.x() - v.x()) > 0 || (u.y() - v.y()) * (w.y() - v.y()) > 0;
}

}  // namespace

HeightFieldNodes::HeightFieldNodes(const TriangleBvh& tree, const Eigen::MatrixX3i& faces,
                                   const std::vector<std::array<int, 2>>& edges,
                                   const std::vector<std::vector<int>>& vertex_faces)
    : tree_(tree), faces_(faces) {
  const int nodes = tree.num_nodes();
  loop_.resize(static_cast<std::size_t>(nodes));
  node_mask_.assign(static_cast<std::size_t>(nodes), 0);
  top_.assign(static_cast<std::size_t>(nodes), -1);

  // Each node's boundary loop. Its faces' sides, directed as the faces go
  // round: a side met twice is inside the node and must be met once each
  // way (the faces agree on which way is up, so that "every face turns the
  // same way" means the sheet does not fold over); a side met once is on
  // the boundary; a side of three faces is no sheet.
  struct Side {
    int lo, hi;
    bool forward;  // the face goes lo -> hi
    bool operator<(const Side& o) const { return std::pair{lo, hi} < std::pair{o.lo, o.hi}; }
  };
  std::vector<Side> sides;
  std::vector<std::array<int, 2>> border;
  for (int i = 0; i < nodes; ++i) {
    const TriangleBvh::Span& span = tree.span(i);
    if (span.last - span.first < 2) continue;  // one face: its own edges share its corners
    sides.clear();
    for (int slot = span.first; slot < span.last; ++slot) {
      const int f = tree.face_at(slot);
      for (int k = 0; k < 3; ++k) {
        const int a = faces(f, k), b = faces(f, (k + 1) % 3);
        sides.push_back({std::min(a, b), std::max(a, b), a < b});
      }
    }
    std::sort(sides.begin(), sides.end());
    border.clear();
    bool sheet = true;
    for (std::size_t j = 0; j < sides.size() && sheet;) {
      std::size_t k = j;
      while (k < sides.size() && sides[k].lo == sides[j].lo && sides[k].hi == sides[j].hi) ++k;
      if (k - j == 1) border.push_back({sides[j].lo, sides[j].hi});
      else sheet = k - j == 2 && sides[j].forward != sides[j + 1].forward;
      j = k;
    }
    if (sheet && border.size() >= 3) loop_[static_cast<std::size_t>(i)] = single_loop(border);
  }

  // The smallest node holding every face at each edge: the lowest common
  // ancestor of the leaves of its faces.
  std::vector<int> depth(static_cast<std::size_t>(nodes), 0), leaf_of_slot(static_cast<std::size_t>(faces.rows()), 0);
  for (int i = 1; i < nodes; ++i) depth[static_cast<std::size_t>(i)] = depth[static_cast<std::size_t>(tree.span(i).parent)] + 1;
  for (int i = 0; i < nodes; ++i)
    if (tree.is_leaf(i))
      for (int slot = tree.span(i).first; slot < tree.span(i).last; ++slot) leaf_of_slot[static_cast<std::size_t>(slot)] = i;
  const auto common = [&](int a, int b) {
    while (a != b) {
      if (depth[static_cast<std::size_t>(a)] < depth[static_cast<std::size_t>(b)]) std::swap(a, b);
      a = tree.span(a).parent;
    }
    return a;
  };
  edge_node_.assign(edges.size(), -1);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    int node = -1;
    for (const int f : vertex_faces[static_cast<std::size_t>(a)]) {
      if (faces(f, 0) != b && faces(f, 1) != b && faces(f, 2) != b) continue;
      const int leaf = leaf_of_slot[static_cast<std::size_t>(tree.slot_of(f))];
      node = node < 0 ? leaf : common(node, leaf);
    }
    edge_node_[e] = node;
  }
}

void HeightFieldNodes::certify(const Eigen::MatrixX3d& x) {
  const int nodes = tree_.num_nodes();
  certified_ = 0;
  if (nodes == 0) return;
  // Each face's directions: bit 2k when its projection along axis k (the
  // other two coordinates, in cyclic order) turns counter-clockwise, i.e.
  // its normal's k-th component is positive; bit 2k + 1 when negative.
  const auto face_mask = [&](int f) {
    unsigned mask = 0;
    for (int k = 0; k < 3; ++k) {
      const int u = (k + 1) % 3, w = (k + 2) % 3;
      const Eigen::Vector2d a(x(faces_(f, 0), u), x(faces_(f, 0), w)), b(x(faces_(f, 1), u), x(faces_(f, 1), w)),
          c(x(faces_(f, 2), u), x(faces_(f, 2), w));
      const int turn = exact::orient2d(a, b, c);
      mask |= turn > 0 ? 1u << (2 * k) : turn < 0 ? 1u << (2 * k + 1) : 0u;
    }
    return static_cast<unsigned char>(mask);
  };
  // A node's directions are those all its faces share. Children come after
  // their parent, so a backward sweep has folded every child in before the
  // parent passes its own on.
  std::fill(node_mask_.begin(), node_mask_.end(), static_cast<unsigned char>(0x3f));
  for (int i = nodes - 1; i >= 0; --i) {
    const TriangleBvh::Span& span = tree_.span(i);
    if (tree_.is_leaf(i))
      for (int slot = span.first; slot < span.last; ++slot) node_mask_[static_cast<std::size_t>(i)] &= face_mask(tree_.face_at(slot));
    if (span.parent >= 0) node_mask_[static_cast<std::size_t>(span.parent)] &= node_mask_[static_cast<std::size_t>(i)];
  }
  // Largest first: a node under a height field is one too, and is not tried.
  for (int i = 0; i < nodes; ++i) {
    const int parent = tree_.span(i).parent;
    int& top = top_[static_cast<std::size_t>(i)];
    if (parent >= 0 && top_[static_cast<std::size_t>(parent)] >= 0) {
      top = top_[static_cast<std::size_t>(parent)];
      continue;
    }
    top = -1;
    const unsigned mask = node_mask_[static_cast<std::size_t>(i)];
    const std::vector<int>& loop = loop_[static_cast<std::size_t>(i)];
    if (mask == 0 || loop.empty()) continue;
    for (int k = 0; k < 3 && top < 0; ++k)
      if ((mask >> (2 * k) & 3u) != 0 && loop_is_simple(loop, k, x)) top = i, ++certified_;
  }
}

bool HeightFieldNodes::loop_is_simple(const std::vector<int>& loop, int axis, const Eigen::MatrixX3d& x) {
  const auto m = loop.size();
  projected_.resize(m);
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  for (std::size_t i = 0; i < m; ++i) projected_[i] = {x(loop[i], u), x(loop[i], w)};
  const auto& p = projected_;
  const auto at = [&](std::size_t i) -> const Eigen::Vector2d& { return p[i % m]; };
  // Neighbouring segments meet only at their common end: neither has zero
  // length, and the loop does not turn straight back.
  for (std::size_t i = 0; i < m; ++i) {
    if (at(i) == at(i + 1)) return false;
    if (exact::orient2d(at(i), at(i + 1), at(i + 2)) == 0 && folds_back(at(i), at(i + 1), at(i + 2))) return false;
  }
  // Any other two do not meet at all (their boxes first).
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::Vector2d &a = at(i), &b = at(i + 1);
    const Eigen::Vector2d lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    for (std::size_t j = i + 2; j < m; ++j) {
      if (i == 0 && j + 1 == m) continue;  // the last segment is the first's neighbour
      const Eigen::Vector2d &c = at(j), &d = at(j + 1);
      if (std::max(c.x(), d.x()) < lo.x() || std::min(c.x(), d.x()) > hi.x() || std::max(c.y(), d.y()) < lo.y() ||
          std::min(c.y(), d.y()) > hi.y())
        continue;
      if (exact::segments_meet_2d(a, b, c, d)) return false;
    }
  }
  return true;
}

}  // namespace drape::geometry
