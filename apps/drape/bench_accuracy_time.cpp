// `drape bench accuracy-time`: what accuracy costs in time, on held-out bodies.
// Every method drapes the same test bodies of a dataset and is measured against
// a fully converged simulation of each (the scene run with a long settling
// budget): its wall time per body on one core, its mean vertex distance to the
// converged drape (ME) and its potential L_p under the scene. Methods: the
// simulator at several step budgets, the network alone, and the network with
// 10/30/100 iterations of physics-enforced optimisation. Each drape's
// crossings are counted too (garment edges through the body, through the
// garment's own faces: exact tests that share no code with the push-out), so
// the rows of a model's post-processing tiers show what each guarantee
// costs and what it buys. Writes a Markdown
// table, optionally CSV, and an SVG chart of ME against time with the Pareto
// front (the methods no other method beats on both axes) named.
// The dataset's scene decides how each body is draped, as drape generate
// draped it: the body's own size with size: auto (chosen on the body at
// rest), and a posed dataset's body reached along the scene's pose path
// from its rest shape, so posed data is benched like A-pose data.
#include "bench.hpp"
#include "model_body.hpp"

#include <drape/assets/dataset_assets.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/training/model_params.hpp>
#include <drape/training/data_parallel.hpp>
#include <drape/io/dataset.hpp>
#include <drape/services/dataset_poses.hpp>
#include <drape/training/evaluation.hpp>
#include <drape/training/model.hpp>
#include <drape/training/physics_optimization.hpp>
#include <drape/progress.hpp>
#include <drape/registry.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/services/graded_scene.hpp>
#include <drape/services/scene_body.hpp>
#include <drape/io/svg_chart.hpp>
#include <fstream>
#include <limits>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

// The topology every drape of the bench shares: the body model's and the
// garment's faces (the model's template, which the dataset's scene drapes).
struct Topology {
  Eigen::MatrixX3i body_faces, garment_faces;
};

struct Method {
  std::string name;
  double seconds = 0, me_cm = 0, potential = 0, p_percent = 0;  // means over the bodies
  double body_crossings = 0, self_crossings = 0;                 // edges per body: through the body, through the garment
  int bodies_crossed = 0;                                       // bodies with a crossing of either kind
  bool pareto = false;

  // One body's result, as its share of the means over `bodies` bodies.
  void add(double body_seconds, const Eigen::MatrixX3d& garment, const Eigen::MatrixX3d& reference, double body_potential,
           double penetration, const Eigen::MatrixX3d& body, const Topology& topology, std::size_t bodies) {
    const double n = double(bodies);
    seconds += body_seconds / n;
    me_cm += 100.0 * (garment - reference).rowwise().norm().mean() / n;
    potential += body_potential / n;
    p_percent += 100.0 * std::max(0.0, penetration) / n;
    const int through_body =
        geometry::surface_crossings(garment, topology.garment_faces, body, topology.body_faces).garment_edges_through_body;
    const auto through_self = static_cast<int>(geometry::self_edge_crossings(garment, topology.garment_faces).size());
    body_crossings += through_body / n;
    self_crossings += through_self / n;
    bodies_crossed += through_body + through_self > 0 ? 1 : 0;
  }
};

// "10,30,100" -> {10, 30, 100}; UsageError naming the option otherwise, and
// for a value below `least` (--spectral-k 0 was dropped without a word).
std::vector<int> int_list(const po::variables_map& vm, const char* option, int least) {
  std::vector<int> out;
  for (std::stringstream s(vm[option].as<std::string>()); s.good();) {
    std::string item;
    std::getline(s, item, ',');
    std::size_t used = 0;
    try {
      out.push_back(std::stoi(item, &used));
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size()) throw UsageError(std::string("--") + option + ": '" + item + "' is not a whole number");
    if (out.back() < least)
      throw UsageError(std::string("--") + option + ": " + item + " is below " + std::to_string(least) + ", the least it takes");
  }
  return out;
}

Scene with_budget(Scene scene, int morph_steps, int settle_steps) {
  scene.solver["morph_steps"].node = YAML::Node(morph_steps);
  scene.solver["settle_steps"].node = YAML::Node(settle_steps);
  return scene;
}

// "2:4,5:10" -> {{2, 4}, {5, 10}}: the simulator's morph_steps:settle_steps budgets.
std::vector<std::pair<int, int>> simulator_budgets(const po::variables_map& vm) {
  std::vector<std::pair<int, int>> budgets;
  for (std::stringstream s(vm["budgets"].as<std::string>()); s.good();) {
    std::string item;
    std::getline(s, item, ',');
    int m = 0, n = 0;
    if (std::sscanf(item.c_str(), "%d:%d", &m, &n) != 2 || m < 0 || n < 1)
      throw UsageError("--budgets: '" + item + "' is not morph_steps:settle_steps");
    budgets.push_back({m, n});
  }
  return budgets;
}

// A test body as the dataset's generation draped it: the body at rest and,
// in a posed dataset, its stored pose, which scene_body (services/
// scene_body.hpp) poses and draws the size for, as drape simulate does.
struct TestBody {
  std::string name;  // "<data> sample i", for messages
  Eigen::MatrixX3d unposed;
  Pose pose;  // empty in an A-pose dataset
};

std::vector<TestBody> test_bodies(const DatasetReader& reader, const std::string& data,
                                  const std::vector<std::size_t>& indices) {
  const std::vector<std::string>& angles = reader.layout().pose_angles;
  const Tensor rest = angles.empty() ? reader.body_vertices(indices) : reader.posing(indices).unposed;
  const Tensor degrees = angles.empty() ? Tensor() : reader.poses(indices);
  std::vector<TestBody> out;
  for (std::size_t b = 0; b < indices.size(); ++b) {
    const int i = static_cast<int>(b);
    TestBody t{data + " sample " + std::to_string(indices[b]), rest.mat(i).cast<double>(), {}};
    for (std::size_t a = 0; a < angles.size(); ++a) t.pose.angles[angles[a]] = degrees(i, 0, static_cast<int>(a));
    out.push_back(std::move(t));
  }
  return out;
}

// One test body draped by a scene's simulations: in the size they choose
// for it at rest, towards its pose.
SimulationResult drape_test_body(const SceneSimulations& simulations, const TestBody& body) {
  return drape_scene_body(scene_body(simulations, body.unposed, body.name, body.pose.empty() ? nullptr : &body.pose));
}

// The spectral branch (if any) at fewer eigenvectors than it was trained with:
// (node, k) for every k of spectral_k below the node's.
std::vector<std::pair<std::string, int>> spectral_cuts_of(Model& probe, const std::vector<int>& spectral_k) {
  std::vector<std::pair<std::string, int>> spectral_cuts;
  for (const auto& node : probe.graph().describe())
    if (node.type == "spectral")
      for (const auto& [port, shape] : node.outputs)
        if (port == "coefficients")  // [k, 3]
          for (int k : spectral_k) {
            if (k == 0) continue;  // (the documented "none")
            if (k < shape.rows) spectral_cuts.push_back({node.name, k});
            else  // (no cut: the branch has no more eigenvectors than that; said, not dropped without a word)
              std::fprintf(stderr, "note: --spectral-k %d: the spectral branch '%s' has %d eigenvectors; a cut must be fewer, so no row for it\n",
                           k, node.name.c_str(), static_cast<int>(shape.rows));
          }
  return spectral_cuts;
}

// Bodies the scene dresses today in another size than the one they were
// simulated in (the size chart grew since): said, as every method drapes
// them in today's size.
void report_regraded(const GradedScene& graded, const DatasetReader& reader, const std::vector<std::size_t>& bodies,
                     const std::vector<TestBody>& test) {
  if (!reader.layout().has_stat("garment_grade")) return;
  const std::vector<double> stored = reader.stat("garment_grade", bodies);
  std::size_t regraded = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (std::abs(graded.grade_for(test[b].unposed, test[b].name) - stored[b]) > 1e-3) ++regraded;
  if (regraded > 0)
    std::printf("%zu of %zu test bodies were simulated in another size than the scene chooses today; every method "
                "drapes them in today's size.\n",
                regraded, bodies.size());
}

// The push-out nodes the model's graph applies after the network: the bench
// also times the network without each, so the table shows what the
// clearance costs and what it buys; and without the mirror average before
// one (docs/poses.md, "The mirror average"), what the twin costs and buys.
// A push-out node that also lifts edges or undoes the garment's crossings
// of itself gets rows with less of that: without the untangle, and with the
// vertices' push-out alone (the strain limit kept), each guarantee's cost in
// time beside the crossings it leaves.
struct PostProcessing {
  std::vector<std::string> push_outs, mirror_averages;  // node names
  std::vector<std::pair<std::string, Model::ParamOverrides>> tiers;  // (row name, the node's parameters)
};
PostProcessing post_processing(const Registry& registry, const std::string& model_file) {
  PostProcessing out;
  for (const PushOutSetting& p : push_out_settings(registry, read_checkpoint(model_file).graph, model_file + " (graph)")) {
    if (p.enabled) out.push_outs.push_back(p.node);
    if (p.mirror_average) out.mirror_averages.push_back(p.node);
    if (!p.enabled) continue;
    if (p.untangle && p.edges)
      out.tiers.push_back({"network, push-out " + p.node + " without its untangle", {{p.node, {{"untangle", "false"}}}}});
    if (p.untangle || p.edges)
      out.tiers.push_back({"network, push-out " + p.node + " of the vertices only (no edge lift, no untangle)",
                           {{p.node, {{"edges", "false"}, {"untangle", "false"}}}}});
  }
  return out;
}

// The methods no other method beats on both time and ME.
void mark_pareto_front(std::vector<Method>& methods) {
  for (Method& m : methods) {
    m.pareto = true;
    for (const Method& o : methods)
      if (&o != &m && o.seconds <= m.seconds && o.me_cm <= m.me_cm && (o.seconds < m.seconds || o.me_cm < m.me_cm))
        m.pareto = false;
  }
}

// The converged reference simulations, for the table's heading.
struct Reference {
  int morph = 0, settle = 0;
  int converged = 0;
  double seconds = 0;  // per body
};

void print_table(const std::vector<Method>& methods, std::size_t bodies, const std::string& data, bool posed,
                 const Reference& ref) {
  std::ostringstream table;
  table << "## What accuracy costs in time: " << bodies << (posed ? " posed" : "") << " test bodies of " << data
        << ", one core\n\n"
        << "Reference: the scene simulated with " << ref.morph << " morph and " << ref.settle
        << " settling steps (" << ref.converged << " of " << bodies << " settled; " << ref.seconds
        << " s per body).\n\nCrossings: garment edges through the body, and through the garment's own faces "
           "(sharing no vertex with them), per body; bodies with any.\n\n"
        << "| method | s per body | ME to converged (cm) | L_p (J) | p (%) | through the body | through itself | bodies "
           "crossed | Pareto |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const Method& m : methods) {
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %.3g | %.3f | %.5g | %.2f | %.1f | %.1f | %d of %zu | %s |\n", m.name.c_str(),
                  m.seconds, m.me_cm, m.potential, m.p_percent, m.body_crossings, m.self_crossings, m.bodies_crossed,
                  bodies, m.pareto ? "yes" : "");
    table << line;
  }
  std::printf("%s", table.str().c_str());
}

// The CSV's columns, which --replot reads back (read_csv). A CSV of before
// the crossings were counted ends after `pareto`.
constexpr const char* kCsvColumns = "method,seconds_per_body,me_cm,potential_j,p_percent,pareto";
constexpr const char* kCsvCrossingColumns = ",body_crossing_edges,self_crossing_edges,bodies_crossed";

void write_csv(const std::vector<Method>& methods, const std::string& file) {
  std::ostringstream csv;
  csv << kCsvColumns << kCsvCrossingColumns << "\n";
  for (const Method& m : methods)
    csv << "\"" << m.name << "\"," << m.seconds << "," << m.me_cm << "," << m.potential << "," << m.p_percent << ","
        << (m.pareto ? 1 : 0) << "," << m.body_crossings << "," << m.self_crossings << "," << m.bodies_crossed << "\n";
  write_text_atomically(file, csv.str());
  std::printf("wrote %s\n", file.c_str());
}

// ME against time, the Pareto front starred.
void write_chart(const std::vector<Method>& methods, std::size_t bodies, bool posed, const std::string& file) {
  ScatterChart chart;
  chart.title = "What accuracy costs in time (" + std::to_string(bodies) + (posed ? " posed" : "") +
                (bodies == 1 ? " test body" : " test bodies") + ", one core); * and dashed = Pareto front";
  chart.x_label = "seconds per body on one core";
  chart.y_label = "ME to the converged simulation (cm)";
  for (const Method& m : methods) {
    char label[320];
    std::snprintf(label, sizeof label, "%s%s: %.3g s, ME %.2f cm, L_p %.4g J, p %.2f%%", m.pareto ? "* " : "",
                  m.name.c_str(), m.seconds, m.me_cm, m.potential, m.p_percent);
    std::string text = label;
    if (std::isfinite(m.body_crossings)) {  // (unknown in a replotted CSV of before they were counted)
      std::snprintf(label, sizeof label, ", edges crossing the body %.1f, itself %.1f", m.body_crossings, m.self_crossings);
      text += label;
    }
    chart.points.push_back({m.seconds, m.me_cm, text, m.pareto});
  }
  chart.write(file);
  std::printf("wrote %s\n", file.c_str());
}

// The test bodies draped by one method after another, each drape measured
// against the body's converged reference drape.
struct Bench {
  const Registry& registry;
  const std::string& model_file;
  const DatasetReader& reader;
  const std::vector<std::size_t>& bodies;
  const std::vector<TestBody>& test_bodies;
  const std::vector<Eigen::MatrixX3d>& reference;
  const Topology& topology;
  ProgressBar& bar;

  // The simulator at m morph and s settling steps.
  Method simulator(const Scene& scene, int m, int s) const {
    const std::size_t n = bodies.size();
    const SceneSimulations simulations(registry, with_budget(scene, m, s));
    Method row{"simulation " + std::to_string(m) + "+" + std::to_string(s) + " steps"};
    for (std::size_t b = 0; b < n; ++b) {
      const SimulationResult r = drape_test_body(simulations, test_bodies[b]);
      row.add(r.seconds, r.garment, reference[b], r.total_energy, r.penetration, r.body, topology, n);
      bar.advance();
    }
    return row;
  }

  // The network's prediction (with the graph's parameters overridden), its
  // potential under the scene's garment for the body. A model of several
  // sizes takes the grade the scene chooses today, not the one stored: the
  // references are simulated today, so a body drawn when the size chart
  // lacked its size (an early thin body stored in small) is compared in the
  // same garment the network is asked for.
  Method network(const GradedScene& graded, const std::string& name, const Model::ParamOverrides& overrides) const {
    const std::size_t n = bodies.size();
    Method row{name};
    Model model = Model::load(registry, model_file, overrides);
    PhysicsOptimizationOptions none;
    none.iterations = 0;
    for (std::size_t b = 0; b < n; ++b) {
      SampleBatch one = read_samples(reader, {bodies[b]}, model.graph(), false);
      const Simulation& sim = graded.for_model(model, one, false, test_bodies[b].name);
      const double seconds = 1e-3 * prediction_ms(model, one, 5);
      const PhysicsOptimizationResult r = optimize_drape(model, sim, one, none);
      row.add(seconds, r.before, reference[b], r.potential_before, r.penetration_before, one.body.mat(0).cast<double>(),
              topology, n);
      bar.advance();
    }
    return row;
  }

  // The prediction optimised for `its` iterations.
  Method optimised(const GradedScene& graded, int its) const {
    const std::size_t n = bodies.size();
    Method row{"network + " + std::to_string(its) + " optimisation iterations"};
    PhysicsOptimizationOptions o;
    o.iterations = its;
    int unseparated = 0;
    for (std::size_t b = 0; b < n; ++b) {
      Model model = Model::load(registry, model_file);  // the optimisation changes the weights
      SampleBatch one = read_samples(reader, {bodies[b]}, model.graph(), false);
      const Simulation& sim = graded.for_model(model, one, false, test_bodies[b].name);
      const PhysicsOptimizationResult r = optimize_drape(model, sim, one, o);
      row.add(r.seconds, r.after, reference[b], r.potential_after, r.penetration_after, one.body.mat(0).cast<double>(),
              topology, n);
      unseparated += r.separated ? 0 : 1;
      bar.advance();
    }
    // With a barrier, a drape whose body has not grown back yet is not a result (docs/optimization.md).
    if (unseparated > 0)
      row.name += " (" + std::to_string(unseparated) + " of " + std::to_string(n) + " not yet clear of the body)";
    return row;
  }
};

// The rows of a CSV this bench wrote (write_csv), to draw its chart again
// without the hours of drapes behind it (--replot).
std::vector<Method> read_csv(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw ConfigError(file + ": cannot be read");
  std::string line;
  std::getline(in, line);
  if (line.rfind(kCsvColumns, 0) != 0)
    throw ConfigError(file + ":1: not a CSV of drape bench accuracy-time (its header: " + kCsvColumns + "...)");
  std::vector<Method> methods;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::size_t close = line.size() > 1 && line[0] == '"' ? line.find('"', 1) : std::string::npos;
    if (close == std::string::npos || close + 1 >= line.size() || line[close + 1] != ',')
      throw ConfigError(file + ":" + std::to_string(number) + ": expected \"method\",numbers...");
    Method m;
    m.name = line.substr(1, close - 1);
    std::istringstream rest(line.substr(close + 2));
    std::vector<double> v;
    for (std::string field; std::getline(rest, field, ',');) {
      try {
        v.push_back(std::stod(field));
      } catch (const std::exception&) {
        throw ConfigError(file + ":" + std::to_string(number) + ": '" + field + "' is not a number");
      }
    }
    // (A CSV of before the crossings were counted has five numbers: they are unknown there.)
    if (v.size() != 5 && v.size() < 8)
      throw ConfigError(file + ":" + std::to_string(number) + ": expected 5 or 8 numbers after the method");
    m.seconds = v[0], m.me_cm = v[1], m.potential = v[2], m.p_percent = v[3], m.pareto = v[4] != 0;
    const double unknown = std::numeric_limits<double>::quiet_NaN();
    m.body_crossings = v.size() >= 8 ? v[5] : unknown, m.self_crossings = v.size() >= 8 ? v[6] : unknown;
    m.bodies_crossed = v.size() >= 8 ? static_cast<int>(v[7]) : 0;
    methods.push_back(m);
  }
  if (methods.empty()) throw ConfigError(file + ": no rows");
  return methods;
}

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
      "the spectral branch cut to these eigenvector counts (its use_k), comma-separated; 0: no such rows")(
      "csv", po::value<std::string>(), "also write the table as CSV")(
      "svg", po::value<std::string>(), "also draw ME against time with the Pareto front")(
      "replot", po::value<std::string>(), "draw --svg from a CSV this bench wrote instead (with --bodies, --posed as it ran)")(
      "posed", "with --replot: the bodies were posed (the chart's title says so)");
  po::variables_map vm;
  const std::string usage = "drape bench accuracy-time --data data.h5 [--model model.h5] [--bodies 4] [--svg chart.svg]\n"
                            "       drape bench accuracy-time --replot results.csv --svg chart.svg [--bodies 4] [--posed]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  // (--bodies 0 and -1 ran one body, and titled a replotted chart of two "1 test body".)
  if (vm["bodies"].as<int>() < 1) throw UsageError("--bodies " + std::to_string(vm["bodies"].as<int>()) + ": expected 1 or more test bodies");
  if (vm.count("replot")) {
    if (!vm.count("svg")) throw UsageError("--replot needs --svg (the chart to draw)");
    write_chart(read_csv(vm["replot"].as<std::string>()), static_cast<std::size_t>(vm["bodies"].as<int>()),
                vm.count("posed") > 0, vm["svg"].as<std::string>());
    return 0;
  }
  if (!vm.count("data")) throw UsageError("--data FILE is required (its test bodies are the held-out bodies)");
  const std::string data = vm["data"].as<std::string>();
  const std::vector<std::pair<int, int>> budgets = simulator_budgets(vm);
  const std::vector<int> iterations = int_list(vm, "iterations", 0), spectral_k = int_list(vm, "spectral-k", 0);
  Registry& registry = Registry::load_default(plugin_path(vm));
  const DatasetReader reader(data);
  std::vector<std::size_t> bodies = reader.indices(Split::Test);
  bodies.resize(std::min<std::size_t>(bodies.size(), static_cast<std::size_t>(vm["bodies"].as<int>())));
  if (bodies.empty()) throw ConfigError(data + ": the test split is empty");
  const std::string model_file = model_file_for_samples(vm, registry, reader, bodies);
  const Scene scene = parse_scene(reader.layout().scene);
  const std::vector<TestBody> test = test_bodies(reader, data, bodies);
  const bool posed = !reader.layout().pose_angles.empty();
  // The model once, for what every row shares: its template (checked
  // against the dataset's; its faces count the crossings) and its graph.
  Topology topology;
  std::vector<std::pair<std::string, int>> spectral_cuts;
  {
    Model probe = Model::load(registry, model_file);  // (graph() is not const)
    check_dataset_template(reader, data, probe.assets());
    check_model_takes_dataset_poses(probe, reader, bodies);
    if (!probe.assets().garment) throw ConfigError(model_file + ": the model binds no garment; the bench compares garments");
    topology.body_faces = probe.assets().body.faces;
    topology.garment_faces = probe.assets().garment->mesh.faces;
    // The spectral branch (if any) at fewer eigenvectors than it was trained with.
    spectral_cuts = spectral_cuts_of(probe, spectral_k);
  }
  const PostProcessing post = post_processing(registry, model_file);
  const OmpThreadsScope one_core(1);
  const int steps = static_cast<int>(bodies.size()) *
                    (2 + static_cast<int>(budgets.size() + iterations.size() + spectral_cuts.size() +
                                          post.push_outs.size() + post.mirror_averages.size() + post.tiers.size()));
  ProgressBar bar("accuracy-time", static_cast<std::size_t>(steps), std::cerr);

  // The converged reference of every body.
  Reference ref;
  ref.morph = static_cast<int>(Params(scene_solver_specs(), scene.solver, "solver").get_int("morph_steps"));
  ref.settle = vm["reference-settle"].as<int>();
  const SceneSimulations reference_sims(registry, with_budget(scene, ref.morph, ref.settle));
  std::vector<Eigen::MatrixX3d> reference;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const SimulationResult r = drape_test_body(reference_sims, test[b]);
    reference.push_back(r.garment);
    ref.converged += r.converged ? 1 : 0;
    ref.seconds += r.seconds / double(bodies.size());
    bar.advance();
  }

  std::vector<Method> methods;
  const Bench bench{registry, model_file, reader, bodies, test, reference, topology, bar};
  for (const auto& [m, s] : budgets) methods.push_back(bench.simulator(scene, m, s));
  // The network alone (its potential and p from a zero-iteration optimisation,
  // which leaves the weights alone), with its spectral branch cut to fewer
  // eigenvectors, then optimised (from the loaded weights for every body).
  const SceneSimulations simulations(registry, scene);
  const GradedScene graded(registry, simulations);
  report_regraded(graded, reader, bodies, test);
  methods.push_back(bench.network(graded, "network", {}));
  for (const auto& [node, k] : spectral_cuts)
    methods.push_back(bench.network(graded, "network, spectral branch k = " + std::to_string(k),
                                    {{node, {{"use_k", std::to_string(k)}}}}));
  for (const auto& [name, overrides] : post.tiers) methods.push_back(bench.network(graded, name, overrides));
  for (const std::string& node : post.push_outs)
    methods.push_back(bench.network(graded, "network, push-out " + node + " off", {{node, {{"enabled", "false"}}}}));
  for (const std::string& node : post.mirror_averages)
    methods.push_back(bench.network(graded, "network, mirror average off", {{node, {{"mirror_average", "false"}}}}));
  for (int its : iterations) methods.push_back(bench.optimised(graded, its));
  bar.finish();
  mark_pareto_front(methods);
  print_table(methods, bodies.size(), data, posed, ref);
  if (vm.count("csv")) write_csv(methods, vm["csv"].as<std::string>());
  if (vm.count("svg")) write_chart(methods, bodies.size(), posed, vm["svg"].as<std::string>());
  return 0;
}

const RegisterBench registration{
    {"accuracy-time",
     "simulator budgets, the network, and network + optimisation on test bodies: time against ME to a converged drape and L_p",
     run}};

}  // namespace
}  // namespace drape::cli
