#pragma once
// Carries the template to another shape: each vertex follows its bound parts
// (blended), lands on the shape's surface by Newton projection and is relaxed
// along it. A level set never intersects itself, so neither does the result
// as long as its triangles stay unfolded (the tests check both).
#include "body_template.hpp"

namespace drape::parametric {

Eigen::MatrixX3d fit_template(const BodyTemplate& tpl, const ImplicitBody& body);

// Rescales y so that the mesh spans [0, height] exactly (feet on the floor).
void normalise_height(Eigen::MatrixX3d& vertices, double height);

}  // namespace drape::parametric
