// Scene settings' specs and the check of a scene's names against the registry.
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/physics/solver.hpp>

#include "barrier_morph.hpp"

#include <cstdio>
#include <string>

namespace drape {

namespace {

// The solver's own defaults (SolverSettings, BarrierMorph) written as scene
// defaults, so that the two cannot drift apart.
std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}
std::string number(int v) { return std::to_string(v); }
std::string number(bool v) { return v ? "true" : "false"; }
std::string list_of_two(double a, double b) {
  char text[64];
  std::snprintf(text, sizeof text, "[%.6g, %.6g]", a, b);  // as number()
  return text;
}

}  // namespace

const std::vector<ParamSpec>& scene_solver_specs() {
  static const SolverSettings d;
  static const scene_detail::BarrierMorph carry;  // its carry distances are morph_carry's default
  static const std::vector<ParamSpec> specs = {
      {.name = "time_step", .type = ParamType::Float, .default_value = number(d.time_step),
       .doc = "backward-Euler time step, s", .min = 1e-5, .max = 10.0},
      {.name = "damping", .type = ParamType::Float, .default_value = number(d.damping),
       .doc = "fraction of the velocity dropped per step (1 = quasi-static)", .min = 0.0, .max = 1.0},
      {.name = "morph_steps", .type = ParamType::Int, .default_value = "20",
       .doc = "steps over which the body morphs from the mean shape to the target", .min = 0.0, .max = 1e6},
      {.name = "settle_steps", .type = ParamType::Int, .default_value = "120",
       .doc = "at most this many steps on the target body to settle", .min = 0.0, .max = 1e6},
      {.name = "max_newton_iterations", .type = ParamType::Int, .default_value = number(d.max_newton_iterations),
       .doc = "Newton iterations per settling step at most", .min = 1.0, .max = 1e4},
      {.name = "morph_newton_iterations", .type = ParamType::Int, .default_value = "3",
       .doc = "Newton iterations per morphing step at most", .min = 1.0, .max = 1e4},
      {.name = "tolerance", .type = ParamType::Float, .default_value = number(d.tolerance),
       .doc = "a step converges at |grad Phi| <= tolerance * |weight|", .min = 1e-14, .max = 1.0},
      {.name = "settle_tolerance", .type = ParamType::Float, .default_value = number(d.settle_tolerance),
       .doc = "the drape is settled at |grad E| <= this * |weight|", .min = 1e-14, .max = 10.0},
      {.name = "rest_displacement", .type = ParamType::Float, .default_value = number(d.rest_displacement),
       .doc = "m: settled when no vertex moves farther in a step", .min = 0.0, .max = 1.0},
      {.name = "kink_tolerance", .type = ParamType::Float, .default_value = number(d.kink_tolerance),
       .doc = "at rest counts as settled only below this stationarity / |weight|", .min = 0.0, .max = 1e6},
      {.name = "kink_radius", .type = ParamType::Float, .default_value = number(d.kink_radius),
       .doc = "m: contact pushes sampled this far around a vertex count towards its balance (the stationarity of a crease)",
       .min = 0.0, .max = 0.1},
      {.name = "max_displacement", .type = ParamType::Float, .default_value = number(d.max_displacement),
       .doc = "m: no vertex moves farther in one Newton iteration", .min = 1e-6, .max = 10.0},
      {.name = "linear_solver", .type = ParamType::String, .default_value = d.linear_solver,
       .doc = "sparse Cholesky: auto (cholmod when built with it), eigen, cholmod",
       .choices = {"auto", "eigen", "cholmod"}},
      {.name = "reuse_factorization", .type = ParamType::Bool, .default_value = number(d.reuse_factorization),
       .doc = "precondition CG with the last Cholesky factor; factorise only when CG stalls"},
      {.name = "preconditioner", .type = ParamType::String, .default_value = d.float_preconditioner ? "float" : "double",
       .doc = "precision of the kept factor's solves inside CG (cholmod): float halves their memory traffic; double is exact",
       .choices = {"float", "double"}},
      {.name = "newton_forcing", .type = ParamType::Float, .default_value = number(d.newton_forcing),
       .doc = "inexact Newton: CG stops at |H d + g| <= this * |g|", .min = 1e-12, .max = 0.9},
      {.name = "max_cg_iterations", .type = ParamType::Int, .default_value = number(d.max_cg_iterations),
       .doc = "CG iterations before the Newton matrix is factorised anew", .min = 1, .max = 10000},
      {.name = "exact_hessian_below", .type = ParamType::Float, .default_value = number(d.exact_hessian_below),
       .doc = "below this step residual (|grad Phi| / |W|) try the exact, unprojected Newton matrix first and keep it when positive definite; 0: always project",
       .min = 0.0, .max = 1e30},
      {.name = "adaptive_tries", .type = ParamType::Bool, .default_value = number(d.adaptive_tries),
       .doc = "after a PCG solve that stalls or an exact matrix found indefinite, factorise / project without trying them for a while; false: try at every iteration"},
      {.name = "settle_check", .type = ParamType::String, .default_value = "iteration",
       .doc = "when a settling drape checks that it has settled: every Newton iteration, or only at the end of a time step (the solver of 2026-11-28)",
       .choices = {"iteration", "step"}},
      {.name = "morph_carry", .type = ParamType::FloatList,
       .default_value = list_of_two(carry.carry_inner, carry.carry_outer),
       .doc = "m: under a barrier, cloth within the first distance of the skin moves with it during the morph, fading to not at all at the second (larger carries loose sleeves with a raising arm: docs/poses.md)",
       .min = 0.0, .max = 0.5},
      {.name = "pose_path", .type = ParamType::String, .default_value = "together",
       .doc = "how a posed body moves from the start: shape morph and joint angles together, the pose first, or the shape first",
       .choices = {"together", "pose_first", "shape_first"}},
      {.name = "gravity_direction", .type = ParamType::FloatList, .default_value = "[0, -1, 0]",
       .doc = "direction of gravity (the magnitude is the gravity effect's g)"},
  };
  return specs;
}

const std::vector<ParamSpec>& scene_shape_specs() {
  static const std::vector<ParamSpec> specs = {
      {.name = "bmi", .type = ParamType::Float, .default_value = "24",
       .doc = "body mass index of the target body, kg/m^2", .min = 5.0, .max = 100.0},
      {.name = "height", .type = ParamType::Float, .default_value = "1.75",
       .doc = "height of the target body, m", .min = 0.5, .max = 2.5},
      {.name = "sex", .type = ParamType::Float, .default_value = "1",
       .doc = "0 female ... 1 male", .min = 0.0, .max = 1.0},
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
                                 "s: " + (known.empty() ? "none (no " + kind + " plugin was loaded)" : joined(known)) +
                                 registry.refused_notes());
  }
  return *d;
}

}  // namespace

void validate_scene(const Scene& scene, const Registry& registry) {
  const SourceLocation file{scene.file, 0};
  const auto or_file = [&](const SourceLocation& at) { return at.file.empty() ? file : at; };
  const PluginDescriptor& body = plugin_of_kind(registry, scene.body_model, "body", "body model", or_file(scene.body_model_where));
  Params(body.params, scene.body_params, "body '" + scene.body_model + "'");
  Params(scene_shape_specs(), scene.shape, "body shape");
  const PluginDescriptor& garment = plugin_of_kind(registry, scene.garment, "garment", "garment template", or_file(scene.garment_where));
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
