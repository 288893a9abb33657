// The `self_contact` energy plugin: IPC-style barrier between the garment and itself (self_contact.hpp).
#include "self_contact.hpp"

#include <drape/energy.hpp>
#include <drape/physics/barrier_function.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "self_contact";
  d.doc = "Cloth that never passes through itself: IPC's log barrier over every garment vertex-triangle and "
          "edge-edge pair within `distance` (less pairs sharing a vertex, fabric neighbours close at rest, and pairs "
          "inside a place where the rest mesh already crosses itself), with continuous collision checks on every move.";
  // 1 mm: about two of the knit's thicknesses (4.7e-4 m, docs/materials.md);
  // layers pressed together rest between d_hat / 2 and d_hat apart.
  d.params = barrier_param_specs("garment pairs closer than this push apart");
  d.params.insert(d.params.end(), {
      {.name = "rest_exclusion", .type = ParamType::Float, .default_value = "3",
       .doc = "in units of distance: pairs joined by at most two mesh edges and closer than this in the rest mesh are "
              "not checked (slivers and short hem edges would fight the cloth's own shape)", .min = 0, .max = 100},
      {.name = "thin_rest_neighbours", .type = ParamType::Bool, .default_value = "false",
       .doc = "keep those pairs instead, each with half its rest distance (at most `distance`) as its own distance: "
              "nothing pushed at rest, and no fold between fabric neighbours passes through the cloth (a crowded seam)"},
   });
  d.create_energy = [](const Params& p) {
    return std::make_unique<self_contact::SelfContact>(self_contact::SelfContactSettings{
        .distance = p.get_float("distance"),
        .stiffness = p.get_float("stiffness"),
        .min_separation = p.get_float("min_separation"),
        .rest_exclusion = p.get_float("rest_exclusion"),
        .thin_rest_neighbours = p.get_bool("thin_rest_neighbours"),
    });
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
