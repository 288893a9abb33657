#pragma once
// Where the template needs finer triangles than the rest of the body (the
// hands, a few centimetres across their thumb), it is meshed in a warped space
// that magnifies those places: the grid of surface_nets.cpp is uniform in the
// warped space, so its cells are `scale` times smaller in the body near each
// magnifier's centre. Each magnifier is a radial map of a ball onto itself,
// r -> W(r) with W(0) = 0 and W(support) = support: W' = scale out to `inner`,
// then falling to `min_slope` at `outer` and back to 1 at the support, which
// is as far out as it must be for the ball to map onto itself. So W' > 0 and
// W(r) >= r: a bijection, never coarser than the plain grid across the
// radius, coarser along it (at most 1 / min_slope) in the shell between outer
// and the support. Magnifiers must not overlap (checked).
#include <Eigen/Core>

#include <vector>

namespace drape::parametric {

struct Magnifier {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double scale = 1;        // how much finer the cells are at the centre
  double inner = 0;        // radius (m) of the uniformly magnified ball
  double outer = 0;        // radius where the radial slope is lowest
  double min_slope = 0.6;  // that lowest slope
  double support() const;  // radius beyond which nothing moves
};

using Magnifiers = std::vector<Magnifier>;

// The body point x in the warped space, and back. Throw Error when two
// magnifiers overlap.
Eigen::Vector3d warp(const Magnifiers& m, const Eigen::Vector3d& x);
Eigen::Vector3d unwarp(const Magnifiers& m, const Eigen::Vector3d& y);
void check_magnifiers(const Magnifiers& m);

}  // namespace drape::parametric
