// Scene settings' specs and the check of a scene's names against the registry.
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/physics/solver.hpp>

#include <cstdio>
#include <string>

namespace drape {

namespace {

// The solver's own defaults (SolverSettings) written as scene defaults, so
// that the two cannot drift apart.
std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}
std::string number(int v) { return std::to_string(v); }
std::string number(bool v) { return v ? "true" : "false"; }

}  // namespace

const std::vector<ParamSpec>& scene_solver_specs() {
  static const SolverSettings d;
  static const std::vector<ParamSpec> specs = {
      {"time_step", ParamType::Float, number(d.time_step), "backward-Euler time step, s", 1e-5, 10.0},
      {"damping", ParamType::Float, number(d.damping), "fraction of the velocity dropped per step (1 = quasi-static)", 0.0, 1.0},
      {"morph_steps", ParamType::Int, "20", "steps over which the body morphs from the mean shape to the target", 0.0, 1e6},
      {"settle_steps", ParamType::Int, "60", "at most this many steps on the target body to settle", 0.0, 1e6},
      {"max_newton_iterations", ParamType::Int, number(d.max_newton_iterations), "Newton iterations per settling step at most", 1.0, 1e4},
      {"morph_newton_iterations", ParamType::Int, "3", "Newton iterations per morphing step at most", 1.0, 1e4},
      {"tolerance", ParamType::Float, number(d.tolerance), "a step converges at |grad Phi| <= tolerance * |weight|", 1e-14, 1.0},
      {"settle_tolerance", ParamType::Float, number(d.settle_tolerance), "the drape is settled at |grad E| <= this * |weight|", 1e-14, 10.0},
      {"rest_displacement", ParamType::Float, number(d.rest_displacement), "m: settled when no vertex moves farther in a step", 0.0, 1.0},
      {"kink_tolerance", ParamType::Float, number(d.kink_tolerance), "at rest counts as settled only below this stationarity / |weight|", 0.0, 1e6},
      {"kink_radius", ParamType::Float, number(d.kink_radius),
       "m: contact pushes sampled this far around a vertex count towards its balance (the stationarity of a crease)", 0.0,
       0.1},
      {"max_displacement", ParamType::Float, number(d.max_displacement), "m: no vertex moves farther in one Newton iteration", 1e-6, 10.0},
      {"linear_solver", ParamType::String, d.linear_solver, "sparse Cholesky: auto (cholmod when built with it), eigen, cholmod",
       {}, {}, {"auto", "eigen", "cholmod"}},
      {"reuse_factorization", ParamType::Bool, number(d.reuse_factorization), "precondition CG with the last Cholesky factor; factorise only when CG stalls"},
      {"preconditioner", ParamType::String, d.float_preconditioner ? "float" : "double",
       "precision of the kept factor's solves inside CG (cholmod): float halves their memory traffic; double is exact",
       {}, {}, {"float", "double"}},
      {"newton_forcing", ParamType::Float, number(d.newton_forcing), "inexact Newton: CG stops at |H d + g| <= this * |g|", 1e-12, 0.9},
      {"max_cg_iterations", ParamType::Int, number(d.max_cg_iterations), "CG iterations before the Newton matrix is factorised anew", 1, 10000},
      {"exact_hessian_below", ParamType::Float, number(d.exact_hessian_below),
       "below this step residual (|grad Phi| / |W|) try the exact, unprojected Newton matrix first and keep it when positive definite; 0: always project",
       0.0, 1e30},
      {"adaptive_tries", ParamType::Bool, number(d.adaptive_tries),
       "after a PCG solve that stalls or an exact matrix found indefinite, factorise / project without trying them for a while; false: try at every iteration"},
      {"settle_check", ParamType::String, "iteration",
       "when a settling drape checks that it has settled: every Newton iteration, or only at the end of a time step (the solver of 2026-11-28)",
       {}, {}, {"iteration", "step"}},
      {"gravity_direction", ParamType::FloatList, "[0, -1, 0]", "direction of gravity (the magnitude is the gravity effect's g)"},
  };
  return specs;
}

const std::vector<ParamSpec>& scene_shape_specs() {
  static const std::vector<ParamSpec> specs = {
      {"bmi", ParamType::Float, "24", "body mass index of the target body, kg/m^2", 5.0, 100.0},
      {"height", ParamType::Float, "1.75", "height of the target body, m", 0.5, 2.5},
      {"sex", ParamType::Float, "1", "0 female ... 1 male", 0.0, 1.0},
  };
  return specs;
}

namespace {

std::vector<std::string> names_of_kind(const Registry& registry, const std::string& kind) {
  std::vector<std::string> out;
  for (const PluginDescriptor* d : registry.all())
    if (d->kind == kind) out.push_back(d->name);
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

const PluginDescriptor& plugin_of_kind(const Registry& registry, const std::string& name, const std::string& kind,
                                       const std::string& what, const SourceLocation& where) {
  const PluginDescriptor* d = registry.find(name);
  if (!d || d->kind != kind) {
    const auto known = names_of_kind(registry, kind);
    throw ConfigError(where, "unknown " + what + " '" + name + "'" + did_you_mean(name, known) + "; known " + what +
                                 "s: " + (known.empty() ? "none (no " + kind + " plugin was loaded)" : joined(known)));
  }
  return *d;
}

}  // namespace

void validate_scene(const Scene& scene, const Registry& registry) {
  const SourceLocation file{scene.file, 0};
  const PluginDescriptor& body = plugin_of_kind(registry, scene.body_model, "body", "body model", file);
  Params(body.params, scene.body_params, "body '" + scene.body_model + "'");
  Params(scene_shape_specs(), scene.shape, "body shape");
  const PluginDescriptor& garment = plugin_of_kind(registry, scene.garment, "garment", "garment template", file);
  Params(garment.params, scene.garment_params, "garment '" + scene.garment + "'");
  if (scene.effects.empty()) throw ConfigError(file, "the scene names no effects: list the energies to simulate under `effects:`");
  for (const SceneEffect& e : scene.effects) {
    const PluginDescriptor& d = plugin_of_kind(registry, e.name, "energy", "effect", e.where);
    Params(d.params, e.params, "effect '" + e.name + "'");
  }
  const Params solver(scene_solver_specs(), scene.solver, "solver");
  const auto g = solver.get_float_list("gravity_direction");
  if (g.size() != 3) throw ConfigError(file, "solver: gravity_direction must have 3 numbers");
}

}  // namespace drape
