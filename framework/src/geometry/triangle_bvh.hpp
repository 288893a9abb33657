#pragma once
// A bounding-volume hierarchy over the triangles of a mesh for closest-point
// queries (internal to the geometry layer; see drape/geometry/closest_point.hpp).
//
// Median split on the longest centroid axis, four triangles per leaf, nodes in
// depth-first order (left child next to its parent) so that refitting is one
// backward sweep. For nearest-point queries a median split is as good as SAH
// (SAH optimises ray hits, not distance bounds) and keeps the tree balanced,
// so the traversal stack has a fixed bound.
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <vector>

namespace drape::geometry {

class TriangleBvh {
 public:
  TriangleBvh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

  // Same faces, new positions: boxes grow or shrink, the tree stays.
  void refit(const Eigen::MatrixX3d& vertices);

  // The closest triangle to p strictly within sqrt(max_squared_distance);
  // returns -1 (and leaves `hit` alone) when there is none. With face_labels
  // (one per face), faces labelled `excluded` are passed over. A hint (a face
  // expected near p, e.g. the answer for a nearby point) is tested first: its
  // distance bounds the search, which then opens only the boxes closer than
  // it. The answer does not depend on the hint: of faces at the same computed
  // distance the lowest-numbered wins.
  int nearest(const Eigen::Vector3d& p, double max_squared_distance, TrianglePoint& hit,
              const int* face_labels = nullptr, int excluded = 0, int hint = -1) const;

  int num_nodes() const { return static_cast<int>(nodes_.size()); }

 private:
  struct Node {
    Eigen::Vector3d lo, hi;
    int first = 0;  // leaf: first triangle in leaf order; inner: right child (left is this + 1)
    int count = 0;  // triangles in the leaf; 0 for an inner node
  };
  static constexpr int kLeafSize = 4;
  static constexpr int kMaxDepth = 64;

  int build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& centroids, int begin, int end, int depth);
  void gather_corners(const Eigen::MatrixX3d& vertices);
  // Inline: it is most of a query's work, and an exported member would go through the PLT.
  static double box_distance2(const Node& n, const Eigen::Vector3d& p) {
    const double dx = std::max({n.lo.x() - p.x(), p.x() - n.hi.x(), 0.0});
    const double dy = std::max({n.lo.y() - p.y(), p.y() - n.hi.y(), 0.0});
    const double dz = std::max({n.lo.z() - p.z(), p.z() - n.hi.z(), 0.0});
    return dx * dx + dy * dy + dz * dz;
  }

  Eigen::MatrixX3i faces_;
  std::vector<Node> nodes_;
  std::vector<int> face_of_;                // face id of each triangle in leaf order
  std::vector<int> slot_of_face_;           // its inverse: the leaf-order slot of each face
  std::vector<Eigen::Vector3d> corners_;    // 3 per triangle in leaf order (contiguous for the cache)
};

}  // namespace drape::geometry
