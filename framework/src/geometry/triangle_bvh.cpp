#include "triangle_bvh.hpp"

#include <algorithm>
#include <cassert>

namespace drape::geometry {

TriangleBvh::TriangleBvh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) : faces_(faces) {
  const int nf = static_cast<int>(faces.rows());
  std::vector<Eigen::Vector3d> centroids(nf);
  for (int f = 0; f < nf; ++f)
    centroids[f] = (vertices.row(faces(f, 0)) + vertices.row(faces(f, 1)) + vertices.row(faces(f, 2))).transpose() / 3;
  std::vector<int> order(nf);
  for (int f = 0; f < nf; ++f) order[f] = f;
  nodes_.reserve(2 * static_cast<std::size_t>(nf / kLeafSize + 1));
  if (nf > 0) build(order, centroids, 0, nf, 0);
  face_of_ = std::move(order);
  slot_of_face_.assign(nf, -1);
  for (int t = 0; t < nf; ++t) slot_of_face_[face_of_[t]] = t;
  refit(vertices);
}

int TriangleBvh::build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& centroids, int begin, int end,
                       int depth) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  Eigen::Vector3d lo = centroids[order[begin]], hi = lo;
  for (int i = begin + 1; i < end; ++i) lo = lo.cwiseMin(centroids[order[i]]), hi = hi.cwiseMax(centroids[order[i]]);
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
  // Splitting by count keeps the depth at log2(F / kLeafSize) + 1 whatever the geometry.
  assert(depth < kMaxDepth);
  build(order, centroids, begin, mid, depth + 1);
  const int right = build(order, centroids, mid, end, depth + 1);
  nodes_[index].first = right;
  return index;
}

void TriangleBvh::gather_corners(const Eigen::MatrixX3d& vertices) {
  corners_.resize(3 * face_of_.size());
  for (std::size_t t = 0; t < face_of_.size(); ++t)
    for (int k = 0; k < 3; ++k) corners_[3 * t + k] = vertices.row(faces_(face_of_[t], k)).transpose();
}

void TriangleBvh::refit(const Eigen::MatrixX3d& vertices) {
  gather_corners(vertices);
  // Children come after their parent, so a backward sweep sees them first.
  for (int i = num_nodes() - 1; i >= 0; --i) {
    Node& n = nodes_[i];
    if (n.count > 0) {
      n.lo = n.hi = corners_[3 * n.first];
      for (int c = 3 * n.first + 1; c < 3 * (n.first + n.count); ++c)
        n.lo = n.lo.cwiseMin(corners_[c]), n.hi = n.hi.cwiseMax(corners_[c]);
    } else {
      const Node& l = nodes_[i + 1];
      const Node& r = nodes_[n.first];
      n.lo = l.lo.cwiseMin(r.lo);
      n.hi = l.hi.cwiseMax(r.hi);
    }
  }
}

int TriangleBvh::nearest(const Eigen::Vector3d& p, double max_squared_distance, TrianglePoint& hit,
                         const int* face_labels, int excluded, int hint) const {
  if (nodes_.empty()) return -1;
  double best = max_squared_distance;
  int best_triangle = -1;
  if (hint >= 0 && hint < static_cast<int>(slot_of_face_.size()) && !(face_labels && face_labels[hint] == excluded)) {
    const int t = slot_of_face_[hint];
    const TrianglePoint q = closest_point_on_triangle(p, corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]);
    const double d2 = (q.point - p).squaredNorm();
    if (d2 < best) best = d2, best_triangle = t, hit = q;
  }
  // Of faces at the same computed distance the lowest index wins, and a box is
  // passed over only when it is farther than the best by more than rounding:
  // the answer is the argmin of (distance, face) over all faces, whatever the
  // hint and the order of the search (so a training step that warm-starts from
  // other faces, or a resumed run that has none, finds the same bits).
  auto farther = [&best](double d2) { return d2 > best * (1 + 1e-12); };
  auto better = [&](double d2, int t) {
    return d2 < best || (best_triangle >= 0 && d2 == best && face_of_[t] < face_of_[best_triangle]);
  };
  struct Pending {
    int node;
    double distance2;
  };
  Pending stack[kMaxDepth];
  int top = 0;
  int node = 0;
  if (farther(box_distance2(nodes_[0], p))) return best_triangle < 0 ? -1 : face_of_[best_triangle];
  for (;;) {
    const Node& n = nodes_[node];
    if (n.count > 0) {
      for (int t = n.first; t < n.first + n.count; ++t) {
        if (t == best_triangle || (face_labels && face_labels[face_of_[t]] == excluded)) continue;
        // The triangle's own box first: no triangle is nearer than its box, and
        // the box test costs a fraction of the exact one.
        const Eigen::Vector3d &a = corners_[3 * t], &b = corners_[3 * t + 1], &c = corners_[3 * t + 2];
        double box = 0;
        for (int k = 0; k < 3; ++k) {
          const double lo = std::min({a[k], b[k], c[k]}), hi = std::max({a[k], b[k], c[k]});
          const double e = std::max({lo - p[k], p[k] - hi, 0.0});
          box += e * e;
        }
        if (farther(box)) continue;
        const TrianglePoint q = closest_point_on_triangle(p, a, b, c);
        const double d2 = (q.point - p).squaredNorm();
        if (better(d2, t)) best = d2, best_triangle = t, hit = q;
      }
    } else {
      // Visit the nearer child first: it tightens `best` and prunes the other.
      int near = node + 1, far = n.first;
      double dn = box_distance2(nodes_[near], p), df = box_distance2(nodes_[far], p);
      if (df < dn) std::swap(near, far), std::swap(dn, df);
      if (!farther(df)) stack[top++] = {far, df};
      if (!farther(dn)) {
        node = near;
        continue;
      }
    }
    // Pop the next subtree that can still hold something closer.
    for (;;) {
      if (top == 0) return best_triangle < 0 ? -1 : face_of_[best_triangle];
      const Pending next = stack[--top];
      if (!farther(next.distance2)) {
        node = next.node;
        break;
      }
    }
  }
}

}  // namespace drape::geometry
