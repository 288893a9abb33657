// Scene -> energies, body and garment; the morph-then-settle run (simulation.hpp).
#include <drape/vertex_count.hpp>
#include <drape/physics/dissipation.hpp>
#include <drape/bodies/body.hpp>
#include <drape/bodies/fit_body.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/geometry/girth.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/garment_grading.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/registry.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/error_context.hpp>
#include <drape/warnings.hpp>
#include <drape/physics/barrier_function.hpp>

#include "barrier_morph.hpp"
#include "cloth_fit.hpp"
#include "garment_region.hpp"
#include "gradient_consistency.hpp"
#include "body_overlap.hpp"
#include "scene_materials.hpp"
#include "separated_start.hpp"
#include "unsettled.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <tuple>
#include <utility>

namespace drape {

namespace {

// Where a garment's own error (a plugin knows no file) is placed: at the
// first of its parameters written in the scene's own file, else in the file
// of the first one (a `base:`), else at the scene's file.
SourceLocation garment_params_where(const Scene& scene) {
  SourceLocation where{scene.file, 0};
  for (const auto& [name, value] : scene.garment_params) {
    const bool better_file = value.where.file == scene.file && where.file != scene.file;
    if (where.line == 0 || better_file || (value.where.file == where.file && value.where.line < where.line)) where = value.where;
  }
  return where;
}

// The scene's garment template, its parameter checks placed (garment_params_where).
std::unique_ptr<GarmentSource> garment_of_scene(const Registry& registry, const Scene& scene,
                                                const PluginDescriptor& descriptor) {
  const Params params(descriptor.params, scene.garment_params, "garment '" + scene.garment + "'");  // placed itself
  try {
    return registry.create_garment(scene.garment, params);
  } catch (...) {
    rethrow_at(garment_params_where(scene), scene.garment);  // the registry's "tshirt: ..." already names it
  }
}

// The garment built, its errors placed as garment_of_scene's are (an outside
// check: MakeHuman clothes' "no piece 9" named the asset's .obj, not the
// scene's line that asked for it).
Garment build_garment(const Registry& registry, const Scene& scene, const PluginDescriptor& descriptor) {
  const std::unique_ptr<GarmentSource> source = garment_of_scene(registry, scene, descriptor);
  try {
    return source->build();
  } catch (...) {
    rethrow_at(garment_params_where(scene), scene.garment);  // (the plugin's "makehuman_clothes: ..." names it)
  }
}

// The solver's morph_carry, [inner, outer] m (scene_solver_specs, whose
// bounds Params checks per element), refused at its line unless two, inner
// below outer.
std::pair<double, double> morph_carry(const Params& solver, const Scene& scene) {
  const auto carry = solver.get_float_list("morph_carry");
  if (carry.size() != 2 || !(carry[1] > carry[0])) {
    const auto key = scene.solver.find("morph_carry");
    throw ConfigError(key == scene.solver.end() ? SourceLocation{scene.file, 0} : key->second.where,
                      "solver: morph_carry must be two distances [inner, outer] in m with 0 <= inner < outer <= 0.5");
  }
  return {carry[0], carry[1]};
}

// m: body faces this close to the dressed garment lie under it (a shirt is
// worn within a few centimetres of the skin; sleeves hang farther).
constexpr double kGarmentReach = 0.05;

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Counts every step's work into the result and reports it (SimulationOptions::on_step).
struct StepRecorder {
  SimulationResult& result;
  const SimulationOptions& options;
  int total;
  void operator()(int k, bool morphing, const StepReport& r, double stationarity, double slip_ratio = 0) const {
    ++result.steps;
    result.iterations += r.iterations;
    result.line_search_failures += r.line_search_failures;
    if (options.on_step) options.on_step({k, total, morphing, r, stationarity, slip_ratio});
  }
};

// The settling steps on the target body, until the drape is stationary and
// nothing slides, it comes to rest, or it falls off the body; then whether it
// converged.
void settle(ClothSolver& solver, Eigen::MatrixX3d& x, Eigen::MatrixX3d& v, const Eigen::MatrixX3d& target_body,
            int morph_steps, int settle_steps, bool settle_every_iteration, const StepRecorder& record,
            SimulationResult& result) {
  result.initial_energy = solver.energy(x);
  // Settled by stationarity, which at a body crease counts the pushes of both
  // faces (ClothSolver::stationarity); the plain residual is reported as well.
  const double kink_radius = solver.settings().kink_radius;
  result.stationarity = solver.stationarity(x, kink_radius);
  // With friction, a drape whose forces friction balances may still slide:
  // it has settled only when no contact slips faster than friction holds.
  result.slip_ratio = solver.slip_ratio(x);
  const double settle_tolerance = solver.settings().settle_tolerance;
  // A step that moves no vertex ends the settling: further steps from a
  // stall change nothing (tried: on a stalled BMI 65 body 54 more steps only
  // found no decrease). Whether that counts as settled is decided below.
  const double at_rest_limit = solver.settings().kink_tolerance;
  result.settle_tolerance = settle_tolerance, result.rest_tolerance = at_rest_limit;
  for (int k = 1; k <= settle_steps && (result.stationarity > settle_tolerance || result.sliding()) && !result.at_rest; ++k) {
    // The step ends at the Newton iteration where the drape balances, not at
    // the end of the step (stationarity <= the step's balance, see solver.hpp).
    const StepReport r = solver.step(x, v, settle_every_iteration ? settle_tolerance : 0.0);
    result.stationarity = solver.stationarity(x, kink_radius);
    result.slip_ratio = solver.slip_ratio(x);
    result.at_rest = r.max_displacement <= solver.settings().rest_displacement;
    record(morph_steps + k, false, r, result.stationarity, result.slip_ratio);
    if (scene_detail::fell_off_body(x, target_body)) break;  // falling on: nothing can bring it back
  }
  // At rest counts only near equilibrium: a stall with large unbalanced forces is not a drape.
  result.converged = ((result.stationarity <= settle_tolerance && !result.sliding()) ||
                      (result.at_rest && result.stationarity <= at_rest_limit)) &&
                     !scene_detail::fell_off_body(x, target_body);  // (at rest on the feet is no drape)
}

// The settled drape's energies and forces, why it did not settle (when it did
// not), and how far it is inside the body.
void measure_drape(const ClothSolver& solver, std::vector<NamedEnergy>& energies, const Eigen::MatrixX3d& x,
                   const Eigen::MatrixX3d& target_body, const Mesh& garment, const Eigen::MatrixX3d& mean_body,
                   const Eigen::MatrixX3i& body_faces, int morph_steps, bool sized, const SimulationOptions& options,
                   std::unique_ptr<geometry::BodySurface>& surface, SimulationResult& result) {
  const double settle_tolerance = solver.settings().settle_tolerance;
  const double at_rest_limit = solver.settings().kink_tolerance;
  result.total_energy = solver.energy(x, &result.energies);
  Eigen::MatrixX3d gradient = solver.static_gradient(x);
  result.residual = gradient.norm() / solver.force_scale();
  // Unbalanced: what friction (its push in the last step) leaves of grad E.
  for (const NamedEnergy& e : energies)
    if (const Dissipation* d = e.energy->dissipation()) d->add_gradient(x, gradient);
  result.vertex_force = gradient.rowwise().norm();
  const bool has_friction =
      std::any_of(energies.begin(), energies.end(), [](const NamedEnergy& e) { return e.energy->dissipation() != nullptr; });
  if (!result.converged) {
    const double ease = garment_ease(garment.vertices, garment.faces, mean_body, target_body, body_faces);
    result.unsettled =
        scene_detail::why_unsettled(result, x, settle_tolerance, result.steps - morph_steps, at_rest_limit, ease, target_body,
                                    sized, has_friction);
    // Steps that found no decrease: an energy whose gradient is not its
    // value's derivative is one cause (a plugin's mistake), named.
    if (result.line_search_failures > 0) result.unsettled += scene_detail::inconsistent_gradients(energies, x, gradient);
    // A solver setting far from its default, named (cloth_fit.hpp).
    for (const std::string& slow : scene_detail::slow_solver_settings(solver.settings(), [](int n) {
           return "max_newton_iterations " + std::to_string(n) + " (the default " +
                  std::to_string(SolverSettings{}.max_newton_iterations) + ") ends each step after so few iterations";
         }))
      result.unsettled += "; " + slow;
  }
  // A piece that slid down the body (a two-piece outfit's skirt at the
  // feet) is no drape of it, settled or not: said (a garment that fell off
  // whole is said by why_unsettled).
  if (!scene_detail::fell_off_body(x, target_body)) {
    const std::string slid = scene_detail::pieces_slid_down(garment.vertices, mean_body, x, target_body, garment.faces, has_friction);
    if (!slid.empty() && result.converged) warn(slid);
    else if (!slid.empty()) result.unsettled += "; " + slid;
  }
  result.garment = x;
  result.body = target_body;
  result.linear_solver = solver.linear_solver();
  result.timings = solver.timings();
  if (options.measure_penetration) {
    if (!surface) surface = std::make_unique<geometry::BodySurface>(target_body, body_faces);
    result.body_distance = surface->signed_distances(x);
    const Eigen::VectorXd& d = result.body_distance;
    result.penetration = static_cast<double>((d.array() < 0).count()) / static_cast<double>(d.size());
    result.crossings = geometry::surface_crossings(x, garment.faces, target_body, body_faces);
    result.self_crossings = static_cast<int>(geometry::self_edge_crossings(x, garment.faces, std::size_t{1} << 20).size());
  }
}

}  // namespace

Simulation::Simulation(const Registry& registry, Scene scene) : registry_(registry), scene_(std::move(scene)) {
  validate_scene(scene_, registry_);
  // One Simulation is one garment; grade: auto builds one per grade (SceneSimulations).
  if (scene_.garment_grade_auto)
    throw ConfigError({scene_.file, 0}, "garment `grade: auto` is chosen per body; a Simulation takes one grade "
                                        "(drape simulate, drape generate and Python's drape.Scene choose it)");
  body_model_ = make_scene_body_model(registry_, scene_);
  mean_body_ = body_model_->vertices(body_model_->mean_shape());

  const PluginDescriptor& gd = registry_.get(scene_.garment);
  for (const ParamSpec& p : gd.params) sized_ = sized_ || (p.name == "size" && !p.choices.empty());
  Garment garment = build_garment(registry_, scene_, gd);
  if (!garment.body_model.empty() && garment.body_model != scene_.body_model)
    throw ConfigError({scene_.file, 0}, "garment '" + scene_.garment + "' is fitted to the body model '" +
                                            garment.body_model + "' (its mean body is what the garment is modelled "
                                            "around), and this scene's body is '" + scene_.body_model +
                                            "': set body: {model: " + garment.body_model + "}, or give a garment "
                                            "made for '" + scene_.body_model + "'");
  design_loop_ = garment_girth(garment.mesh.vertices, garment.mesh.faces, mean_body_);
  const bool graded = scene_.garment_grade != 1.0;
  const Eigen::MatrixX3d ungraded = graded ? garment.mesh.vertices : Eigen::MatrixX3d();  // for place_graded_garment
  // Trousers and dresses (pieces reaching below the mean body's crotch) keep their lengths.
  const double legs_below = graded ? mean_body_.col(1).minCoeff() + geometry::crotch_height(mean_body_, body_model_->faces())
                                   : std::numeric_limits<double>::quiet_NaN();
  const double floor = mean_body_.col(1).minCoeff();
  grade_garment(garment, scene_.garment_grade, legs_below, floor);  // before dressing: the graded garment is what goes around the body
  placed_loop_ = scene_.garment_grade == 1.0 ? design_loop_ : garment_girth(garment.mesh.vertices, garment.mesh.faces, mean_body_);
  std::string what = "garment '" + scene_.garment + "'";
  if (const auto file = scene_.garment_params.find("file"); file != scene_.garment_params.end() && file->second.node.IsScalar())
    what += " (" + file->second.node.as<std::string>() + ")";
  // Dressed on the body it is cut for: the mean body, or a larger size's fit
  // body (fit_body.hpp), where every run's morph then starts.
  // A graded garment that the uniform scale leaves through its fit body (a
  // body that grew unevenly: MakeHuman's shirt at grade 1.35 through its fit
  // body's chest), so that no start body shrunk by up to 6 cm is clear of it
  // (separated_start_body), is placed on it by the body's growth from the
  // mean body instead (place_graded_garment). Where the scale can start it is
  // kept: it is what every graded drape so far started from. One graded
  // smaller than the thinnest body the model reaches (its fit body clamped at
  // a larger girth) keeps the scale either way, so that its start is refused
  // with the grade that fits (start_fit_hint) instead of beginning stretched
  // around a body it cannot go around.
  FitBody fit = drape::fit_body(*body_model_, garment.fit_grade);
  const std::string dressed_what = what + " of " + scene_.file;
  const bool below_every_body = fit.clamped && fit.girth_ratio > garment.fit_grade;
  const bool may_grow = graded && !below_every_body;
  const Garment undressed = may_grow ? garment : Garment{};
  undressed_ = garment.mesh.vertices;  // where the file or template placed it, for a refused start's offset hint
  // (Only a garment no loop of which goes around the body, placed_loop_
  // infinite, can lie beside it: the same loops, measured once above.)
  if (!std::isfinite(placed_loop_))
    beside_body_ = garment_beside_body(undressed_, garment.mesh.faces, mean_body_, body_model_->faces());  // refused in run()
  DressReport dressed = dress_on(fit, *body_model_, garment, dressed_what);
  if (may_grow) {
    bool scaled_starts = true;
    try {
      scene_detail::separated_start_body(garment.mesh.vertices, fit.vertices, body_model_->faces(), garment.mesh.faces);
    } catch (const ConfigError&) {
      scaled_starts = false;
    }
    if (!scaled_starts) {
      garment = undressed;
      place_graded_garment(garment, ungraded, mean_body_, fit.vertices, body_model_->faces(), scene_.garment_grade,
                           legs_below, floor);
      dressed = dress_on(fit, *body_model_, garment, dressed_what);
    }
  }
  // Refused in run(), where a refused start gets its offset hint.
  if (placed_through(dressed)) placed_through_ = dressed.pushed_through, placed_through_depth_ = dressed.deepest_through;
  fit_body_ = std::move(fit.vertices);
  fit_request_ = fit.request;
  for (const SceneMaterial& dropped : scene_.dropped_materials)
    for (const Material& own : garment.materials)
      if (own.name == dropped.region)
        material_notes_.push_back(dropped.where.str() + ": `" + dropped.region +
                                  ": null` drops the base scene's material for region '" + dropped.region + "' (" +
                                  (dropped.spec.IsScalar() ? dropped.spec.Scalar() : std::string("an inline preset")) +
                                  "): it wears the garment template's own; name a preset to choose one");
  scene_detail::apply_scene_materials(garment, scene_);
  garment_ = std::make_shared<Garment>(std::move(garment));

  for (const SceneEffect& e : scene_.effects) {
    const PluginDescriptor& d = registry_.get(e.name);
    effect_params_.emplace_back(d.params, e.params, "effect '" + e.name + "'");
    try {
      needs_body_ = needs_body_ || registry_.create_energy(e.name, effect_params_.back())->needs_body();
    } catch (...) {
      rethrow_at(e.where, e.name);  // a plugin's own check of its parameters: at the effect's line
    }
  }
  cloth_loop_ = garment_material_girth(garment_->mesh, mean_body_);  // once, for every fit question below and in run()
  // Where the garment's cloth at rest comes from: its UVs, or its mesh as
  // given (a garment plugin's material_space: rest).
  const Params garment_params(gd.params, scene_.garment_params, "garment '" + scene_.garment + "'");
  bool rest_from_shape = false;
  for (const ParamSpec& p : gd.params)
    if (p.name == "material_space") rest_from_shape = garment_params.get_string("material_space") == "rest";
  // A garment whose cloth cannot go around the body it is put on, said now
  // (run() refuses it before any work; cloth_fit.hpp).
  if (needs_body_) {
    scene_detail::PatternSource pattern;
    for (const ParamSpec& p : gd.params) pattern.has_uv_scale = pattern.has_uv_scale || p.name == "uv_scale";
    if (pattern.has_uv_scale) pattern.uv_scale = garment_params.get_float("uv_scale");
    pattern.grade = scene_.garment_grade;
    pattern.from_shape = rest_from_shape;
    start_refusal_ = scene_detail::cloth_too_short(cloth_loop_, fit_body_, body_model_->faces(), pattern);
    if (start_refusal_.empty()) start_refusal_ = scene_detail::cloth_far_longer_than_shape(cloth_loop_, placed_loop_, pattern);
    shape_note_ = scene_detail::shape_larger_than_cloth(cloth_loop_, placed_loop_, pattern);
  }
  // A cloth whose rest shape is the mesh as given (material_space: rest)
  // is made through itself where that mesh passes through itself: the
  // self-contact leaves pairs near each other at rest alone, so they cross
  // freely (an outside check's mesh crossing itself at 33 edges "settled" at
  // 58, exit 0). Dressing untangles the start, not the cloth's rest shape.
  if (start_refusal_.empty() && rest_from_shape) {
    const auto crossed = geometry::self_edge_crossings(undressed_, garment_->mesh.faces, 1000);
    if (!crossed.empty()) {
      std::vector<int> where;
      for (const auto& [edge, face] : crossed) where.push_back(edge.first), where.push_back(edge.second);
      start_refusal_ = "simulate: the garment's mesh passes through itself: " + std::to_string(crossed.size()) +
                       (crossed.size() >= 1000 ? " or more" : "") + " of its edges through its own faces (" +
                       scene_detail::describe_region(undressed_, where) +
                       "), and with material_space: rest that mesh is the cloth at rest, so the cloth would be made "
                       "crossed there; give a mesh that does not cross itself, or UVs for its material space";
    }
  }
  const Params solver(scene_solver_specs(), scene_.solver, "solver");
  morph_steps_ = static_cast<int>(solver.get_int("morph_steps"));
  settle_steps_ = static_cast<int>(solver.get_int("settle_steps"));
  morph_newton_ = static_cast<int>(solver.get_int("morph_newton_iterations"));
  morph_carry_ = morph_carry(solver, scene_);  // checked here, before anything is simulated
  settle_check_ = solver.get_string("settle_check");
  pose_path_ = pose_path_named(solver.get_string("pose_path"));
  target_pose_ = scene_pose(scene_, *body_model_);
  const auto g = solver.get_float_list("gravity_direction");
  gravity_direction_ = Eigen::Vector3d(g[0], g[1], g[2]);
  if (!(gravity_direction_.norm() > 0)) throw ConfigError({scene_.file, 0}, "solver: gravity_direction must not be zero");
  gravity_direction_.normalize();
}

Simulation::~Simulation() = default;

void Simulation::rethrow_with_offset_hint(const ConfigError& refused, const SimulationOptions& options) const {
  // Only for the scene's own start (the garment dressed on its fit body),
  // and not for a garment too small to go around it (start_fit_hint's case:
  // no translation clears it, and the search would cost seconds for nothing).
  if (options.start_garment || options.start_body || garment_ease(placed_loop_, fit_body_, body_model_->faces()) < 0)
    throw refused;
  const std::string hint = scene_detail::clear_offset_hint(*garment_, undressed_, fit_body_, body_model_->faces());
  if (hint.empty()) throw refused;
  throw ConfigError(std::string(refused.what()) + "; " + hint);
}

bool Simulation::stretches() const {
  for (std::size_t i = 0; i < scene_.effects.size(); ++i)
    if (scene_.effects[i].name == "stretching" && effect_params_[i].get_float("stiffness_scale") > 0.0) return true;
  return false;
}

std::vector<std::string> Simulation::effect_notes() const {
  std::vector<std::string> notes = material_notes_;
  // A scene may leave effects out (docs/scenes.md), but two of them are what
  // makes a drape: without stretching the cloth has no in-plane stiffness and
  // a step's Newton iterations need not end (such a run sat at its first
  // step for minutes); without contact it falls through the body.
  if (!scene_.has_effect("stretching"))
    notes.push_back("the scene has no stretching effect: the cloth resists no stretch, so a step may never settle "
                    "(each takes up to its Newton iterations)");
  for (std::size_t i = 0; i < scene_.effects.size(); ++i)
    if (scene_.effects[i].name == "stretching" && effect_params_[i].get_float("stiffness_scale") == 0.0)
      notes.push_back("the stretching effect's stiffness_scale is 0: the cloth resists no stretch, so a step may never "
                      "settle (each takes up to its Newton iterations)");
  const bool barrier = scene_.has_effect("barrier");
  // A barrier set far below its defaults leaves the morph little room: a
  // blocked morph said "nothing in the scene stands out" of an outside
  // check's distance 1e-5 m and stiffness 1e-3 Pa, both in range.
  for (std::size_t i = 0; i < scene_.effects.size(); ++i) {
    if (scene_.effects[i].name != "barrier") continue;
    for (const ParamSpec& spec : barrier_param_specs("")) {
      if (spec.name == "min_separation") continue;
      const double value = effect_params_[i].get_float(spec.name), usual = std::stod(spec.default_value);
      if (!(value < 0.1 * usual)) continue;
      char note[300];
      std::snprintf(note, sizeof note,
                    "the barrier's %s is %g, under a tenth of its default %g: %s", spec.name.c_str(), value, usual,
                    spec.name == "distance" ? "the cloth is pushed off the body only within that gap, so the body's growth "
                                              "meets it before it can move"
                                            : "its push is so weak that the body's growth presses into the cloth before "
                                              "it gives way");
      notes.emplace_back(note);
    }
  }
  if (!barrier && !scene_.has_effect("collision"))
    notes.push_back("the scene has no contact with the body (barrier or collision): the garment falls through it");
  // A material's thickness is kept with it (ArcSim's format has the key) but
  // no effect reads it: an outside check's ten times thicker shirt draped bit
  // for bit as the default, without a word.
  for (const SceneMaterial& m : scene_.materials) {
    const bool sets = m.spec.IsMap() && (m.spec["thickness"] || (m.spec["multipliers"].IsMap() && m.spec["multipliers"]["thickness"]));
    if (sets)
      notes.push_back("materials: " + m.region + "'s thickness is kept with the material, but no effect reads it: the "
                      "cloth's distances are the barrier's distance (off the body) and self_contact's thickness (off "
                      "itself), set on those effects (docs/materials.md)");
  }
  // A penalty contact of no stiffness or no margin keeps nothing out (an
  // outside check's margin 0 "settled" with a third of the garment inside).
  for (std::size_t i = 0; i < scene_.effects.size() && !barrier; ++i) {
    if (scene_.effects[i].name != "collision") continue;
    for (const char* zero : {"stiffness", "margin"})
      if (effect_params_[i].get_float(zero) == 0.0)
        notes.push_back(std::string("the collision effect's ") + zero +
                        " is 0 and the scene has no barrier: nothing keeps the garment out of the body");
  }
  return notes;
}

SolverSettings Simulation::solver_settings() const {
  const Params p(scene_solver_specs(), scene_.solver, "solver");
  SolverSettings s;
  s.time_step = p.get_float("time_step");
  s.damping = p.get_float("damping");
  s.max_newton_iterations = static_cast<int>(p.get_int("max_newton_iterations"));
  s.tolerance = p.get_float("tolerance");
  s.settle_tolerance = p.get_float("settle_tolerance");
  s.max_displacement = p.get_float("max_displacement");
  s.rest_displacement = p.get_float("rest_displacement");
  s.kink_tolerance = p.get_float("kink_tolerance");
  s.kink_radius = p.get_float("kink_radius");
  s.linear_solver = p.get_string("linear_solver");
  s.reuse_factorization = p.get_bool("reuse_factorization");
  s.float_preconditioner = p.get_string("preconditioner") == "float";
  s.newton_forcing = p.get_float("newton_forcing");
  s.max_cg_iterations = static_cast<int>(p.get_int("max_cg_iterations"));
  s.exact_hessian_below = p.get_float("exact_hessian_below");
  s.adaptive_tries = p.get_bool("adaptive_tries");
  return s;
}

Eigen::VectorXd Simulation::shape_for(const BodyRequest& request) const { return body_model_->solve(request); }

BodyRequest Simulation::target_request() const {
  const Params p(scene_shape_specs(), scene_.shape, "body shape");
  BodyRequest r;
  r.bmi = p.get_float("bmi");
  r.height = p.get_float("height");
  r.sex = p.get_float("sex");
  return r;
}

Eigen::VectorXd Simulation::target_shape() const { return shape_for(target_request()); }

Eigen::MatrixX3d Simulation::body_vertices(const Eigen::VectorXd& shape) const { return body_model_->vertices(shape); }

std::vector<NamedEnergy> Simulation::make_energies(const BodyQuery* body, const BodyQuery* step_bounding_body) const {
  EnergyContext context;
  context.garment = garment_.get();
  context.gravity = gravity_direction_ * 9.81;
  std::vector<NamedEnergy> energies;
  for (std::size_t i = 0; i < scene_.effects.size(); ++i) {
    const std::string& name = scene_.effects[i].name;
    auto e = registry_.create_energy(name, effect_params_[i]);
    context.body = e->bounds_steps() && step_bounding_body ? step_bounding_body : body;
    if (e->needs_body() && !context.body)
      throw ConfigError(scene_.effects[i].where, "effect '" + name + "' needs a body and none was given");
    try {
      e->bind(context);
    } catch (...) {
      rethrow_at(scene_.effects[i].where, name);  // a setting the plugin refuses once it sees the garment
    }
    energies.push_back({name, std::move(e)});
  }
  return energies;
}

std::function<Eigen::MatrixX3d(double)> Simulation::body_path(const SimulationOptions& options,
                                                              const Eigen::MatrixX3d& morph_from,
                                                              const Eigen::MatrixX3d& target_body) const {
  if (!options.target_pose || options.target_pose->empty())
    return [&morph_from, &target_body](double t) -> Eigen::MatrixX3d { return morph_from + t * (target_body - morph_from); };
  const Eigen::MatrixX3d& unposed = *options.unposed_target;
  require_vertex_count(unposed.rows(), mean_body_.rows(), "the unposed target body",
                       "the scene's body model '" + scene_.body_model + "'");
  // The path must end on the body asked for: the pose of that unposed body.
  const Eigen::MatrixX3d end = body_model_->posed_vertices(unposed, *options.target_pose, 1.0);
  const double off = (end - target_body).rowwise().norm().maxCoeff();
  if (!(off <= 1e-9))
    throw ConfigError("the posed target body is not the unposed target in its pose (" + std::to_string(off) +
                      " m apart): pose it with BodyModel::posed_vertices");
  // The start shape's offset from the body model's rest (a shrunk start,
  // separated_start.hpp) is part of the shape morph; the joints turn from
  // the start body's own rest angles (posed_vertices' fraction).
  const Pose& pose = *options.target_pose;
  return [this, &morph_from, &unposed, &pose](double t) -> Eigen::MatrixX3d {
    const MorphFractions f = morph_fractions(pose_path_, t);
    return body_model_->posed_vertices(morph_from + f.shape * (unposed - morph_from), pose, f.pose);
  };
}

SimulationResult Simulation::run(const Eigen::MatrixX3d& target_body, const SimulationOptions& options) const {
  const auto start = Clock::now();
  require_vertex_count(target_body.rows(), mean_body_.rows(), "the target body",
                       "the scene's body model '" + scene_.body_model + "'");
  check_body_units(target_body, "the target body");
  if (options.start_body) check_body_units(*options.start_body, "the start body");
  if (!options.start_garment && !options.start_body && !start_refusal_.empty()) throw ConfigError(start_refusal_);
  // Cloth with no in-plane stiffness cannot be carried by a body growing
  // under the barrier: each morph step is cut into partial moves that make
  // almost no headway (an outside check's run sat at morph step 3 of 20
  // after 3 minutes, its ETA 3 h 35 min). Refused before any work.
  if (morph_steps_ > 0 && scene_.has_effect("barrier") && !stretches()) {
    // At the stretching effect's line when it is there with stiffness_scale
    // 0, else at the barrier's (the refusal named the file alone).
    SourceLocation where{scene_.file, 0};
    for (const SceneEffect& e : scene_.effects)
      if (e.name == "barrier" && where.line == 0) where = e.where;
    for (const SceneEffect& e : scene_.effects)
      if (e.name == "stretching") where = e.where;
    throw ConfigError(where, "the cloth has no stretching (the effect is missing, or its stiffness_scale is 0), "
                                        "so the barrier cannot carry it as the body morphs: the run would crawl for "
                                        "hours; give the scene `stretching: {}` (a stiffness_scale above 0)");
  }
  const Eigen::MatrixX3d& body_start = options.start_body ? *options.start_body : fit_body_;
  const Eigen::MatrixX3d& garment_start = options.start_garment ? *options.start_garment : garment_->mesh.vertices;
  if (body_start.rows() != mean_body_.rows() || garment_start.rows() != garment_->mesh.vertices.rows())
    throw ConfigError("simulation start state has the wrong vertex count");
  if (!options.target_pose != !options.unposed_target)
    throw ConfigError("a posed target needs both the pose and the unposed body (SimulationOptions)");

  // The body's closest-point structure exists only when an effect needs it.
  std::unique_ptr<geometry::BodySurface> surface;
  if (needs_body_) {
    surface = std::make_unique<geometry::BodySurface>(morph_steps_ > 0 ? body_start : target_body, body_model_->faces());
    // A body that passes through itself under the garment has no inside
    // there (body_overlap.hpp): refused, naming the place.
    const std::string overlap = scene_detail::body_overlap_near_garment(*surface, target_body, garment_start, kGarmentReach);
    if (!overlap.empty()) throw ConfigError(overlap);
  }
  std::vector<NamedEnergy> energies = make_energies(surface.get());
  ClothSolver solver(*garment_, energies, solver_settings());

  SimulationResult result;
  Eigen::MatrixX3d x = garment_start;
  Eigen::MatrixX3d v = Eigen::MatrixX3d::Zero(x.rows(), 3);
  const StepRecorder record{result, options, morph_steps_ + settle_steps_};
  // While the body morphs each step only has to follow it approximately; the
  // settling steps get the full Newton budget.
  const int settle_newton = solver.settings().max_newton_iterations;
  solver.set_max_newton_iterations(std::min(settle_newton, morph_newton_));
  // A body barrier: a step-bounding energy on the body (self_contact bounds
  // steps too, but of the cloth against itself: the solver's line search
  // checks it, and it needs no separated start body).
  const bool barrier = std::any_of(energies.begin(), energies.end(), [](const NamedEnergy& e) {
    return e.energy->bounds_steps() && e.energy->needs_body();
  });
  // The morph starts from a body the garment is separated from (shrunk when
  // the dressed start cuts through it); without morph steps the target itself
  // must be separated.
  Eigen::MatrixX3d separated_body;
  try {  // a start refused: with the offset that would clear it, when there is one
    // A garment placed through the body went on inside out where it passed
    // through (its panel pushed out of the body's far side), whatever the contact.
    if (!placed_through_.empty() && !options.start_garment) {
      char depth[32];
      std::snprintf(depth, sizeof depth, "%.1f", 100 * placed_through_depth_);
      throw ConfigError("simulate: the garment is placed through the body: " +
                        scene_detail::describe_region(undressed_, placed_through_) + " lie up to " + depth +
                        " cm inside it with their cloth facing the other way, so dressing would push them out through "
                        "the body's far side and the garment would start inside out there (a panel pushed out in front "
                        "of or behind the torso drapes as an apron or falls off); it must be placed around the body it "
                        "is dressed on, in the body model's frame");
    }
    // (After: a garment through the body there is said so, where it is.)
    if (!beside_body_.empty() && !options.start_garment)
      throw ConfigError("simulate: the garment does not go around the body: " + beside_body_ +
                        "; dressing cannot bring it round, and its drape would hang beside the body as an apron or "
                        "fall off: it must be placed around the body it is dressed on, in the body model's frame "
                        "(metres, Y up, facing +Z)");
    if (barrier && morph_steps_ > 0) {
      // A start a little inside the body is rescued by shrinking the start
      // body along its normals (by a few centimetres at most) until the garment
      // is clear of it; the morph then grows it to the target under the
      // barrier. A start that cuts through the body is refused, naming where.
      separated_body = scene_detail::separated_start_body(x, body_start, body_model_->faces(), garment_->mesh.faces,
                                                          &result.start_shrink);
      surface->update(separated_body);
    } else if (barrier) {
      scene_detail::check_separated_start(x, *surface, garment_->mesh.faces, /*morphs=*/false);
    }
  } catch (const ConfigError& e) {
    rethrow_with_offset_hint(e, options);
  }
  const Eigen::MatrixX3d& morph_from = separated_body.rows() ? separated_body : body_start;
  const std::function<Eigen::MatrixX3d(double)> body_at = body_path(options, morph_from, target_body);
  scene_detail::BarrierMorph barrier_morph;
  barrier_morph.morph_newton = std::min(settle_newton, morph_newton_);
  barrier_morph.settle_newton = settle_newton;
  std::tie(barrier_morph.carry_inner, barrier_morph.carry_outer) = morph_carry_;
  for (int k = 1; k <= morph_steps_; ++k) {
    if (options.on_partial_move)
      barrier_morph.on_partial_move = [&, k](int moves, double done) {
        options.on_partial_move(k, morph_steps_ + settle_steps_, moves, done);
      };
    const double t = static_cast<double>(k) / morph_steps_;
    const Eigen::MatrixX3d next = body_at(t);
    if (barrier) {
      // The body's move is checked too (barrier_morph.hpp).
      try {
        record(k, true, scene_detail::barrier_morph_step(solver, *surface, next, k, barrier_morph, x, v, result), -1);
      } catch (const scene_detail::MorphBlocked& blocked) {
        throw Error(scene_detail::why_morph_blocked(blocked, morph_steps_, *garment_, cloth_loop_, surface->vertices(),
                                                    body_model_->faces(), solver.settings(), sized_, effect_notes()));
      }
    } else {
      if (surface) surface->update(next);
      record(k, true, solver.step(x, v), -1);
    }
  }
  if (surface && morph_steps_ > 0) {
    surface->update(target_body);
    surface->rebuild();  // the hierarchy was built on the start shape
  }
  solver.set_max_newton_iterations(settle_newton);
  settle(solver, x, v, target_body, morph_steps_, settle_steps_, settle_check_ == "iteration", record, result);
  measure_drape(solver, energies, x, target_body, garment_->mesh, mean_body_, body_model_->faces(), morph_steps_, sized_,
                options, surface, result);
  result.seconds = since(start);
  return result;
}

std::unique_ptr<BodyModel> make_scene_body_model(const Registry& registry, const Scene& scene) {
  const PluginDescriptor& bd = registry.get(scene.body_model);
  return registry.create_body(scene.body_model, Params(bd.params, scene.body_params, "body '" + scene.body_model + "'"));
}

}  // namespace drape
