#include <drape/vertex_count.hpp>
#include <drape/nn/body_graph_input.hpp>

#include <drape/assets/assets.hpp>
#include <drape/errors.hpp>

namespace drape::nn {

const Mesh& check_body_graph_input(const ShapeMap& in, const NodeContext& context, const std::string& who) {
  const Shape body = in.at("body");
  if (body.cols != 3) throw ConfigError("input 'body' must be [vertices, 3], got " + body.str());
  if (!context.assets || context.assets->body.num_vertices() == 0)
    throw ConfigError(who + " needs the template's assets (the body mesh's graph); none are bound");
  const Mesh& mesh = context.assets->body;
  require_vertex_count(body.rows, mesh.num_vertices(), "input 'body'", "the assets' body mesh");
  return mesh;
}

}  // namespace drape::nn
