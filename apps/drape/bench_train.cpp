// `drape bench train (--model model.h5 | --graph g.yaml) --data data.h5`: the
// training throughput -- samples per second (and per core) of full steps
// (read the batch, forward, backward, gradient reduction, Adam) -- and the
// process's peak resident memory (VmHWM of /proc/self/status).
#include "bench.hpp"

#include <drape/data_parallel.hpp>
#include <drape/dataset.hpp>
#include <drape/model.hpp>
#include <drape/optimizer.hpp>
#include <drape/registry.hpp>
#include <drape/rng.hpp>
#include <drape/trainer.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

namespace drape::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Peak resident set size in MiB, or -1 when /proc is not there.
double peak_memory_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // the value is in kB
  return -1;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench train");
  opts.add_options()("model", po::value<std::string>(), "model file (its graph and assets are used, weights too)")(
      "graph", po::value<std::string>(), "or a graph YAML (fresh weights)")(
      "data", po::value<std::string>(), "dataset (drape generate) to draw the training batches from")(
      "batch", po::value<int>()->default_value(8), "samples per step")(
      "threads", po::value<int>()->default_value(1), "threads (0: all cores); samples/s per core divides by it")(
      "steps", po::value<int>()->default_value(10), "timed steps (after one untimed)")(
      "k", po::value<int>()->default_value(1000), "with --graph: eigenvectors in the assets");
  po::variables_map vm;
  const std::string usage =
      "drape bench train (--model model.h5 | --graph g.yaml) --data data.h5 [--batch 8] [--threads 1] [--steps 10]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  require_model_or_graph(vm);
  if (!vm.count("data")) throw UsageError("--data FILE is required");
  const int batch_size = std::max(1, vm["batch"].as<int>()), steps = std::max(1, vm["steps"].as<int>());
  int threads = vm["threads"].as<int>();
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::string data = vm["data"].as<std::string>();

  Registry& registry = Registry::load_default(plugin_path(vm));
  const DatasetReader reader(data);
  GraphSpec spec;
  std::shared_ptr<const Assets> assets;
  std::unique_ptr<Model> model;
  if (vm.count("model")) {
    model = std::make_unique<Model>(Model::load(registry, vm["model"].as<std::string>()));
    assets = model->shared_assets();
    check_dataset_template(reader, data, *assets);
    spec = model->graph().spec();
  } else {
    assets = assets_for_dataset(registry, reader, data, vm["k"].as<int>(), default_cache_dir());
    spec = parse_graph_file(vm["graph"].as<std::string>());
    check_graph_inputs(spec);
  }
  GraphOptions options;
  options.dims = graph_dims(*assets, reader.layout().body_params);
  options.assets = assets.get();
  DataParallelGraph dp(spec, registry, options, threads);
  if (model) {
    const auto from = model->graph().weights(), to = dp.graph().weights();
    for (std::size_t i = 0; i < to.size(); ++i) to[i].second->value.vec() = from[i].second->value.vec();
    dp.sync_weights();
  }
  Adam adam(dp.graph().weights());
  const auto inputs = dp.graph().input_names();
  const bool params = std::find(inputs.begin(), inputs.end(), "body_params") != inputs.end();

  std::vector<std::size_t> pool = reader.indices(Split::Train);
  if (pool.empty()) pool = reader.indices();
  if (pool.empty()) throw ConfigError(data + ": no samples");
  Rng rng(1);
  const OmpThreadsScope one(1);
  // Seconds in each part of a step: reading, forward+backward+reduction, Adam, copying the weights.
  double read = 0, grad = 0, step = 0, sync = 0;
  auto lap = [](Clock::time_point& t) {
    const auto now = Clock::now();
    const double s = std::chrono::duration<double>(now - t).count();
    t = now;
    return s;
  };
  for (int s = 0; s <= steps; ++s) {
    std::vector<std::size_t> indices;
    for (int k = 0; k < batch_size; ++k) indices.push_back(pool[rng.index(pool.size())]);
    const bool timed = s > 0;  // the first step allocates
    auto t = Clock::now();
    SampleBatch batch;
    batch.body = reader.body_vertices(indices);
    batch.target = reader.garment_vertices(indices);
    if (params) batch.body_params = reader.body_params(indices);
    read += timed * lap(t);
    dp.gradients(batch);
    grad += timed * lap(t);
    {
      const OmpThreadsScope all(threads);
      adam.step(1e-4);
    }
    step += timed * lap(t);
    dp.sync_weights();
    sync += timed * lap(t);
  }
  const double seconds = read + grad + step + sync;
  const double rate = double(steps) * batch_size / seconds;
  std::printf("## Training throughput: %s on %s\n\n", model ? vm["model"].as<std::string>().c_str()
                                                              : vm["graph"].as<std::string>().c_str(), data.c_str());
  std::printf("garment %d vertices, body %d vertices, batch %d, %d thread%s, %d steps\n\n",
              assets->garment->mesh.num_vertices(), assets->body.num_vertices(), batch_size, threads, threads > 1 ? "s" : "",
              steps);
  std::printf("| samples/s | samples/s per core | ms per step | read | forward+backward | Adam | weight copies | peak memory (MiB, VmHWM) |\n"
              "|---|---|---|---|---|---|---|---|\n");
  std::printf("| %.2f | %.2f | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f |\n", rate, rate / threads, 1e3 * seconds / steps,
              1e3 * read / steps, 1e3 * grad / steps, 1e3 * step / steps, 1e3 * sync / steps, peak_memory_mib());
  return 0;
}

const RegisterBench registration{{"train", "training samples/s (per core) and peak memory of a graph on a dataset", run}};

}  // namespace
}  // namespace drape::cli
