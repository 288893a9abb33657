// `drape bench optimize`: the cost of the physics-enforced optimisation on one
// core -- N Adam iterations of the network's weights against the scene's
// potential, for one body -- at the resolution of the scene's garment. The
// time does not depend on the weights, so `--graph` times a graph with fresh
// weights on any resolution (the seed's target: 100 iterations at the default
// resolution within 2 s, 7 s on its GPU); `--model` times a trained model.
// Several runs from the same weights: the best and the median are shown.
#include "bench.hpp"

#include <drape/io/shipped_files.hpp>

#include <drape/training/model.hpp>
#include <drape/training/physics_optimization.hpp>
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/services/graded_scene.hpp>
#include <drape/services/model_body.hpp>
#include <drape/training/model_domain.hpp>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench optimize");
  opts.add_options()("model", po::value<std::string>(), "a trained model whose template is the scene's garment")(
      "graph", po::value<std::string>(), "or a graph, with fresh weights on the scene's template")(
      "scene", po::value<std::string>()->default_value("graphs/scenes/tshirt.yaml"), "scene whose potential is minimised")(
      "bmi", po::value<double>()->default_value(35), "BMI of the body")(
      "iterations", po::value<int>()->default_value(100), "Adam iterations")(
      "repeats", po::value<int>()->default_value(3), "timed runs from the same weights (best and median shown)")(
      "k", po::value<int>()->default_value(1000), "with --graph: eigenvectors in the assets");
  po::variables_map vm;
  const std::string usage =
      "drape bench optimize (--graph graphs/drape.yaml | --model model.h5) [--scene graphs/scenes/tshirt.yaml] [--iterations 100]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  require_model_or_graph(vm);
  const int iterations = count_option(vm, "iterations"), repeats = count_option(vm, "repeats");
  Registry& registry = Registry::load_default(plugin_path(vm));
  const Scene scene = load_scene(find_input_file(vm["scene"].as<std::string>()));
  Model model = vm.count("model") ? Model::load(registry, find_input_file(vm["model"].as<std::string>()))
                                  : Model::untrained(registry, parse_graph_file(find_input_file(vm["graph"].as<std::string>())),
                                                     assets_spec_for(scene, vm["k"].as<int>()));
  BodyRequest request;
  request.bmi = vm["bmi"].as<double>();
  SampleBatch body = model.body_for(request);
  // A model of sizes is timed as drape optimize runs it: the body in the
  // size the tailor's rule gives it, optimised against the garment the scene
  // dresses it in (size: auto and grade: auto scenes too; the shipped coarse
  // models were refused here, "the graph takes input 'garment_grade'").
  if (vm.count("model")) BodyPreparation(model, read_domain(model.file())).choose_sizes(body);
  const SceneSimulations simulations(registry, scene);
  std::string regraded;
  const Simulation& simulation = GradedScene(registry, simulations).for_model(model, body, false, "drape bench optimize", &regraded);
  if (!regraded.empty()) std::printf("note: %s\n", regraded.c_str());
  // The optimisation tunes the model's weights in place: every run starts
  // from a copy of the original ones, so that each does the same work.
  std::vector<Tensor> original;
  for (const auto& [name, w] : model.graph().weights()) original.push_back(w->value);
  auto restore = [&] {
    std::size_t i = 0;
    for (const auto& [name, w] : model.graph().weights()) w->value = original[i++];
  };
  PhysicsOptimizationOptions o;
  o.iterations = 1;
  optimize_drape(model, simulation, body, o);  // warm-up: allocations, caches
  o.iterations = iterations;
  std::vector<double> seconds;
  PhysicsOptimizationResult r;
  for (int k = 0; k < repeats; ++k) {
    restore();
    r = optimize_drape(model, simulation, body, o);
    seconds.push_back(r.seconds);
  }
  const auto [best, median] = best_and_median(seconds);
  std::printf("## Physics-enforced optimisation on one core: %s, scene %s\n\n", model.file().string().c_str(),
              vm["scene"].as<std::string>().c_str());
  std::printf("garment %d vertices, body %d vertices, BMI %g\n\n", model.assets().garment->mesh.num_vertices(),
              model.assets().body.num_vertices(), request.bmi);
  std::printf("| iterations | s, best of %d | s, median | ms per iteration (best) | L_p before -> after (J) |\n"
              "|---|---|---|---|---|\n",
              repeats);
  std::printf("| %d | %.3f | %.3f | %.2f | %.5g -> %.5g |\n", o.iterations, best, median,
              1000.0 * best / std::max(1, o.iterations), r.potential_before, r.potential_after);
  return 0;
}

const RegisterBench registration{
    {"optimize", "seconds for N iterations of physics-enforced optimisation of one body on one core", run}};

}  // namespace
}  // namespace drape::cli
