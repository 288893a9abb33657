#pragma once
// A bounding-volume hierarchy over the triangles of a mesh for closest-point
// queries (internal to the geometry layer; see drape/geometry/closest_point.hpp).
//
// Four children a node, their boxes stored side by side in float so that one
// vector instruction measures the distance from a point to all four (GCC's
// vector extensions: SSE on x86-64, NEON on ARM, no intrinsics). A binary tree
// with double boxes tested ~170 boxes one by one for a point 1 cm from a
// 13,000-triangle body; the cost of a query was the descent, not the exact
// triangle tests. The float boxes are rounded outwards and the query's own
// rounding is subtracted from every gap, so a box is passed over only when it
// is provably farther than the best triangle: the answer is the same argmin of
// (distance, face) as an exhaustive search in double.
//
// Built by count (median splits on the longest centroid axis, twice a level),
// so the depth is log4(F) + 1 whatever the geometry and the traversal stack has
// a fixed bound; leaves hold up to four triangles, each with its own box.
// Nodes are in depth-first order (children after their parent), so refitting
// is one backward sweep.
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <array>
#include <utility>
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

  // Every face whose computed squared distance to p is at most
  // max_squared_distance, as (squared distance, face) pairs in no set order;
  // the distances are the bits nearest() computes for the same faces.
  void within(const Eigen::Vector3d& p, double max_squared_distance, std::vector<std::pair<double, int>>& out) const;

  // Appends to `out` every face whose box overlaps the closed box [lo, hi],
  // and a few whose box only touches it within float rounding (the boxes are
  // rounded outwards): the broad phase of an exact test that follows.
  // With skip_node, that node's subtree is passed over (a part of the mesh
  // known to hold nothing the caller looks for: height_field_nodes.hpp).
  void overlapping(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<int>& out, int skip_node = -1) const;

  // Appends to `out` every face whose box the segment [p, q] meets, and a
  // few it only passes within a rounding slack of: the broad phase of an
  // exact segment test. (The box of a slanted segment holds faces the
  // segment never nears: a sweep of the coarse shirt's 2,899 edges over a
  // thin man of the human rig, with the exact tests after, took 655 us
  // with overlapping() of each edge's box and 545 us with this.)
  void along_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::vector<int>& out) const;

  // The closest point of one face to p, computed as nearest() computes it.
  TrianglePoint face_point(const Eigen::Vector3d& p, int face) const;

  int num_nodes() const { return static_cast<int>(nodes_.size()); }

  // The hierarchy's shape, for a pass over its nodes: node 0 is the root,
  // children come after their parent, and the triangles under a node are the
  // leaf-order slots [first, last), face_at(slot) the face in each.
  struct Span {
    int first, last, parent;  // parent -1 at the root
  };
  const Span& span(int node) const { return spans_[static_cast<std::size_t>(node)]; }
  bool is_leaf(int node) const { return nodes_[static_cast<std::size_t>(node)].leaf; }
  int face_at(int slot) const { return face_of_[static_cast<std::size_t>(slot)]; }
  int slot_of(int face) const { return slot_of_face_[static_cast<std::size_t>(face)]; }

 private:
  static constexpr int kWidth = 4;
  static constexpr int kMaxDepth = 48;
  typedef float Lanes __attribute__((vector_size(4 * sizeof(float))));

  struct Node {
    Lanes lo[3], hi[3];   // per axis, the four children's boxes (an unused slot is empty: lo > hi)
    int child[kWidth];    // inner: node index; leaf: triangle in leaf order
    int count = 0;        // slots in use
    bool leaf = false;
  };
  // A query point in float for the box tests, and how far rounding moved it
  // along each axis (rounded up): subtracted from every gap, so a float gap
  // never exceeds the exact one.
  struct FloatQuery {
    explicit FloatQuery(const Eigen::Vector3d& p);
    // Lower bounds of the squared distances to the node's four boxes.
    Lanes distance2(const Node& n) const;
    Lanes point[3], moved[3];
  };


  int build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& centroids, int begin, int end, int depth, int parent);
  void gather_corners(const Eigen::MatrixX3d& vertices);

  Eigen::MatrixX3i faces_;
  std::vector<Node> nodes_;
  std::vector<Span> spans_;                 // each node's slots and parent
  std::vector<float> vertex_lo_, vertex_hi_;  // each vertex's coordinates rounded down / up (refit's scratch)
  std::vector<int> face_of_;                // face id of each triangle in leaf order
  std::vector<int> slot_of_face_;           // its inverse: the leaf-order slot of each face
  std::vector<Eigen::Vector3d> corners_;    // 3 per triangle in leaf order (contiguous for the cache)
};

}  // namespace drape::geometry
