#pragma once
// What the encoders that convolve on the body mesh's graph (gcn, gcn_learned)
// check in setup(), in one place: input `body` is [vertices, 3] with the
// vertex count of the bound assets' body, whose faces give the graph.
#include <drape/mesh.hpp>
#include <drape/node.hpp>

#include <string>

namespace drape::nn {

// The assets' body mesh; ConfigError naming the encoder (`who`) and what is wrong otherwise.
const Mesh& check_body_graph_input(const ShapeMap& in, const NodeContext& context, const std::string& who);

}  // namespace drape::nn
