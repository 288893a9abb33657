#pragma once
// The faces of a mesh nearest to each of a set of points, kept so that a query
// from a point close to one of them tests a few faces instead of searching the
// whole tree.
//
// Training asks, at every step, for the closest body point of every predicted
// garment vertex x; the ground-truth vertex y of the same row is fixed data and
// lies a few millimetres from x once the network has learnt anything. The
// distance to a face is 1-Lipschitz, so dist(x, f) >= dist(y, f) - |x - y|:
// walking y's faces in order of dist(y, f), no face can beat the best found so
// far once dist(y, f) - |x - y| exceeds it, and faces past the list are ruled
// out the same way by the radius within which the list is complete. The answer
// is the one the tree search gives, bit for bit (NearestTriangles::nearest_from);
// when the list cannot prove it (x far from y), the tree is searched.
#include <cstddef>
#include <vector>

namespace drape::geometry {

struct NearbyFaces {
  std::vector<int> start;        // point i's faces are [start[i], start[i + 1])
  std::vector<int> face;         // nearest first
  std::vector<float> reach;      // dist(y_i, face), rounded down
  std::vector<float> complete;   // per point: every face nearer than this is listed (rounded down)

  int points() const { return static_cast<int>(complete.size()); }
  std::size_t bytes() const {
    return sizeof(int) * (start.size() + face.size()) + sizeof(float) * (reach.size() + complete.size());
  }
};

}  // namespace drape::geometry
