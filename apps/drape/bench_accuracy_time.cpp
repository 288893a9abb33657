// `drape bench accuracy-time`: what accuracy costs in time, on held-out bodies.
// Every method drapes the same test bodies of a dataset and is measured against
// a fully converged simulation of each (the scene run with a long settling
// budget): its wall time per body on one core, its mean vertex distance to the
// converged drape (ME) and its potential L_p under the scene. Methods: the
// simulator at several step budgets, the network alone, and the network with
// 10/30/100 iterations of physics-enforced optimisation. Writes a Markdown
// table, optionally CSV, and an SVG chart of ME against time with the Pareto
// front (the methods no other method beats on both axes) named.
#include "bench.hpp"

#include <drape/atomic_file.hpp>
#include <drape/data_parallel.hpp>
#include <drape/dataset.hpp>
#include <drape/model.hpp>
#include <drape/physics_optimization.hpp>
#include <drape/progress.hpp>
#include <drape/registry.hpp>
#include <drape/scene.hpp>
#include <drape/simulation.hpp>
#include <drape/svg_chart.hpp>
#include <drape/trainer.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace drape::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct Method {
  std::string name;
  double seconds = 0, me_cm = 0, potential = 0, p_percent = 0;  // means over the bodies
  bool pareto = false;
};

Scene with_budget(Scene scene, int morph_steps, int settle_steps) {
  scene.solver["morph_steps"].node = YAML::Node(morph_steps);
  scene.solver["settle_steps"].node = YAML::Node(settle_steps);
  return scene;
}

double me_cm(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) { return 100.0 * (a - b).rowwise().norm().mean(); }

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench accuracy-time");
  opts.add_options()("data", po::value<std::string>(), "dataset whose test bodies are draped (its scene is the simulator's)")(
      "model", po::value<std::string>(), "model file (default: the shipped model)")(
      "bodies", po::value<int>()->default_value(4), "test bodies (the first ones of the test split)")(
      "reference-settle", po::value<int>()->default_value(300), "settling steps of the converged reference simulation")(
      "budgets", po::value<std::string>()->default_value("2:4,5:10,10:20,20:60"),
      "simulator budgets, morph_steps:settle_steps, comma-separated")(
      "iterations", po::value<std::string>()->default_value("10,30,100"), "optimisation iterations, comma-separated")(
      "spectral-k", po::value<std::string>()->default_value("16,64,256"),
      "the spectral branch cut to these eigenvector counts (its use_k), comma-separated")(
      "csv", po::value<std::string>(), "also write the table as CSV")(
      "svg", po::value<std::string>(), "also draw ME against time with the Pareto front");
  po::variables_map vm;
  const std::string usage = "drape bench accuracy-time --data data.h5 [--model model.h5] [--bodies 4] [--svg chart.svg]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  if (!vm.count("data")) throw UsageError("--data FILE is required (its test bodies are the held-out bodies)");
  const std::string data = vm["data"].as<std::string>();
  const std::string model_file = vm.count("model") ? vm["model"].as<std::string>() : default_model_path().string();
  if (model_file.empty()) throw UsageError("no --model and no shipped model found");
  std::vector<std::pair<int, int>> budgets;
  for (std::stringstream s(vm["budgets"].as<std::string>()); s.good();) {
    std::string item;
    std::getline(s, item, ',');
    int m = 0, n = 0;
    if (std::sscanf(item.c_str(), "%d:%d", &m, &n) != 2 || m < 0 || n < 1)
      throw UsageError("--budgets: '" + item + "' is not morph_steps:settle_steps");
    budgets.push_back({m, n});
  }
  std::vector<int> iterations;
  for (std::stringstream s(vm["iterations"].as<std::string>()); s.good();) {
    std::string item;
    std::getline(s, item, ',');
    try {
      iterations.push_back(std::stoi(item));
    } catch (const std::exception&) {
      throw UsageError("--iterations: '" + item + "' is not a number");
    }
  }

  std::vector<int> spectral_k;
  for (std::stringstream s(vm["spectral-k"].as<std::string>()); s.good();) {
    std::string item;
    std::getline(s, item, ',');
    try {
      spectral_k.push_back(std::stoi(item));
    } catch (const std::exception&) {
      throw UsageError("--spectral-k: '" + item + "' is not a number");
    }
  }
  Registry& registry = Registry::load_default(plugin_path(vm));
  const DatasetReader reader(data);
  std::vector<std::size_t> bodies = reader.indices(Split::Test);
  bodies.resize(std::min<std::size_t>(bodies.size(), static_cast<std::size_t>(std::max(1, vm["bodies"].as<int>()))));
  if (bodies.empty()) throw ConfigError(data + ": the test split is empty");
  const Scene scene = parse_scene(reader.layout().scene);
  const Tensor body_tensor = reader.body_vertices(bodies);
  {
    const Model probe = Model::load(registry, model_file);
    check_dataset_template(reader, data, probe.assets());
  }
  // The spectral branch (if any) at fewer eigenvectors than it was trained with.
  std::vector<std::pair<std::string, int>> spectral_cuts;
  {
    Model probe = Model::load(registry, model_file);
    for (const auto& node : probe.graph().describe())
      if (node.type == "spectral")
        for (const auto& [port, shape] : node.outputs)
          if (port == "coefficients")  // [k, 3]
            for (int k : spectral_k)
              if (k > 0 && k < shape.rows) spectral_cuts.push_back({node.name, k});
  }
  const OmpThreadsScope one_core(1);
  const int steps =
      static_cast<int>(bodies.size()) * (2 + static_cast<int>(budgets.size() + iterations.size() + spectral_cuts.size()));
  ProgressBar bar("accuracy-time", static_cast<std::size_t>(steps), std::cerr);

  // The converged reference of every body.
  const int morph = static_cast<int>(Params(scene_solver_specs(), scene.solver, "solver").get_int("morph_steps"));
  const Simulation reference_sim(registry, with_budget(scene, morph, vm["reference-settle"].as<int>()));
  std::vector<Eigen::MatrixX3d> reference;
  int converged = 0;
  double reference_seconds = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const SimulationResult r = reference_sim.run(body_tensor.mat(static_cast<int>(b)).cast<double>());
    reference.push_back(r.garment);
    converged += r.converged ? 1 : 0;
    reference_seconds += r.seconds / double(bodies.size());
    bar.advance();
  }

  std::vector<Method> methods;
  auto add = [&](Method m) { methods.push_back(std::move(m)); };
  const double n = double(bodies.size());
  for (const auto& [m, s] : budgets) {
    const Simulation sim(registry, with_budget(scene, m, s));
    Method row{"simulation " + std::to_string(m) + "+" + std::to_string(s) + " steps"};
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const SimulationResult r = sim.run(body_tensor.mat(static_cast<int>(b)).cast<double>());
      row.seconds += r.seconds / n;
      row.me_cm += me_cm(r.garment, reference[b]) / n;
      row.potential += r.total_energy / n;
      row.p_percent += 100.0 * std::max(0.0, r.penetration) / n;
      bar.advance();
    }
    add(row);
  }
  // The network alone (its potential and p from a zero-iteration optimisation),
  // with its spectral branch cut to fewer eigenvectors, then optimised.
  const Simulation sim(registry, scene);
  auto measure_network = [&](const std::string& name, const Model::ParamOverrides& overrides) {
  Method network{name};
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    Model model = Model::load(registry, model_file, overrides);
    SampleBatch one;
    one.body = reader.body_vertices({bodies[b]});
    if (model.needs_body_params()) one.body_params = reader.body_params({bodies[b]});
    model.predict(one);
    double best = 1e300;
    for (int r = 0; r < 5; ++r) {
      const auto t = Clock::now();
      model.predict(one);
      best = std::min(best, std::chrono::duration<double>(Clock::now() - t).count());
    }
    PhysicsOptimizationOptions none;
    none.iterations = 0;
    const PhysicsOptimizationResult r = optimize_drape(model, sim, one, none);
    network.seconds += best / n;
    network.me_cm += me_cm(r.before, reference[b]) / n;
    network.potential += r.potential_before / n;
    network.p_percent += 100.0 * r.penetration_before / n;
    bar.advance();
  }
  add(network);
  };
  measure_network("network", {});
  for (const auto& [node, k] : spectral_cuts) measure_network("network, spectral branch k = " + std::to_string(k), {{node, {{"use_k", std::to_string(k)}}}});
  for (int its : iterations) {
    Method row{"network + " + std::to_string(its) + " optimisation iterations"};
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      Model model = Model::load(registry, model_file);  // fresh weights for every body
      SampleBatch one;
      one.body = reader.body_vertices({bodies[b]});
      if (model.needs_body_params()) one.body_params = reader.body_params({bodies[b]});
      PhysicsOptimizationOptions o;
      o.iterations = its;
      const PhysicsOptimizationResult r = optimize_drape(model, sim, one, o);
      row.seconds += r.seconds / n;
      row.me_cm += me_cm(r.after, reference[b]) / n;
      row.potential += r.potential_after / n;
      row.p_percent += 100.0 * r.penetration_after / n;
      bar.advance();
    }
    add(row);
  }
  bar.finish();
  for (Method& m : methods) {
    m.pareto = true;
    for (const Method& o : methods)
      if (&o != &m && o.seconds <= m.seconds && o.me_cm <= m.me_cm && (o.seconds < m.seconds || o.me_cm < m.me_cm))
        m.pareto = false;
  }

  std::ostringstream table;
  table << "## What accuracy costs in time: " << bodies.size() << " test bodies of " << data << ", one core\n\n"
        << "Reference: the scene simulated with " << morph << " morph and " << vm["reference-settle"].as<int>()
        << " settling steps (" << converged << " of " << bodies.size() << " settled; " << reference_seconds
        << " s per body).\n\n| method | s per body | ME to converged (cm) | L_p (J) | p (%) | Pareto |\n|---|---|---|---|---|---|\n";
  for (const Method& m : methods) {
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %.3g | %.3f | %.5g | %.2f | %s |\n", m.name.c_str(), m.seconds, m.me_cm,
                  m.potential, m.p_percent, m.pareto ? "yes" : "");
    table << line;
  }
  std::printf("%s", table.str().c_str());
  if (vm.count("csv")) {
    std::ostringstream csv;
    csv << "method,seconds_per_body,me_cm,potential_j,p_percent,pareto\n";
    for (const Method& m : methods)
      csv << "\"" << m.name << "\"," << m.seconds << "," << m.me_cm << "," << m.potential << "," << m.p_percent << ","
          << (m.pareto ? 1 : 0) << "\n";
    write_text_atomically(vm["csv"].as<std::string>(), csv.str());
    std::printf("wrote %s\n", vm["csv"].as<std::string>().c_str());
  }
  if (vm.count("svg")) {
    ScatterChart chart;
    chart.title = "What accuracy costs in time (" + std::to_string(bodies.size()) + " test bodies, one core); * = Pareto front";
    chart.x_label = "seconds per body on one core";
    chart.y_label = "ME to the converged simulation (cm)";
    for (const Method& m : methods) {
      char label[200];
      std::snprintf(label, sizeof label, "%s%s: %.3g s, ME %.2f cm, L_p %.4g J, p %.2f%%", m.pareto ? "* " : "",
                    m.name.c_str(), m.seconds, m.me_cm, m.potential, m.p_percent);
      chart.points.push_back({m.seconds, m.me_cm, label});
    }
    chart.write(vm["svg"].as<std::string>());
    std::printf("wrote %s\n", vm["svg"].as<std::string>().c_str());
  }
  return 0;
}

const RegisterBench registration{
    {"accuracy-time",
     "simulator budgets, the network, and network + optimisation on test bodies: time against ME to a converged drape and L_p",
     run}};

}  // namespace
}  // namespace drape::cli
