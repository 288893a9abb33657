// `drape bench simulate`: what a drape costs on one core. (1) Whole drapes of
// the default and the coarse T-shirt. (2) One solver iteration with every
// effect, then with each effect removed in turn, and with each linear solver:
// an effect the scene does not name costs nothing, because nothing of it is
// built (its energy, the body's closest-point hierarchy for collision).
#include "bench.hpp"

#include <drape/io/shipped_files.hpp>

#include <drape/bodies/posed_body.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/registry.hpp>
#include <drape/scene/simulation.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

// CPU seconds of the process, not the wall clock: on a shared machine the
// wall clock counted other users' load (an outside check's table had an
// effect "cost" -44 ms: removing it looked slower, by 59 %). With one thread
// (the default) it is the time on one core.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double since(double start) { return cpu_seconds() - start; }

struct Row {
  std::string config;
  double ms = 0;  // best per iteration
  double relative = 0;
};

// The scene's energies bound to `body` (and the body structure they query,
// built only when an effect needs it).
struct BoundEnergies {
  std::unique_ptr<geometry::BodySurface> surface;
  std::vector<NamedEnergy> energies;
  BoundEnergies(const Simulation& sim, const Eigen::MatrixX3d& body) {
    if (sim.needs_body()) surface = std::make_unique<geometry::BodySurface>(body, sim.body_model().faces());
    energies = sim.make_energies(surface.get());
  }
};

// Best time of one Newton iteration of a fresh step from (x, v) on `body`.
double iteration_ms(const Simulation& sim, const Eigen::MatrixX3d& body, const Eigen::MatrixX3d& x0, int repeats,
                    const std::string& linear_solver) {
  BoundEnergies bound(sim, body);
  SolverSettings settings = sim.solver_settings();
  settings.max_newton_iterations = 1;
  settings.tolerance = 0;  // always iterate
  settings.linear_solver = linear_solver;
  // Every configuration factorises its own Newton matrix: with the factor
  // kept, an iteration's cost would depend on how far the configuration's
  // first PCG solve happens to get, not on the effects it evaluates.
  settings.reuse_factorization = false;
  // And the projected matrix alone: from a settled drape an iteration would
  // otherwise first try the exact one (solver.hpp), a second assembly and
  // factorisation whenever it is indefinite.
  settings.exact_hessian_below = 0;
  ClothSolver solver(sim.garment(), bound.energies, settings);
  double best = 1e300;
  for (int r = 0; r < repeats + 1; ++r) {  // the first run also analyses the pattern: not counted
    Eigen::MatrixX3d x = x0, v = Eigen::MatrixX3d::Zero(x0.rows(), 3);
    const double t = cpu_seconds();
    solver.step(x, v);
    if (r > 0) best = std::min(best, since(t));
  }
  return best * 1e3;
}

// Best time to evaluate what the scene's effects contribute to one Newton
// iteration: the energy with its gradient, then the lower Hessian's triplets.
// This part depends only on which effects are built, not on where the solver
// goes next, so it shows what each one costs. The drape alternates with a
// copy moved by 0.1 um, so that no evaluation is served from the collision's
// cache of the last x.
double evaluation_ms(const Simulation& sim, const Eigen::MatrixX3d& body, const Eigen::MatrixX3d& x0, int repeats) {
  BoundEnergies bound(sim, body);
  const Eigen::MatrixX3d x1 = x0.array() + 1e-7;
  Eigen::MatrixX3d g(x0.rows(), 3);
  Triplets h;
  double best = 1e300, sink = 0;
  for (int r = 0; r < 2 * repeats + 1; ++r) {  // the first run fills caches and allocations: not counted
    const Eigen::MatrixX3d& x = r % 2 ? x1 : x0;
    const double t = cpu_seconds();
    g.setZero();
    h.clear();
    for (NamedEnergy& e : bound.energies) {
      sink += e.energy->add_gradient(x, g);
      e.energy->add_hessian_lower(x, h);
    }
    if (r > 0) best = std::min(best, since(t));
  }
  if (!std::isfinite(sink)) std::printf("(a non-finite energy in the evaluation benchmark)\n");
  return best * 1e3;
}

Scene without(const Scene& scene, const std::string& effect) {
  Scene s = scene;
  s.effects.erase(std::remove_if(s.effects.begin(), s.effects.end(), [&](const SceneEffect& e) { return e.name == effect; }),
                  s.effects.end());
  return s;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench simulate");
  opts.add_options()("scene", po::value<std::string>()->default_value("graphs/scenes/tshirt.yaml"), "scene of the full drape")(
      "coarse-scene", po::value<std::string>()->default_value("graphs/scenes/tshirt_coarse.yaml"), "scene of the coarse drape ('' to skip)")(
      "bmi", po::value<double>()->default_value(35), "target BMI of the drapes")(
      "repeats", po::value<int>()->default_value(5), "iterations timed per configuration (best shown)")(
      "drape-repeats", po::value<int>()->default_value(3), "runs of each whole drape (best and median shown)")(
      "threads", po::value<int>()->default_value(1), "OpenMP threads (figures are per core with 1)")(
      "out", po::value<std::string>(), "also write the tables as Markdown here");
  po::variables_map vm;
  if (!parse("drape bench simulate [--scene S] [--coarse-scene S] [--bmi 35] [--repeats 5] [--out bench.md]", args, opts, {},
             vm))
    return 0;
#ifdef _OPENMP
  omp_set_num_threads(count_option(vm, "threads"));
#endif
  const int repeats = count_option(vm, "repeats");
  Registry& registry = Registry::load_default(plugin_path(vm));
  std::ostringstream md;
  std::string report;  // everything printed, for --out

  // (1) Whole drapes.
  // A drape is deterministic: repeated runs differ only in how busy the machine was.
  const int drape_repeats = count_option(vm, "drape-repeats");
  md << "## Whole drapes (BMI " << vm["bmi"].as<double>() << ", " << vm["threads"].as<int>() << " thread)\n\n"
     << "| scene | garment vertices | steps | Newton iterations | settled | p (%) | CPU time (s), best of " << drape_repeats
     << " | median |\n|---|---|---|---|---|---|---|---|\n";
  Eigen::MatrixX3d body, draped;
  std::vector<std::string> scenes{find_input_file(vm["scene"].as<std::string>()).string()};
  if (!vm["coarse-scene"].as<std::string>().empty()) scenes.push_back(vm["coarse-scene"].as<std::string>());
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    Scene scene = load_scene(scenes[k]);
    scene.shape["bmi"] = ParamValue{YAML::Node(vm["bmi"].as<double>()), {"command line", 0}};
    const Simulation sim(registry, scene);
    // A posed scene's body in its pose, reached along the scene's pose path.
    const Eigen::MatrixX3d unposed = sim.body_vertices(sim.target_shape());
    const Eigen::MatrixX3d target = pose_vertices(sim.body_model(), scene.body_model, unposed, sim.target_pose());
    SimulationOptions options;
    if (!sim.target_pose().empty()) {
      options.target_pose = &sim.target_pose();
      options.unposed_target = &unposed;
    }
    SimulationResult r;
    std::vector<double> seconds;
    for (int run = 0; run < drape_repeats; ++run) {
      const double t = cpu_seconds();
      r = sim.run(target, options);
      seconds.push_back(since(t));
    }
    const BestAndMedian time = best_and_median(seconds);
    md << "| " << scenes[k] << " | " << sim.garment().mesh.num_vertices() << " | " << r.steps << " | " << r.iterations << " | "
       << (r.converged ? "yes" : "no") << " | " << 100 * r.penetration << " | " << time.best << " | " << time.median
       << " |\n";
    std::printf("%s", md.str().c_str());
    std::fflush(stdout);
    report += md.str();
    md.str("");
    md.clear();
    if (k == 0) {
      body = target;
      draped = r.garment;
    }
  }

  // (2) One iteration, on the settled default drape.
  const Scene scene = load_scene(scenes[0]);
  const Simulation all(registry, scene);
  // Each configuration: a whole iteration, and the effects' evaluation alone.
  std::vector<Row> rows, evaluations;
  const double base = iteration_ms(all, body, draped, repeats, "auto");
  const double all_effects = evaluation_ms(all, body, draped, repeats);
  rows.push_back({"all effects", base, 1});
  evaluations.push_back({"all effects", all_effects, 1});
  for (const SceneEffect& e : scene.effects) {
    if (scene.effects.size() < 2) break;  // a scene needs an effect
    const Simulation sim(registry, without(scene, e.name));
    const double ms = iteration_ms(sim, body, draped, repeats, "auto");
    rows.push_back({"without " + e.name, ms, ms / base});
    const double evaluation = evaluation_ms(sim, body, draped, repeats);
    evaluations.push_back({"without " + e.name, evaluation, evaluation / all_effects});
  }
  const double eigen = iteration_ms(all, body, draped, repeats, "eigen");
  rows.push_back({"all effects, Eigen SimplicialLLT", eigen, eigen / base});
  md << "\n## One solver iteration (" << all.garment().mesh.num_vertices() << " garment vertices, "
     << all.mean_body().rows() << " body vertices; best of " << repeats << ")\n\n"
     << "| configuration | CPU ms per iteration | relative |\n|---|---|---|\n";
  char line[256];
  for (const Row& r : rows) {
    std::snprintf(line, sizeof line, "| %s | %.1f | %.2f |\n", r.config.c_str(), r.ms, r.relative);
    md << line;
  }
  md << "\nEach iteration above factorises its own Newton matrix and runs the line search from the same drape; "
        "without an effect the drape is no longer at rest, so the search may take a different number of trials. "
        "What the effects themselves cost per iteration (energy, gradient and Hessian, best of "
     << 2 * repeats << "; a negative share is the timing's noise, shown as such):\n\n| configuration | CPU ms to evaluate | "
        "relative | the removed effect's share (ms) |\n|---|---|---|---|\n";
  for (const Row& r : evaluations) {
    char share[48] = "";
    // Removing an effect cannot make the evaluation cost more: a negative
    // difference is noise (another process's cache traffic), not a share.
    if (&r != &evaluations.front())
      std::snprintf(share, sizeof share, all_effects - r.ms >= 0 ? "%.2f" : "~0 (%.2f: noise)", all_effects - r.ms);
    std::snprintf(line, sizeof line, "| %s | %.2f | %.2f | %s |\n", r.config.c_str(), r.ms, r.relative, share);
    md << line;
  }
  std::printf("%s", md.str().c_str());
  report += md.str();
  if (vm.count("out")) std::ofstream(vm["out"].as<std::string>()) << report;
  return 0;
}

const RegisterBench registration{{"simulate", "time one drape and one solver iteration with and without each effect", run}};

}  // namespace
}  // namespace drape::cli
