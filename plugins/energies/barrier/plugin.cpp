// The `barrier` energy plugin: IPC-style barrier contact with the body (barrier.hpp).
#include "barrier.hpp"

#include <drape/energy.hpp>
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
  d.params = {
      {"distance", ParamType::Float, "0.001",
       "d_hat in m: pairs closer than this push apart (the cloth's clearance off the skin)", 1e-6, 0.1},
      // 0.2 kappa at 0.9 d_hat: 200 Pa, a shirt's pressure over the shoulders.
      {"stiffness", ParamType::Float, "1000",
       "kappa in Pa: the contact pressure scale (0.2 kappa at 0.9 d_hat, 4.3 kappa at d_hat / 2, unbounded at 0)", 1e-6},
      {"min_separation", ParamType::Float, "0.1",
       "a move stops where a pair is down to this fraction of its distance (continuous collision check)", 1e-3, 0.9},
      // ArcSim's default cloth-obstacle coefficient is 0.3 (its `obs_friction`).
      {"friction", ParamType::Float, "0",
       "Coulomb's coefficient between cloth and body (IPC's lagged friction; 0: frictionless, ArcSim's default 0.3)", 0, 2},
      {"slip_velocity", ParamType::Float, "0.01",
       "eps_v in m/s: slower slip is held as static friction (IPC's smoothing; a step of h s creeps up to eps_v h)", 1e-6, 1},
  };
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
