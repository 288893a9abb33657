// `drape optimize --model model.h5 --scene scene.yaml (--body body.obj | --bmi 35)
// --iters 100 --out garment.obj`: the seed's physics-enforced optimisation of
// one drape (drape/training/physics_optimization.hpp) -- the network's weights
// fine-tuned for this body to minimise the scene's potential energy.
#include "command.hpp"

#include "model_body.hpp"
#include "sample_ranges.hpp"

#include <drape/services/dataset_optimization.hpp>

#include <drape/io/shipped_files.hpp>
#include <drape/io/dataset.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/training/model.hpp>
#include <drape/io/output_lock.hpp>
#include <drape/io/write_failure.hpp>
#include <drape/training/physics_optimization.hpp>
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/services/graded_scene.hpp>
#include <drape/io/svg_figure.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <thread>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

void print_terms(const char* when, const std::vector<EnergyTerm>& terms, double total, double p) {
  std::printf("%-7s", when);
  for (const auto& t : terms) std::printf("  %s %.6g", t.name.c_str(), t.value);
  std::printf("  | L_p %.6g J  | p %.3f%%\n", total, 100.0 * p);
}

int run_on_dataset(const po::variables_map& vm) {
  if (vm.count("body") || vm.count("bmi")) throw UsageError("--data optimises the dataset's bodies: drop --body/--bmi");
  OptimizeDatasetOptions o;
  o.data = vm["data"].as<std::string>();
  {
    // Without --model, the shipped model of the dataset's rig and poses.
    const DatasetReader data(o.data);
    o.model = model_file_for_samples(vm, Registry::load_default(plugin_path(vm)), data, data.indices());
  }
  o.out = vm["out"].as<std::string>();
  o.scene_file = find_input_file(vm["scene"].as<std::string>());
  o.split = vm["split"].as<std::string>();
  o.shard = parse_shard(vm["shard"].as<std::string>());
  DatasetReader::check_splits(o.split);  // a misspelt split fails before any work
  o.threads = vm["threads"].as<int>();
  if (o.threads <= 0) o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.optimization.iterations = vm["iters"].as<int>();
  o.optimization.learning_rate = vm["lr"].as<double>();
  std::error_code ec;
  const bool finished_before = std::filesystem::exists(o.out, ec);  // (then "nothing to do", or refused)
  const std::size_t n = optimize_dataset(Registry::load_default(plugin_path(vm)), o);
  if (!finished_before) std::printf("wrote %s: %zu samples optimised in this run\n", o.out.c_str(), n);
  return 0;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape optimize");
  opts.add_options()("model", po::value<std::string>(), "model file from drape train (default: the shipped model)")(
      "scene", po::value<std::string>(), "scene whose effects and materials make the potential (graphs/scenes/*.yaml)")(
      "iters", po::value<int>()->default_value(100), "Adam iterations on the network's weights")(
      "lr", po::value<double>()->default_value(1e-4), "Adam's learning rate")(
      "out", po::value<std::string>(), "optimised garment mesh to write")(
      "before", po::value<std::string>(), "also write the network's prediction before optimising")(
      "svg", po::value<std::string>(), "also draw the drape before and after (.svg, or .html: a 3D viewer)")(
      "data", po::value<std::string>(), "or optimise every sample of a dataset split (then --out is a dataset)")(
      "split", po::value<std::string>()->default_value("train"), "with --data: train | val | test | all, or a list: train,val")(
      "threads", po::value<int>()->default_value(0), "with --data: samples at once (0: all cores)")(
      "shard", po::value<std::string>()->default_value("0/1"), "with --data: only part i of N of the split (a job array's task; join with drape dataset merge)")(
      "verbose,v", po::bool_switch(), "print L_p at every iteration");
  add_model_body_options(opts, "body mesh in the model's body topology");
  po::variables_map vm;
  const std::string usage =
      "drape optimize [--model model.h5] --scene scene.yaml (--body body.obj | --bmi 35) [--iters 100] [--lr 1e-4] "
      "--out garment.obj\n       drape optimize [--model model.h5] --scene scene.yaml --data data.h5 [--split train] "
      "--out optimized.h5 [--threads T] [--shard i/N]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  // (--before too: an outside check's --before in a missing folder was
  // refused after the optimisation, its --out written.)
  if (!vm.count("data")) check_mesh_outputs(vm, {"out", "before"});  // with --data, --out is a dataset
  if (!vm.count("scene")) throw UsageError("--scene FILE is required (its effects and materials make the potential)");
  if (!vm.count("out")) throw UsageError("--out FILE is required (the optimised garment, or dataset with --data)");
  // Before any file is made (an outside check: with --data they were refused
  // after the output's .partial was begun, whose resume then refused the
  // corrected command), naming the option.
  if (vm["iters"].as<int>() < 0)
    throw UsageError("--iters " + std::to_string(vm["iters"].as<int>()) + ": expected 0 or more Adam iterations");
  if (const double lr = vm["lr"].as<double>(); !(lr > 0) || !(lr <= 1)) {  // (1e300 ran and kept its first drape)
    char text[96];
    std::snprintf(text, sizeof text, "--lr %g: Adam's learning rate must be a number in (0, 1]", lr);
    throw UsageError(text);
  }
  // Before anything looks at the output (output_lock.hpp).
  const OutputLock lock(vm["out"].as<std::string>(), "drape optimize", vm.count("data") > 0);  // --data: resumable
  if (vm.count("data")) {
    // It said "delete it to generate it again", of the dataset it reads.
    refuse_output_among_inputs(vm["out"].as<std::string>(), dataset_inputs(vm["data"].as<std::string>()), "--out");
    return run_on_dataset(vm);
  }
  for (const char* option : {"split", "threads", "shard"})
    if (!vm[option].defaulted())
      throw UsageError(std::string("--") + option + " goes with --data (a dataset split); one body is optimised alone");
  if (vm.count("body") == vm.count("bmi"))
    throw UsageError("give the body either as a mesh (--body FILE) or by its BMI (--bmi X), exactly one");
  // The scene's text first (its simulations take seconds to build): its
  // `body: pose:` poses the body when no --pose is given, as in drape
  // simulate, and sends it to the model of posed drapes.
  const std::filesystem::path scene_file = find_input_file(vm["scene"].as<std::string>());
  Scene scene_spec = load_scene(scene_file);
  Registry& registry = Registry::load_default(plugin_path(vm));
  std::string model_file = model_file_or_default(vm, !pose_given(vm) && !scene_spec.pose.empty());
  // Without --model, the shipped model of the scene's rig when the default
  // drapes the other (optimize --scene graphs/scenes/tshirt_coarse_posed.yaml
  // --bmi 30 was refused: "another rig", a scene of sizes).
  if (!vm.count("body") && !vm.count("model"))  // (the scene's body is made only to be counted)
    model_file = model_file_for_rig(vm, registry, model_file, make_scene_body_model(registry, scene_spec)->num_vertices(),
                                    "the scene " + scene_file.string());
  else model_file = model_file_for_body(vm, registry, model_file);
  Model model = Model::load(registry, model_file);
  BodyMove moved_by;  // the drape is made where (and as) the training bodies stood; written back where the body was
  // The body and its pose before the scene is built: a bad one is refused at once.
  const Pose scene_posed = pose_given(vm) ? Pose{} : scene_pose(scene_spec, model.body_model());
  // A pose in which the body passes through itself is refused before any
  // work, as drape body and simulate refuse it (an outside check's optimize
  // ran on one and ended "NOT separated"); predict only warns.
  SampleBatch batch = model_body(model, vm, &moved_by, nullptr, &scene_posed, "the scene " + scene_file.string(), true);
  const SceneSimulations simulations(registry, std::move(scene_spec));
  // The body optimised on is the model's; the scene gives the garment's
  // energies and the contact. A scene on another rig (another vertex count)
  // was taken without a word when its size is fixed, and refused with "the
  // body has 6904 vertices, expected 6490" of a body the user never gave when
  // it chooses the size by measuring the body on its own rig (an outside
  // check): the first is said, the second refused naming both rigs.
  if (const int scene_vertices = simulations.design().body_model().num_vertices(),
      model_vertices = model.assets().body.num_vertices();
      scene_vertices != model_vertices) {
    const std::string rigs = "its body model '" + simulations.design().scene().body_model + "' makes bodies of " +
                             std::to_string(scene_vertices) + " vertices, and " +
                             std::filesystem::path(model_file).filename().string() + " drapes bodies of " +
                             std::to_string(model_vertices) + " (another rig: docs/bodies.md)";
    if (simulations.auto_size() || simulations.auto_grade())
      throw ConfigError(scene_file.string() + ": " + rigs + ", and the scene chooses the garment's size by measuring the "
                        "body on its own: give a scene on the model's body (the one it was trained in: drape model "
                        "info) or a model of the scene's (--model)");
    std::cerr << "note: " << scene_file.string() << ": " << rigs
              << ": the body is the model's, the scene gives the garment, its energies and the contact\n";
  }
  // A model of several sizes is optimised against the garment the scene dresses this body in.
  std::string regraded;
  const Simulation& scene = GradedScene(registry, simulations)
                                .for_model(model, batch, vm.count("garment-size") || vm.count("garment-grade"),
                                           "drape optimize", &regraded);
  if (!regraded.empty()) std::printf("note: %s\n", regraded.c_str());

  PhysicsOptimizationOptions o;
  o.iterations = vm["iters"].as<int>();
  o.learning_rate = vm["lr"].as<double>();
  if (vm["verbose"].as<bool>()) o.on_iteration = [](int it, double lp) { std::printf("iteration %4d  L_p %.8g J\n", it, lp); };
  const PhysicsOptimizationResult r = optimize_drape(model, scene, batch, o);

  if (o.iterations > 0)
    std::printf("optimised %s for %s: %d iterations in %.2f s (%.1f ms each), best at iteration %d\n", model_file.c_str(),
                vm["scene"].as<std::string>().c_str(), o.iterations, r.seconds, 1000.0 * r.seconds / o.iterations,
                r.best_iteration);
  else
    std::printf("measured %s for %s: 0 iterations, the prediction as it is (%.2f s)\n", model_file.c_str(),
                vm["scene"].as<std::string>().c_str(), r.seconds);
  if (!model.push_out_node().empty())
    std::printf("the push-out that predict applies after the network (node '%s') is not learnt: the drape optimised "
                "is the network's own plus the push-out's correction of the prediction, held fixed\n",
                model.push_out_node().c_str());
  print_terms("before", r.energies_before, r.potential_before, r.penetration_before);
  print_terms("after", r.energies_after, r.potential_after, r.penetration_after);
  // A body given elsewhere is draped where the training bodies stood: the
  // figures are of that drape (an outside check summed m g y over the file
  // written, 0.9 m lower, and found another gravity term).
  if ((moved_by.back(r.after) - r.after).cwiseAbs().maxCoeff() > 1e-9)
    std::printf("(the energies are of the drape where the model drapes the body; the file is moved back with the body, "
                "which changes its gravity term by the body's vertical move and no difference between them)\n");
  // Counted by exact segment-triangle tests that share no code with the contact energies.
  const auto crossings = [&](const Eigen::MatrixX3d& g) {
    return geometry::surface_crossings(g, scene.garment().mesh.faces, batch.body.mat(0).cast<double>(), model.assets().body.faces)
        .total();
  };
  std::printf("surface crossings (garment + body edges through the other's faces): before %d, after %d\n",
              crossings(r.before), crossings(r.after));
  // And the cloth through itself, as simulate and predict count it (an
  // outside check's optimised drape crossed itself at 19 pairs unsaid; the
  // self-contact barrier keeps layers apart, it cannot undo a crossing).
  const std::size_t self_before = geometry::self_edge_crossings(r.before, scene.garment().mesh.faces, geometry::kCrossingsCountedAtMost).size(),
                    self_after = geometry::self_edge_crossings(r.after, scene.garment().mesh.faces, geometry::kCrossingsCountedAtMost).size();
  std::printf("the garment through itself (edge-face pairs): before %zu, after %zu\n", self_before, self_after);
  if (self_after > 0)
    std::cerr << "warning: the optimised garment passes through itself: " << self_after
              << " pairs of an edge and a face it passes through (the prediction's"
              << (self_before > 0 ? ", which the optimisation keeps: a contact keeps layers apart and cannot undo a crossing)"
                                  : " had none)")
              << "\n";
  if (r.start_shrink > 0)
    std::printf("barrier: the prediction crosses the body, so the contact started on the body shrunk by %.1f cm, %s\n",
                100 * r.start_shrink,
                r.grown_iteration > 0 ? ("grown back as the cloth moved out by iteration " + std::to_string(r.grown_iteration)).c_str()
                                      : "not grown back by the last iteration");
  if (r.refused_steps > 0)
    std::printf("%d steps undone because they would have crossed the body (each retried shorter)\n",
                r.refused_steps);
  if (!r.separated) std::printf("NOT separated from the body, so not a result: %s\n", r.unseparated.c_str());
  else if (!r.stopped.empty())
    std::printf("%s; the best drape before it is the result (iteration %d)\n", r.stopped.c_str(), r.best_iteration);
  Mesh body;
  body.vertices = moved_by.back(batch.body.mat(0).cast<double>());
  body.faces = model.assets().body.faces;
  Mesh out = scene.garment().mesh;
  out.vertices = moved_by.back(r.after);
  write_mesh(vm["out"].as<std::string>(), out);
  std::printf("wrote %s\n", vm["out"].as<std::string>().c_str());
  if (vm.count("before")) {
    Mesh before = out;
    before.vertices = moved_by.back(r.before);
    write_mesh(vm["before"].as<std::string>(), before);
    std::printf("wrote %s\n", vm["before"].as<std::string>().c_str());
  }
  if (vm.count("svg")) {
    Mesh before = out;
    before.vertices = r.before;
    char a[96], b[96];
    std::snprintf(a, sizeof a, "network: L_p %.4g J, p %.2f%%", r.potential_before, 100.0 * r.penetration_before);
    std::snprintf(b, sizeof b, "optimised: L_p %.4g J, p %.2f%%", r.potential_after, 100.0 * r.penetration_after);
    SvgFigure figure = drape_figure("drape optimize: " + std::filesystem::path(model_file).filename().string(), a, body, before);
    figure.add_panel(drape_figure("", b, body, out).panels().front());
    figure.write(vm["svg"].as<std::string>());
    std::printf("wrote %s\n", vm["svg"].as<std::string>().c_str());
  }
  return r.separated ? 0 : 1;
}

const RegisterCommand registered{{"optimize", "fine-tune a model for one body to minimise the scene's potential energy", run}};

}  // namespace
}  // namespace drape::cli
