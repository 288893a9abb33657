#pragma once
// The nodes of a mesh's face hierarchy that cannot hold a crossing of the
// mesh with itself, found again for each new set of positions (internal to
// the geometry layer; used by untangle.cpp).
//
// Normal-cone culling (Volino and Magnenat-Thalmann, "Efficient self-collision
// detection on smoothly discretized surface animations using geometrical
// shape regularity", 1994), made exact. A node is a height field along a
// coordinate axis when, seen along it,
//   - every face of the node turns the same way (its projection has a
//     non-zero area of one sign: exact 2D orientation), and
//   - the node's boundary is one loop of edges whose projection is a simple
//     closed curve (no two of its segments meet but neighbours at their
//     common end: exact 2D segment tests).
// Then the projection covers each point of the plane at most once: its degree
// at a point is the boundary's winding number there (0 or 1 for a simple
// curve), and every face adds one where it covers. An edge through a face of
// the node would cover the points near the crossing twice (the face and a
// face at the edge), so a node that is a height field holds no crossing
// between its own edges and faces, and neither does any part of it. (Only a
// touch that both projections see on their borders, an exact coincidence of
// a vertex with an edge, could be passed over.)
//
// The axis is one of the coordinate axes so that a projection drops a
// coordinate and every sign is exact. A node whose faces turn every way (a
// sleeve's tube, the front with the back) is no height field; its children
// are tried. Loops are found once from the topology; signs and the loop's
// simplicity are checked at each certify().
#include "triangle_bvh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::geometry {

class HeightFieldNodes {
 public:
  // `edges`: the mesh's edges, each (a, b) with a < b (edge_list), indexed as
  // cover() takes them; `vertex_faces`: the faces at each vertex (the
  // untangler's topology has both). The tree must outlive this and keep its shape.
  HeightFieldNodes(const TriangleBvh& tree, const Eigen::MatrixX3i& faces, const std::vector<std::array<int, 2>>& edges,
                   const std::vector<std::vector<int>>& vertex_faces);

  // Finds the height-field nodes for these positions (largest first: a node
  // under one is not tried).
  void certify(const Eigen::MatrixX3d& x);

  // The largest height-field node that holds every face at edge e, or -1:
  // the edge crosses no face under it.
  int cover(int e) const {
    const int node = edge_node_[static_cast<std::size_t>(e)];
    return node < 0 ? -1 : top_[static_cast<std::size_t>(node)];
  }

  // Nodes found by the last certify() (the largest ones only).
  int certified() const { return certified_; }

 private:
  bool loop_is_simple(const std::vector<int>& loop, int axis, const Eigen::MatrixX3d& x);

  const TriangleBvh& tree_;
  Eigen::MatrixX3i faces_;
  std::vector<std::vector<int>> loop_;  // each node's boundary as one cycle of vertices; empty: not one loop
  std::vector<int> edge_node_;          // the smallest node holding every face at each edge
  std::vector<unsigned char> node_mask_;  // per node, the axis directions (+x, -x, +y, ...) every face turns to
  std::vector<int> top_;                // per node, the largest height-field node among it and its ancestors, or -1
  std::vector<Eigen::Vector2d> projected_;  // a loop seen along the axis (scratch)
  int certified_ = 0;
};

}  // namespace drape::geometry
