#include <drape/nn/body_loss_inputs.hpp>

#include <drape/assets/assets.hpp>
#include <drape/errors.hpp>
#include <drape/nn/loss_inputs.hpp>

namespace drape {

int check_body_loss_inputs(const ShapeMap& in, const NodeContext& context, const std::string& who) {
  if (!context.assets || context.assets->body.num_faces() == 0)
    throw ConfigError("the " + who + " loss needs the body's faces, but no assets with a body mesh are bound to this graph");
  const Shape pred = check_pred_target(in), body = in.at("body");
  if (pred.cols != 3 || pred.rows < 1) throw ConfigError("pred must be [vertices, 3], got " + pred.str());
  const int body_rows = context.assets->body.num_vertices();
  if (body.cols != 3 || body.rows != body_rows)
    throw ConfigError("body must be [" + std::to_string(body_rows) +
                      ", 3] (the vertices of a body with the assets' topology), got " + body.str());
  return pred.rows;
}

}  // namespace drape
