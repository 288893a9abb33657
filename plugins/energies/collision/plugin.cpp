// The `collision` energy plugin: body collision penalty (body_collision.hpp).
#include "body_collision.hpp"

#include <drape/energy.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "collision";
  d.doc = "Body collision: one-sided cubic penalty area * k * max(0, margin - d)^3 / 3 on each vertex's signed "
          "distance d to the body (PBNS/SNUG); needs a body.";
  d.params = {
      // 30 Pa (a shirt's tension over the torso) at 1.7 mm into the margin, 100 Pa at 3.2 mm.
      {.name = "stiffness", .type = ParamType::Float, .default_value = "1e7",
       .doc = "k in N/m^4: contact pressure k * (margin - d)^2 Pa; the default holds 30 Pa 1.3 mm off the skin",
       .min = 0.0},
      {.name = "margin", .type = ParamType::Float, .default_value = "0.003",
       .doc = "m: wanted clearance between the cloth's mid-surface and the body", .min = 0.0, .max = 0.1},
      {.name = "max_depth", .type = ParamType::Float, .default_value = "0",
       .doc = "m: beyond this depth inside the body the penalty grows linearly (push capped, still outward); 0 = no cap",
       .min = 0.0, .max = 10.0},
      {.name = "smoothing", .type = ParamType::Float, .default_value = "0",
       .doc = "m: distance to a smooth surface blended from the body's vertex planes within this radius (rounds concave "
              "creases, where the exact distance kinks); 0 = exact closest point; must exceed the margin",
       .min = 0.0, .max = 1.0},
      {.name = "creases", .type = ParamType::Bool, .default_value = "true",
       .doc = "also push off the far side of a concave crease of the body (the armpit of a heavy body), so that cloth "
              "squeezed into it has a smooth equilibrium; needs smoothing 0"},
  };
  d.create_energy = [](const Params& p) {
    return std::make_unique<collision::BodyCollision>(collision::CollisionSettings{
        .stiffness = p.get_float("stiffness"),
        .margin = p.get_float("margin"),
        .max_depth = p.get_float("max_depth"),
        .smoothing = p.get_float("smoothing"),
        .creases = p.get_bool("creases"),
    });
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
