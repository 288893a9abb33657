// `drape bench train (--model model.h5 | --graph g.yaml) --data data.h5`: the
// training throughput -- samples per second (and per core) of full steps
// (read the batch, forward, backward, gradient reduction, Adam) -- the
// process's peak resident memory (VmHWM of /proc/self/status), and where a
// step's time goes: forward and backward of every node, the network's and the
// losses' totals.
//
// Training meets each sample once per epoch, and what depends only on the
// data (the ground truth's closest body points) is computed at its first
// meeting and cached (geometry::SurfaceCache). The timed steps are those of
// the later epochs: an untimed epoch over the pool (--pool samples of the
// train split) comes first, unless --cold.
#include "bench.hpp"

#include <drape/io/shipped_files.hpp>

#include <drape/assets/dataset_assets.hpp>
#include <drape/training/data_parallel.hpp>
#include <drape/io/dataset.hpp>
#include <drape/geometry/surface_cache.hpp>
#include <drape/training/model.hpp>
#include <drape/training/optimizer.hpp>
#include <drape/registry.hpp>
#include <drape/training/rng.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <thread>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

using Clock = std::chrono::steady_clock;

// Peak resident set size in MiB, or -1 when /proc is not there.
double peak_memory_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // the value is in kB
  return -1;
}

// A batch of the dataset's samples, as training reads it.
// What drape train reads for a graph (read_samples): the body, the target,
// and the inputs the graph takes beyond them (body_params, a sized graph's
// garment_grade or garment_size, a posed graph's pose inputs). It read the
// first two alone, and no sized or posed model could be timed.
struct BatchReader {
  const DatasetReader& reader;
  const Graph& graph;
  SampleBatch operator()(const std::vector<std::size_t>& indices) const { return read_samples(reader, indices, graph, true); }
};

// Every sample of the file, the training split first: a benchmark has no
// use for the splits, and a pool smaller than the batch would repeat samples
// within a batch, whose closest points the losses then find in the batch's
// own cache (a faster step than training ever takes).
std::vector<std::size_t> sample_pool(const DatasetReader& reader, const std::string& data, int keep, int batch_size) {
  std::vector<std::size_t> pool = reader.indices(Split::Train);
  for (const Split other : {Split::Val, Split::Test})
    for (const std::size_t i : reader.indices(other)) pool.push_back(i);
  if (pool.empty()) pool = reader.indices();
  if (pool.empty()) throw ConfigError(data + ": no samples");
  if (keep > 0 && static_cast<std::size_t>(keep) < pool.size()) pool.resize(keep);
  if (pool.size() < static_cast<std::size_t>(batch_size))
    std::fprintf(stderr, "warning: %zu samples for batches of %d: batches repeat samples, and the repeats' closest "
                 "points are not computed again (give --data a file with at least --batch samples)\n",
                 pool.size(), batch_size);
  return pool;
}

// Where the timed steps' time went.
struct StepTimes {
  // Per node (replica 0's share of the batch): forward and backward ms summed over the timed steps.
  std::vector<Graph::NodeTime> node_sums;
  // Seconds in each part of a step: reading, forward+backward+reduction, Adam, copying the weights.
  double read = 0, grad = 0, step = 0, sync = 0;

  void add_node_times(const std::vector<Graph::NodeTime>& times) {
    if (node_sums.empty()) {
      node_sums = times;
      for (auto& n : node_sums) n.ms = n.backward_ms = 0.0;
    }
    for (std::size_t n = 0; n < times.size() && n < node_sums.size(); ++n) {
      node_sums[n].ms += times[n].ms;
      node_sums[n].backward_ms += times[n].backward_ms;
    }
  }
};

// One untimed step, then `steps` timed ones: read the batch, forward,
// backward and reduction, Adam, the weight copies.
StepTimes time_steps(DataParallelGraph& dp, Adam& adam, const BatchReader& read_batch, const std::vector<std::size_t>& pool,
                     int batch_size, int steps, int threads) {
  Rng rng(1);
  StepTimes times;
  auto lap = [](Clock::time_point& t) {
    const auto now = Clock::now();
    const double s = std::chrono::duration<double>(now - t).count();
    t = now;
    return s;
  };
  // Batches as training draws them: shuffled epochs over the pool, no sample
  // twice in a batch. (Drawing with replacement repeated samples within a
  // batch, and the second copy's closest points came from the first's: with a
  // pool of 8 at batch 8, a third of v2v's work was never timed.)
  std::vector<std::size_t> order;
  std::size_t next = 0;
  for (int s = 0; s <= steps; ++s) {
    std::vector<std::size_t> indices;
    for (int k = 0; k < batch_size; ++k) {
      if (next == order.size()) order = rng.permutation(pool.size()), next = 0;
      indices.push_back(pool[order[next++]]);
    }
    const bool timed = s > 0;  // the first step allocates
    auto t = Clock::now();
    const SampleBatch batch = read_batch(indices);
    times.read += timed * lap(t);
    dp.gradients(batch);
    times.grad += timed * lap(t);
    if (timed) times.add_node_times(dp.graph().last_step_times());
    {
      const OmpThreadsScope all(threads);
      adam.step(1e-4);
    }
    times.step += timed * lap(t);
    dp.sync_weights();
    times.sync += timed * lap(t);
  }
  return times;
}

// Where forward+backward goes, node by node: the network's nodes, then the losses.
void print_node_table(const StepTimes& times, int batch_size, int steps, int threads) {
  const int share = threads > 1 ? (batch_size + threads - 1) / threads : batch_size;
  std::printf("\nPer node, ms per step (replica 0: %d of the %d samples%s):\n\n", share, batch_size,
              threads > 1 ? "; the other replicas run theirs at the same time" : "");
  std::printf("| node | type | forward | backward | total | share of forward+backward |\n|---|---|---|---|---|---|\n");
  double network[2] = {0, 0}, losses[2] = {0, 0};
  const double all_ms = 1e3 * times.grad / steps;
  for (const bool loss : {false, true})
    for (const auto& n : times.node_sums) {
      if (n.is_loss != loss) continue;
      const double f = n.ms / steps, b = n.backward_ms / steps;
      (loss ? losses : network)[0] += f;
      (loss ? losses : network)[1] += b;
      std::printf("| %s%s | %s | %.2f | %.2f | %.2f | %.1f %% |\n", loss ? "loss " : "", n.name.c_str(), n.type.c_str(), f,
                  b, f + b, 100.0 * (f + b) / all_ms);
    }
  std::printf("| **network** | | %.2f | %.2f | %.2f | %.1f %% |\n", network[0], network[1], network[0] + network[1],
              100.0 * (network[0] + network[1]) / all_ms);
  std::printf("| **losses** | | %.2f | %.2f | %.2f | %.1f %% |\n", losses[0], losses[1], losses[0] + losses[1],
              100.0 * (losses[0] + losses[1]) / all_ms);
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench train");
  opts.add_options()("model", po::value<std::string>(), "model file (its graph and assets are used, weights too)")(
      "graph", po::value<std::string>(), "or a graph YAML (fresh weights)")(
      "data", po::value<std::string>(), "dataset (drape generate) to draw the training batches from")(
      "batch", po::value<int>()->default_value(8), "samples per step")(
      "threads", po::value<int>()->default_value(1), "threads (0: all cores); samples/s per core divides by it")(
      "steps", po::value<int>()->default_value(10), "timed steps (after one untimed)")(
      "pool", po::value<int>()->default_value(64), "samples of the train split the batches are drawn from (0: all)")(
      "cold", po::bool_switch(), "time the first epoch's steps (nothing cached yet) instead of the later ones'")(
      "k", po::value<int>()->default_value(1000), "with --graph: eigenvectors in the assets")(
      "encoder-body", po::value<std::string>(),
      "with --graph: the body model whose vertices the encoder reads (as drape train --encoder-body; the human rig's graphs)");
  po::variables_map vm;
  const std::string usage =
      "drape bench train (--model model.h5 | --graph g.yaml) --data data.h5 [--batch 8] [--threads 1] [--steps 10] "
      "[--pool 64] [--cold]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  require_model_or_graph(vm);
  if (!vm.count("data")) throw UsageError("--data FILE is required");
  const int batch_size = count_option(vm, "batch"), steps = count_option(vm, "steps");
  int threads = vm["threads"].as<int>();
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::string data = vm["data"].as<std::string>();

  Registry& registry = Registry::load_default(plugin_path(vm));
  const DatasetReader reader(data);
  GraphSpec spec;
  std::shared_ptr<const Assets> assets;
  std::unique_ptr<Model> model;
  if (vm.count("model")) {
    model = std::make_unique<Model>(Model::load(registry, find_input_file(vm["model"].as<std::string>())));
    assets = model->shared_assets();
    check_dataset_template(reader, data, *assets);
    spec = model->graph().spec();
  } else {
    assets = assets_for_dataset(registry, reader, data, vm["k"].as<int>(), default_cache_dir(), nullptr,
                                vm.count("encoder-body") ? vm["encoder-body"].as<std::string>() : std::string());
    spec = parse_graph_file(find_input_file(vm["graph"].as<std::string>()));
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

  const std::vector<std::size_t> pool = sample_pool(reader, data, vm["pool"].as<int>(), batch_size);
  const OmpThreadsScope one(1);
  const BatchReader read_batch{reader, dp.graph()};
  // The first epoch, untimed: training sees every sample before it sees one again.
  if (!vm["cold"].as<bool>())
    for (std::size_t first = 0; first < pool.size(); first += batch_size) {
      const std::vector<std::size_t> indices(pool.begin() + first,
                                             pool.begin() + std::min(pool.size(), first + batch_size));
      dp.losses(read_batch(indices));
    }
  const StepTimes times = time_steps(dp, adam, read_batch, pool, batch_size, steps, threads);
  const double read = times.read, grad = times.grad, step = times.step, sync = times.sync;
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

  print_node_table(times, batch_size, steps, threads);
  const auto& cache = geometry::SurfaceCache::shared();
  if (cache.entries() > 0)
    std::printf("\nground-truth closest points cached: %zu samples, %.1f MiB of the %.0f MiB budget ($DRAPE_SURFACE_CACHE_MIB)\n",
                cache.entries(), cache.bytes() / 1048576.0, cache.budget() / 1048576.0);
  return 0;
}

const RegisterBench registration{{"train", "training samples/s (per core) and peak memory of a graph on a dataset", run}};

}  // namespace
}  // namespace drape::cli
