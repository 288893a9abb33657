#pragma once
// A smooth signed distance to the body for the collision penalty: implicit
// moving least squares over the body's vertices and their normals (IMLS,
// Kolluri 2008; Oztireli et al. 2009):
//
//   d(x) = sum_j w_j(x) n_j^T (x - v_j) / sum_j w_j(x),   w_j = (1 - |x - v_j|^2 / R^2)^3 inside R, else 0
//
// Why: the exact distance to a triangle mesh is the minimum over its faces.
// In a concave crease (the armpit, where a tight sleeve presses the knit) the
// closest face switches from one side to the other, the penalty's gradient
// jumps there, and Newton's line search stalls with a residual floor (the
// "contact kinks" of docs/scenes.md). d above blends the planes of every
// vertex within R, so it is C^2 everywhere: creases are rounded over a few
// centimetres instead of switching at a line.
//
// Where no body vertex is within R (far outside, or deep inside a thick part)
// the exact closest-point contact is used: far outside both are beyond the
// margin (R must exceed it), so the energy is continuous there; deep inside
// only the push direction matters.
#include "contacts.hpp"

#include <Eigen/Core>

#include <unordered_map>
#include <vector>

namespace drape::collision {

// The body's vertices hashed into cubes of side R, rebuilt for every call (the
// body moves between calls; 6.5k vertices hash in ~0.1 ms).
class VertexGrid {
 public:
  VertexGrid(const Eigen::MatrixX3d& vertices, double cell);
  // Calls f(j) for every vertex j within `cell` of p (and some a little farther).
  template <class F>
  void for_each_near(const Eigen::Vector3d& p, F&& f) const {
    const Eigen::Vector3i c = cell_of(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int j : it->second) f(j);
        }
  }

 private:
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;
  static long long key(const Eigen::Vector3i& c);
  double cell_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

// One contact per row of x: the IMLS distance, its gradient (not unit length)
// and, with with_hessian, its Hessian. Rows with no body vertex within
// `radius` are left default and marked false in `covered`: the caller gives
// them the exact closest-point contact (only those rows need the BVH).
std::vector<Contact> smooth_contacts(const Eigen::MatrixX3d& body_vertices, const Eigen::MatrixX3d& body_normals,
                                     const Eigen::MatrixX3d& x, double radius, bool with_hessian,
                                     std::vector<char>& covered);

}  // namespace drape::collision
