// The `barrier` energy plugin: IPC-style barrier contact with the body (barrier.hpp).
#include "barrier.hpp"

#include <drape/energy.hpp>
#include <drape/physics/barrier_function.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "barrier";
  d.doc = "Body contact that never lets the surfaces cross: IPC's log barrier over every garment vertex-body "
          "triangle, body vertex-garment triangle and edge-edge pair within `distance`, with continuous collision "
          "checks on every move; needs a body.";
  d.params = barrier_param_specs("pairs closer than this push apart (the cloth's clearance off the skin)");
  d.params.insert(d.params.end(), {
      // ArcSim's default cloth-obstacle coefficient is 0.3 (its `obs_friction`).
      {.name = "friction", .type = ParamType::Float, .default_value = "0",
       .doc = "Coulomb's coefficient between cloth and body (IPC's lagged friction; 0: frictionless, ArcSim's default 0.3)",
       .min = 0, .max = 2},
      {.name = "slip_velocity", .type = ParamType::Float, .default_value = "0.01",
       .doc = "eps_v in m/s: slower slip is held as static friction (IPC's smoothing; a step of h s creeps up to eps_v h)",
       .min = 1e-6, .max = 1},
   });
  d.create_energy = [](const Params& p) {
    return std::make_unique<barrier::BarrierContact>(barrier::BarrierSettings{
        .distance = p.get_float("distance"),
        .stiffness = p.get_float("stiffness"),
        .min_separation = p.get_float("min_separation"),
        .friction = p.get_float("friction"),
        .slip_velocity = p.get_float("slip_velocity"),
    });
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
