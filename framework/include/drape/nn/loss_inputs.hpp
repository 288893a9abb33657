#pragma once
// What the losses over pred and target check in setup(), in one place, so that
// every loss refuses a wrong graph with the same words (the losses that also
// read the body: body_loss_inputs.hpp).
#include <drape/mesh.hpp>
#include <drape/node.hpp>

#include <string>

namespace drape {

// pred's shape; ConfigError when pred and target differ in shape.
Shape check_pred_target(const ShapeMap& in);
// The same, and pred must be [garment_vertices, 3].
Shape check_garment_pred_target(const ShapeMap& in, int garment_vertices);
// The bound garment template's mesh; ConfigError otherwise, saying that the
// loss `who` needs `what` of it (e.g. "the garment's edges").
const Mesh& bound_garment_mesh(const NodeContext& context, const std::string& who, const std::string& what);

}  // namespace drape
