// `drape simulate scene.yaml --out garment.obj`: drape the scene's garment on
// its body (or on --body FILE), the body morphing from the mean shape.
#include "command.hpp"
#include "model_body.hpp"
#include "pose_options.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <drape/bodies/pose.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/progress.hpp>
#include <drape/registry.hpp>
#include <drape/scene/rode_up.hpp>
#include <drape/services/scene_body.hpp>
#include <drape/io/svg_figure.hpp>

#include <algorithm>
#include <functional>
#include <cstdio>
#include <iostream>
#include <memory>
#include <numeric>
#include <optional>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

// Overrides of the scene's target shape from the command line.
void override_shape(Scene& scene, const po::variables_map& vm) {
  for (const char* key : {"bmi", "height", "sex"})
    if (vm.count(key)) scene.shape[key] = ParamValue{YAML::Node(vm[key].as<double>()), {"command line", 0}};
}

// "surface crossings 106 garment edges / 257 body edges": where the surfaces
// cross with no vertex inside, which p does not see.
std::string crossings_summary(const SimulationResult& r) {
  if (!r.crossings) return "surface crossings not measured";
  return "surface crossings " + std::to_string(r.crossings->garment_edges_through_body) + " garment edges / " +
         std::to_string(r.crossings->body_edges_through_garment) + " body edges" +
         (r.self_crossings ? ", the garment through itself " + std::to_string(*r.self_crossings) + " edge-face pairs" : "");
}

// The command line: every option, parsed into vm; false after --help.
bool parse_simulate(const std::vector<std::string>& args, po::variables_map& vm) {
  po::options_description opts("drape simulate");
  opts.add_options()("scene", po::value<std::string>(), "scene file (graphs/scenes/*.yaml)")(
      "out", po::value<std::string>(), "draped garment mesh to write (.obj, .ply, .gltf, .glb)")(
      "body", po::value<std::string>(), "drape on this body mesh (the scene body model's topology) instead")(
      "body-out", po::value<std::string>(), "also write the target body mesh")(
      "svg", po::value<std::string>(), "also draw the drape, the garment coloured by its distance to the body (.svg: front view; .html: a 3D viewer)")(
      "bmi", po::value<double>(), "override the scene's target BMI")("height", po::value<double>(), "override the height, m")(
      "sex", po::value<double>(), "override the sex (0 female ... 1 male)")(
      "pose", po::value<std::string>(), "pose the target body instead of the scene's pose: name=degrees,... (docs/poses.md)")(
      "pose-file", po::value<std::string>(), "the same from a YAML map of joint angle names to degrees")(
      "smpl-theta", po::value<std::string>(), "the same as SMPL's theta, 72 or 69 radians (text or .npy; docs/smpl.md)")(
      "verbose,v", po::bool_switch(), "print every solver step")(
      "threads", po::value<int>()->default_value(0), "threads for the energies (0: OpenMP's default, all cores)");
  add_girth_option(opts, "of the scene's target body: ");
  po::positional_options_description pos;
  pos.add("scene", 1);
  const std::string usage =
      "drape simulate SCENE.yaml [--out garment.obj] [--body body.obj | --bmi 35 [--girth belly=0.1]] "
      "[--pose shoulder_abduction=20,elbow_flexion=30] [--threads T] [--verbose]";
  return parse(usage, args, opts, pos, vm);
}

// The body asked for: --body FILE, or the scene's target body changed by
// --bmi/--height/--sex/--girth (services/scene_body.hpp).
// --pose, --pose-file or --smpl-theta replace the scene's pose (a given body
// is taken as unposed and posed too); none: the scene's own (null).
SceneBody target_body(const SceneSimulations& simulations, const Scene& scene, const po::variables_map& vm) {
  const Simulation& design = simulations.design();
  const std::optional<Pose> pose = pose_options(vm, design.body_model(), design.scene().body_model);
  const Pose* posed = pose ? &*pose : nullptr;
  if (vm.count("body")) {
    const std::string file = vm["body"].as<std::string>();
    const Mesh given = read_mesh(file);
    return scene_body(simulations, given.vertices, file, posed, &given.faces);
  }
  BodyRequest request = simulations.design().target_request();
  request.proportions = parse_girths(vm);
  return scene_body(simulations, request, scene.file, posed);
}

// Without --verbose a bar over the steps (at most morph + settle; the
// settling ends early when the drape has settled) with the latest step's
// Newton iterations and balance, redrawn on a terminal; with it, a line per step.
std::function<void(const SimulationStep&)> step_printer(bool verbose, std::unique_ptr<ProgressBar>& bar) {
  if (!verbose)
    return [&bar](const SimulationStep& s) {
      if (!bar) bar = std::make_unique<ProgressBar>("simulate", static_cast<std::size_t>(s.total_steps));
      char status[96];
      if (s.stationarity >= 0)
        std::snprintf(status, sizeof status, "settling, %d Newton iterations, stationarity %.2e", s.report.iterations, s.stationarity);
      else
        std::snprintf(status, sizeof status, "morphing, %d Newton iterations", s.report.iterations);
      bar->set_status(status);
      bar->advance();
    };
  return [](const SimulationStep& s) {
    std::printf("step %3d/%d %-7s newton %2d  residual %.2e  Phi %.6g -> %.6g%s%s\n", s.step, s.total_steps,
                s.morphing ? "morph" : "settle", s.report.iterations, s.report.residual, s.report.phi_start,
                s.report.phi_end, s.stationarity >= 0 ? ("  stationarity/|W| " + std::to_string(s.stationarity)).c_str() : "",
                s.slip_ratio > 0 ? ("  slip/held " + std::to_string(s.slip_ratio)).c_str() : "");
  };
}

// A morph step the contact cuts into partial moves can take minutes: the
// bar's status (or, with --verbose, a line every 8 moves) says how far it is.
std::function<void(int, int, int, double)> partial_move_printer(bool verbose, std::unique_ptr<ProgressBar>& bar) {
  if (!verbose)
    return [&bar](int step, int total_steps, int moves, double done) {
      if (!bar) bar = std::make_unique<ProgressBar>("simulate", static_cast<std::size_t>(total_steps));
      char status[120];
      std::snprintf(status, sizeof status, "morph step %d: %d partial moves, the body %.1f %% of the step's way", step,
                    moves, 100.0 * done);
      bar->set_status(status);
    };
  return [](int step, int, int moves, double done) {
    if (moves % 8 == 0)
      std::printf("step %3d: %d partial moves, the body %.1f %% of the step's way\n", step, moves, 100.0 * done);
  };
}

// Whether it settled, its energies, balance, contact and where the time went.
void print_result(const SimulationResult& r) {
  // Settled at rest above the settle tolerance (within the kink tolerance) is
  // said with both figures: a user who asked for a tighter settle_tolerance
  // was told "settled" with 600 times it (an outside check).
  char status[200];
  if (r.converged && r.at_rest && r.stationarity > r.settle_tolerance)
    std::snprintf(status, sizeof status,
                  "settled (at rest: stationarity %.2e is above settle_tolerance %.2e, within kink_tolerance %.2e)",
                  r.stationarity, r.settle_tolerance, r.rest_tolerance);
  else
    std::snprintf(status, sizeof status, "%s", r.converged ? (r.at_rest ? "settled (at rest)" : "settled") : "NOT settled");
  std::printf("%s after %d steps, %d Newton iterations (%d line-search stops), %s Cholesky\n", status, r.steps, r.iterations,
              r.line_search_failures, r.linear_solver.c_str());
  if (!r.unsettled.empty()) std::printf("why: %s\n", r.unsettled.c_str());
  if (r.start_shrink > 0 || r.morph_substeps > 0)
    std::printf("barrier contact: start body shrunk by %.1f cm to separate it from the garment, %d morph steps cut short\n",
                100.0 * r.start_shrink, r.morph_substeps);
  std::printf("  %-12s %14s\n", "energy", "J");
  // (+ 0.0: an energy of -0, gravity with g = 0, printed as 0)
  for (const auto& t : r.energies) std::printf("  %-12s %14.6g\n", t.name.c_str(), t.value + 0.0);
  std::printf("  %-12s %14.6g\n", "total", r.total_energy + 0.0);
  std::printf("residual |grad E|/|weight| = %.2e (stationarity %.2e), penetration p = %.3f%% of garment vertices, %s, time %.2f s\n",
              r.residual, r.stationarity,
              100.0 * r.penetration, crossings_summary(r).c_str(), r.seconds);
  // The collision checks run inside the line search and while the morph moves the body.
  std::printf("time split: gradient %.2f s, hessian %.2f s, assembly %.2f s, linear solves %.2f s (%d factorisations, "
              "%ld PCG iterations in %d solves, %d of them stopped at the cap, %d skipped after failures; "
              "%d Newton steps on the exact matrix, %d found it indefinite, %d not tried after a refusal), "
              "line search %.2f s (%ld trials), collision checks %.2f s\n",
              r.timings.gradient, r.timings.hessian, r.timings.assembly, r.timings.linear_solves, r.timings.factorizations,
              r.timings.cg_iterations, r.timings.cg_attempts, r.timings.cg_failures, r.timings.cg_skipped,
              r.timings.exact_steps, r.timings.exact_refused, r.timings.exact_skipped, r.timings.line_search,
              r.timings.line_search_trials, r.timings.collision_checks);
}

// --verbose: where the drape is out of balance (the vertices with the largest
// unbalanced forces) and where the surfaces cross.
void print_imbalance(const SimulationResult& r) {
  std::vector<int> order(r.vertex_force.size());
  std::iota(order.begin(), order.end(), 0);
  const int shown = std::min<int>(8, static_cast<int>(order.size()));
  std::partial_sort(order.begin(), order.begin() + shown, order.end(),
                    [&](int a, int b) { return r.vertex_force[a] > r.vertex_force[b]; });
  std::printf("largest unbalanced forces (vertex, N, position m, distance to the body m):\n");
  for (int k = 0; k < shown; ++k) {
    const int i = order[k];
    std::printf("  %5d  %.3e  (%+.3f %+.3f %+.3f)  %s\n", i, r.vertex_force[i], r.garment(i, 0), r.garment(i, 1),
                r.garment(i, 2), r.body_distance.size() ? std::to_string(r.body_distance[i]).c_str() : "-");
  }
  if (r.crossings && !r.crossings->garment_vertices.empty()) {
    // A few of the garment vertices there, to look up in the mesh.
    const std::vector<int>& at = r.crossings->garment_vertices;
    std::printf("garment vertices at surface crossings: %zu (", at.size());
    for (std::size_t k = 0; k < std::min<std::size_t>(12, at.size()); ++k) std::printf("%s%d", k ? " " : "", at[k]);
    std::printf("%s)\n", at.size() > 12 ? " ..." : "");
  }
}

// --out, --body-out and --svg, where the given body stood.
// `notes`: what the run printed about its body and garment, drawn on the picture too.
void write_outputs(const po::variables_map& vm, const Simulation& sim, const SimulationResult& r,
                   const std::vector<std::string>& notes) {
  Mesh garment = sim.garment().mesh;
  garment.vertices = r.garment;
  if (vm.count("out")) {
    write_mesh(vm["out"].as<std::string>(), garment);
    std::printf("wrote %s\n", vm["out"].as<std::string>().c_str());
  }
  Mesh body;
  body.vertices = r.body;
  body.faces = sim.body_model().faces();
  if (vm.count("body-out")) {
    write_mesh(vm["body-out"].as<std::string>(), body);
    std::printf("wrote %s\n", vm["body-out"].as<std::string>().c_str());
  }
  if (vm.count("svg")) {
    char caption[160];
    std::snprintf(caption, sizeof caption, "%s, %d iterations, %.1f s, p = %.2f%%, %d surface crossings",
                  r.converged ? "settled" : "NOT settled", r.iterations, r.seconds, 100.0 * r.penetration,
                  r.crossings ? r.crossings->total() : -1);
    // Which body, as predict's picture says it (the title was the scene alone, and the fit note only on the terminal).
    const std::string which = vm.count("bmi") || vm.count("body") ? asked_body_words(vm) : "the scene's own body";
    SvgFigure figure = drape_figure("drape simulate: " + vm["scene"].as<std::string>() + " on " + which, caption, body, garment);
    for (const std::string& note : notes) figure.add_note(note);
    figure.write(vm["svg"].as<std::string>());
    std::printf("wrote %s\n", vm["svg"].as<std::string>().c_str());
  }
}

int run(const std::vector<std::string>& args) {
  po::variables_map vm;
  if (!parse_simulate(args, vm)) return 0;
  const int threads = vm["threads"].as<int>();
  if (threads < 0) throw UsageError("--threads: expected 0 (all cores) or a count");
#ifdef _OPENMP
  if (threads > 0) omp_set_num_threads(threads);
#endif
  check_mesh_outputs(vm, {"out", "body-out"});
  if (!vm.count("scene")) throw UsageError("a scene file is required, e.g. graphs/scenes/tshirt.yaml");
  if (vm.count("body") && (vm.count("bmi") || vm.count("height") || vm.count("sex") || vm.count("girth")))
    throw UsageError("--body gives the body itself: drop --bmi/--height/--sex/--girth");

  Registry& registry = Registry::load_default(plugin_path(vm));
  Scene scene = load_scene(find_input_file(vm["scene"].as<std::string>()));  // graphs/scenes/... from anywhere
  override_shape(scene, vm);
  // size: auto -- every size is built once (SizeChart); the body comes from
  // the design size's, then runs in the size its girth needs (garment_size.hpp).
  const SceneSimulations simulations(registry, scene);
  const SceneBody target = target_body(simulations, scene, vm);
  std::vector<std::string> notes;  // (each printed, and drawn on --svg's picture)
  for (const std::string& note : target.notes) notes.push_back("note: " + note);
  if (target.size) notes.push_back("size auto: " + target.size->summary());
  if (target.grade) notes.push_back("grade auto: " + target.grade->summary());
  if (!target.pose.empty()) notes.push_back("posed: " + format_pose(target.pose) + "; every other angle at rest");
  for (const std::string& note : notes) std::printf("%s\n", note.c_str());
  const Simulation& sim = *target.simulation;

  const bool verbose = vm["verbose"].as<bool>();
  SimulationOptions options;
  std::unique_ptr<ProgressBar> bar;
  options.on_step = step_printer(verbose, bar);
  options.on_partial_move = partial_move_printer(verbose, bar);
  std::printf("simulating %s: garment %d vertices, body %d vertices, effects:", sim.scene().file.c_str(),
              sim.garment().mesh.num_vertices(), static_cast<int>(target.vertices.rows()));
  for (const auto& e : sim.scene().effects) std::printf(" %s", e.name.c_str());
  std::printf("\n");
  for (const std::string& note : sim.effect_notes()) {
    std::printf("note: %s\n", note.c_str());
    notes.push_back("note: " + note);
  }
  // A garment far finer than the shipped ones: its first step alone can take
  // minutes, with nothing on the screen until then (a 244,606-vertex shirt
  // looked hung); say what to expect.
  constexpr int kLargeGarment = 20000;
  if (const int n = sim.garment().mesh.num_vertices(); n > kLargeGarment)
    std::printf("note: %d garment vertices, %.0f times the default shirt's 3,505 (a drape of which takes 1-2 CPU minutes; "
                "of 14,013 vertices, 11): each step may take minutes, and the bar moves once a step\n",
                n, n / 3505.0);
  const SimulationResult r = drape_scene_body(target, options);  // moved back where the given body stood
  if (bar) bar->finish();
  print_result(r);
  // (a garment far smaller round than the body settles as a band round the chest, p = 0)
  if (const std::string note = garment_rode_up(sim.garment().mesh.vertices, r.garment); !note.empty()) {
    std::printf("note: %s\n", note.c_str());
    notes.push_back("note: " + note);
  }
  if (verbose) print_imbalance(r);
  write_outputs(vm, sim, r, notes);
  return r.converged ? 0 : 1;
}

const RegisterCommand registered{{"simulate", "drape a garment on a body by cloth simulation (a scene file)", run}};

}  // namespace
}  // namespace drape::cli
