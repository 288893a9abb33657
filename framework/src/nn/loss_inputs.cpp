#include <drape/nn/loss_inputs.hpp>

#include <drape/assets/assets.hpp>
#include <drape/errors.hpp>

namespace drape {

Shape check_pred_target(const ShapeMap& in) {
  const Shape pred = in.at("pred"), target = in.at("target");
  if (!(pred == target)) throw ConfigError("pred " + pred.str() + " and target " + target.str() + " differ in shape");
  return pred;
}

Shape check_garment_pred_target(const ShapeMap& in, int garment_vertices) {
  const Shape pred = check_pred_target(in);
  if (pred.cols != 3 || pred.rows != garment_vertices)
    throw ConfigError("pred must be [" + std::to_string(garment_vertices) + ", 3] (the garment's vertices), got " +
                      pred.str());
  return pred;
}

const Mesh& bound_garment_mesh(const NodeContext& context, const std::string& who, const std::string& what) {
  if (!context.assets || !context.assets->garment)
    throw ConfigError("the " + who + " loss needs " + what + ", but no garment template is bound to this graph (set "
                      "`assets:` in the graph or pass a garment)");
  return context.assets->garment->mesh;
}

}  // namespace drape
