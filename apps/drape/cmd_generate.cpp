// `drape generate`: a dataset of simulated drapes (the seed's ground truth) --
// bodies drawn uniformly in BMI (and height), each draped by the scene's
// simulation, in parallel over samples, resumable after a kill, shardable
// across a cluster job array (merge with `drape dataset merge`).
#include "command.hpp"
#include "parallel_samples.hpp"
#include "sample_ranges.hpp"

#include <drape/body_space.hpp>

#include <drape/dataset.hpp>
#include <drape/garment_size.hpp>
#include <drape/model.hpp>
#include <drape/output_lock.hpp>
#include <drape/progress.hpp>
#include <drape/registry.hpp>
#include <drape/rng.hpp>
#include <drape/simulation.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <atomic>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

namespace drape::cli {
namespace {

// The 8:1:1 split of the whole set (all shards): a seeded permutation, the
// first 80% train, the next 10% validation, the rest test.
std::vector<Split> splits(std::size_t total, std::uint64_t seed) {
  const auto order = Rng(Rng::derive(seed, "split")).permutation(total);
  std::vector<Split> out(total);
  for (std::size_t k = 0; k < total; ++k)
    out[order[k]] = k < total * 8 / 10 ? Split::Train : (k < total * 9 / 10 ? Split::Val : Split::Test);
  return out;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape generate");
  opts.add_options()("scene", po::value<std::string>()->default_value("graphs/scenes/tshirt.yaml"), "scene file")(
      "count", po::value<std::size_t>(), "samples in the whole set (all shards)")(
      "bmi", po::value<std::string>()->default_value("10:65"), "BMI range lo:hi (uniform) or a value")(
      "height", po::value<std::string>()->default_value("1.75"), "height range lo:hi in m, or a value")(
      "sex", po::value<std::string>()->default_value("1"), "0, 1, or 0:1 for a random one per sample")(
      "girths", po::value<double>()->default_value(0.0),
      "spread of the body's girths (chest, waist, belly, hips, arms, thighs) as a fraction of the body model's range, "
      "each drawn uniformly; 0 keeps the mean build (docs/bodies.md)")(
      "seed", po::value<std::uint64_t>()->default_value(0), "seed of the bodies and the split")(
      "out", po::value<std::string>(), "dataset file (HDF5) to write")(
      "shard", po::value<std::string>()->default_value("0/1"), "make only shard i of N (a contiguous part), e.g. 3/16")(
      "threads", po::value<int>()->default_value(0), "samples simulated at once (0: all cores)");
  po::positional_options_description pos;
  pos.add("scene", 1);
  po::variables_map vm;
  const std::string usage =
      "drape generate [SCENE.yaml] --count N --bmi 10:65 --seed S --out data.h5 [--shard i/N] [--threads T]";
  if (!parse(usage, args, opts, pos, vm)) return 0;
  if (!vm.count("count") || vm["count"].as<std::size_t>() == 0) throw UsageError("--count N (N >= 1) is required");
  if (!vm.count("out")) throw UsageError("--out FILE is required");
  // Before anything looks at the output (output_lock.hpp).
  const OutputLock lock(vm["out"].as<std::string>(), "drape generate");
  const std::size_t total = vm["count"].as<std::size_t>();
  const Shard shard = parse_shard(vm["shard"].as<std::string>());
  const Range bmi = parse_range("bmi", vm["bmi"].as<std::string>());
  const Range height = parse_range("height", vm["height"].as<std::string>());
  const Range sex = parse_range("sex", vm["sex"].as<std::string>());
  const double girths = vm["girths"].as<double>();
  if (!(girths >= 0 && girths <= 1)) throw UsageError("--girths: expected a fraction in [0, 1]");
  const std::uint64_t seed = vm["seed"].as<std::uint64_t>();
  const std::string out = vm["out"].as<std::string>();

  Registry& registry = Registry::load_default(plugin_path(vm));
  const Scene scene = load_scene(vm["scene"].as<std::string>());
  // size: auto -- each body wears the size its girth needs (garment_size.hpp,
  // every size built once); the dataset's template is the design size's (the
  // sizes share its topology), each sample records its size in garment_size.
  const SceneSimulations simulations(registry, scene);
  const Simulation& sim = simulations.design();
  const auto [bmi_lo, bmi_hi] = sim.body_model().bmi_range();
  if (bmi.lo < bmi_lo - 1e-9 || bmi.hi > bmi_hi + 1e-9) {
    std::ostringstream o;
    o << "--bmi " << bmi.lo << ":" << bmi.hi << " is outside what body model '" << scene.body_model << "' reaches ("
      << bmi_lo << ":" << bmi_hi << ")";
    throw UsageError(o.str());
  }

  // The size flag of a graph trained on several sizes (garment_size_flag).
  const double garment_size = garment_size_flag(sim.scene());

  // This shard's global sample indices: a contiguous block.
  const std::size_t first = shard.first(total), last = shard.last(total);
  const std::vector<Split> split = splits(total, seed);

  DatasetLayout layout;
  layout.samples = last - first;
  layout.body_params = static_cast<int>(sim.body_model().mean_shape().size());
  layout.body_vertices = static_cast<int>(sim.mean_body().rows());
  layout.garment_vertices = sim.garment().mesh.num_vertices();
  for (const auto& e : scene.effects) layout.stats.push_back("energy_" + e.name);
  for (const char* s : {"energy_total", "penetration", "crossings", "residual", "stationarity", "converged", "iterations", "steps", "seconds", "bmi",
                        "height", "sex", "global_index", "garment_size"})
    layout.stats.push_back(s);
  layout.scene = scene.yaml();
  if (simulations.auto_size()) layout.attributes["garment_sizes"] = "auto: each sample's size in its garment_size statistic (docs/garments.md)";
  layout.template_hash = template_hash(sim.garment().mesh, sim.body_model().faces());
  std::ostringstream ranges;
  ranges << "bmi " << bmi.lo << ":" << bmi.hi << ", height " << height.lo << ":" << height.hi << ", sex " << sex.lo
         << ":" << sex.hi << ", girths " << girths << ", seed " << seed << ", count " << total << ", shard " << shard.index << "/" << shard.count;
  layout.attributes["generator"] = "drape generate: " + ranges.str();
  layout.attributes["body_model"] = scene.body_model;
  std::string names;
  for (const auto& n : sim.body_model().shape_names()) names += (names.empty() ? "" : ",") + n;
  layout.attributes["body_param_names"] = names;

  DatasetWriter writer(out, layout);
  const std::vector<std::size_t> todo = writer.missing();
  const std::size_t already = layout.samples - todo.size();
  int threads = vm["threads"].as<int>();
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads), std::max<std::size_t>(todo.size(), 1)));
  std::printf("generating %zu samples (%zu..%zu of %zu) into %s%s, %d at a time; %s\n", layout.samples, first, last - 1,
              total, out.c_str(), writer.resumed() ? (" (resuming: " + std::to_string(already) + " done)").c_str() : "", threads,
              ranges.str().c_str());
  std::fflush(stdout);

  ProgressBar::Options bar_options;
  bar_options.start = already;  // a resumed job: the ETA counts this run's rate only
  ProgressBar bar("generate", layout.samples, std::cerr, bar_options);
  std::mutex write_mutex;
  std::atomic<int> not_settled{0}, penetrating{0}, crossing{0};
  make_samples_in_parallel(writer, bar, todo, threads, [&]() -> SampleWorker {
#ifdef _OPENMP
    omp_set_num_threads(1);  // parallel over samples, not inside one
#endif
    return [&](std::size_t local) {
      const std::size_t global = first + local;
      Rng rng(Rng::derive(seed, "sample-" + std::to_string(global)));
      BodyRequest request;
      request.bmi = rng.uniform(bmi.lo, bmi.hi);
      request.height = height.lo == height.hi ? height.lo : rng.uniform(height.lo, height.hi);
      request.sex = sex.lo == sex.hi ? sex.lo : (rng.uniform() < 0.5 ? sex.lo : sex.hi);
      // Drawn after the rest, and only with a spread, so a seed without
      // girths draws the bodies it always drew.
      if (girths > 0) draw_proportions(girths, sim.body_model(), rng, request);
      const Eigen::VectorXd shape = solve_in_space(sim.body_model(), request);
      const Eigen::MatrixX3d body = sim.body_vertices(shape);
      std::ostringstream who;
      who << "sample " << global << " (BMI " << request.bmi << ", height " << request.height << " m, sex " << request.sex;
      for (const auto& [name, value] : request.proportions) who << ", " << name << " " << value;  // drape body --girth
      who << "; narrow --bmi or --height)";
      SizeChoice choice;
      const Simulation& wearing = simulations.for_body(body, who.str(), &choice);
      const double size_flag = simulations.auto_size() ? garment_size_flag(choice.size) : garment_size;
      const SimulationResult r = [&] {
        try {
          return wearing.run(body);
        } catch (const ConfigError& e) {  // a body the scene refuses: say which sample it is
          throw ConfigError(who.str() + ": " + e.what());
        }
      }();
      DatasetSample s;
      s.body_params = shape.cast<float>();
      s.body_vertices = r.body.cast<float>();
      s.garment_vertices = r.garment.cast<float>();
      s.split = split[global];
      for (const auto& t : r.energies) s.stats["energy_" + t.name] = t.value;
      s.stats["energy_total"] = r.total_energy;
      s.stats["penetration"] = r.penetration;
      const int crossings = r.crossings ? r.crossings->total() : 0;
      s.stats["crossings"] = crossings;
      s.stats["residual"] = r.residual;
      s.stats["stationarity"] = r.stationarity;
      s.stats["converged"] = r.converged ? 1 : 0;
      s.stats["iterations"] = r.iterations;
      s.stats["steps"] = r.steps;
      s.stats["seconds"] = r.seconds;
      s.stats["bmi"] = request.bmi;
      s.stats["height"] = request.height;
      s.stats["sex"] = request.sex;
      s.stats["global_index"] = static_cast<double>(global);
      s.stats["garment_size"] = size_flag;
      if (!r.converged) ++not_settled;
      if (r.penetration > 0) ++penetrating;
      if (crossings > 0) ++crossing;
      {
        const std::lock_guard<std::mutex> lock(write_mutex);
        writer.write(local, s);
      }
      std::ostringstream status;
      status << "last: BMI " << std::fixed << std::setprecision(1) << request.bmi << ", " << r.iterations << " it, "
             << std::setprecision(2) << r.seconds << " s";
      bar.set_status(status.str());
      bar.advance();
    };
  });
  std::printf("wrote %s: %zu samples; %d not settled, %d with a vertex inside the body, %d with crossing surfaces (this run)\n",
              out.c_str(), layout.samples, not_settled.load(), penetrating.load(), crossing.load());
  return 0;
}

const RegisterCommand registered{{"generate", "simulate a dataset of drapes over random bodies (resumable, shardable)", run}};

}  // namespace
}  // namespace drape::cli
