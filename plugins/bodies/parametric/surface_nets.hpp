#pragma once
// Surface nets: one vertex per grid cell that the surface crosses, one quad per
// crossed grid edge (split along its shorter diagonal). Faces are
// counter-clockwise seen from outside (the positive side of the field).
#include "implicit_body.hpp"

#include <Eigen/Core>

namespace drape::parametric {

struct RawMesh {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
};

// `offset` shifts the grid along y and z (in cells), giving another sampling
// of the same surface.
RawMesh surface_nets(const ImplicitBody& body, double cell, const Eigen::Vector2d& offset = Eigen::Vector2d::Zero());

}  // namespace drape::parametric
