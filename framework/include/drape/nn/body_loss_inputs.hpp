#pragma once
// What every loss that reads the body (v2v, direction, penetration) checks in
// setup(), in one place: assets with the body's faces are bound; pred and
// target are both [N, 3]; body is [Nb, 3] with the assets' body topology.
#include <drape/node.hpp>

#include <string>

namespace drape {

// N, the garment rows; ConfigError naming the loss (`who`) and what is wrong otherwise.
int check_body_loss_inputs(const ShapeMap& in, const NodeContext& context, const std::string& who);

}  // namespace drape
