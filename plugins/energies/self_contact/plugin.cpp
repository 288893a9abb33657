// The `self_contact` energy plugin: IPC-style barrier between the garment and itself (self_contact.hpp).
#include "self_contact.hpp"

#include <drape/energy.hpp>
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
  d.params = {
      // 1 mm: about two of the knit's thicknesses (4.7e-4 m, docs/materials.md);
      // layers pressed together rest between d_hat / 2 and d_hat apart.
      {.name = "distance", .type = ParamType::Float, .default_value = "0.001",
       .doc = "d_hat in m: garment pairs closer than this push apart", .min = 1e-6, .max = 0.1},
      {.name = "stiffness", .type = ParamType::Float, .default_value = "1000",
       .doc = "kappa in Pa: the contact pressure scale (0.2 kappa at 0.9 d_hat, 4.3 kappa at d_hat / 2, unbounded at 0)",
       .min = 1e-6},
      {.name = "min_separation", .type = ParamType::Float, .default_value = "0.1",
       .doc = "a move stops where a pair is down to this fraction of its distance (continuous collision check)",
       .min = 1e-3, .max = 0.9},
      {.name = "rest_exclusion", .type = ParamType::Float, .default_value = "3",
       .doc = "in units of distance: pairs joined by at most two mesh edges and closer than this in the rest mesh are "
              "not checked (slivers and short hem edges would fight the cloth's own shape)", .min = 0, .max = 100},
  };
  d.create_energy = [](const Params& p) {
    return std::make_unique<self_contact::SelfContact>(self_contact::SelfContactSettings{
        .distance = p.get_float("distance"),
        .stiffness = p.get_float("stiffness"),
        .min_separation = p.get_float("min_separation"),
        .rest_exclusion = p.get_float("rest_exclusion"),
    });
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
