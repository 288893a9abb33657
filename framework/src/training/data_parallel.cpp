// Data-parallel forward/backward over graph replicas, one thread each.
#include <drape/training/data_parallel.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <cmath>
#include <exception>

namespace drape {
namespace {
// Below this many elements a weight is reduced by one thread (not worth a team).
constexpr long kParallelElements = 1L << 15;
}  // namespace

void LossValues::merge(const LossValues& other) {
  if (other.samples == 0) return;
  const double n = samples + other.samples;
  const double a = samples / n, b = other.samples / n;
  total = a * total + b * other.total;
  for (const auto& [name, value] : other.terms) terms[name] = a * (samples ? terms[name] : 0.0) + b * value;
  samples += other.samples;
}

OmpThreadsScope::OmpThreadsScope(int threads) {
#ifdef _OPENMP
  previous_ = omp_get_max_threads();
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
}

OmpThreadsScope::~OmpThreadsScope() {
#ifdef _OPENMP
  omp_set_num_threads(previous_);
#endif
}

DataParallelGraph::DataParallelGraph(const GraphSpec& spec, const Registry& registry, const GraphOptions& options,
                                     int threads) {
  if (threads < 1) throw ConfigError("threads must be at least 1, got " + std::to_string(threads));
  for (int t = 0; t < threads; ++t) replicas_.push_back(std::make_unique<Graph>(spec, registry, options));
}

DataParallelGraph::~DataParallelGraph() = default;

void DataParallelGraph::sync_weights() {
  const auto master = replicas_.front()->weights();
  std::vector<NamedWeights> others;
  for (std::size_t r = 1; r < replicas_.size(); ++r) others.push_back(replicas_[r]->weights());
  const int threads = static_cast<int>(replicas_.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads) if (threads > 1)
  for (long job = 0; job < static_cast<long>(others.size() * master.size()); ++job) {
    const std::size_t r = static_cast<std::size_t>(job) / master.size(), i = static_cast<std::size_t>(job) % master.size();
    others[r][i].second->value.vec() = master[i].second->value.vec();
  }
}

LossValues DataParallelGraph::gradients(const SampleBatch& batch) { return run(batch, true); }
LossValues DataParallelGraph::losses(const SampleBatch& batch) { return run(batch, false); }

LossValues DataParallelGraph::run(const SampleBatch& batch, bool backward) {
  const int n = batch.size();
  if (n <= 0) throw Error("an empty batch");
  // As many workers as samples at most, so that every chunk is non-empty.
  const int workers = std::min(threads(), n);
  std::vector<LossValues> results(static_cast<std::size_t>(workers));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));
  auto work = [&](int t) {
    try {
      const int first = n * t / workers, count = n * (t + 1) / workers - first;
      Graph& g = *replicas_[static_cast<std::size_t>(t)];
      const SampleBatch part = workers == 1 ? batch : batch.slice(first, count);
      g.forward(graph_inputs(g, part, true), true);
      if (backward) {
        g.zero_grad();
        g.backward();
      }
      LossValues& r = results[static_cast<std::size_t>(t)];
      r.samples = count;
      r.total = g.loss();
      r.terms = g.loss_terms();
    } catch (...) {
      errors[static_cast<std::size_t>(t)] = std::current_exception();
    }
  };
  // One OpenMP team for the replicas, Adam and the reductions: std::threads
  // next to OpenMP's spinning idle workers would fight over the cores.
  // Iteration t always runs replica t, so the thread that takes it changes nothing.
#pragma omp parallel for schedule(static, 1) num_threads(workers) if (workers > 1)
  for (int t = 0; t < workers; ++t) {
    const OmpThreadsScope one(1);  // plugins' own parallel loops stay serial inside
    work(t);
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);

  LossValues total;
  for (const auto& r : results) total.merge(r);
  if (backward) {
    // Replica 0's gradient becomes the sample-weighted mean of all replicas',
    // added in replica order for every element (so any split of the elements
    // among threads gives the same bits).
    std::vector<float> share(static_cast<std::size_t>(workers));
    for (int t = 0; t < workers; ++t) share[static_cast<std::size_t>(t)] = float(results[static_cast<std::size_t>(t)].samples) / float(n);
    std::vector<NamedWeights> all;
    for (int t = 0; t < workers; ++t) all.push_back(replicas_[static_cast<std::size_t>(t)]->weights());
    for (std::size_t i = 0; i < all[0].size(); ++i) {
      float* g0 = all[0][i].second->grad.data();
      const long size = static_cast<long>(all[0][i].second->grad.size());
#pragma omp parallel for schedule(static) num_threads(workers) if (workers > 1 && size > kParallelElements)
      for (long k = 0; k < size; ++k) {
        float sum = share[0] * g0[k];
        for (int t = 1; t < workers; ++t) sum += share[static_cast<std::size_t>(t)] * all[static_cast<std::size_t>(t)][i].second->grad.data()[k];
        g0[k] = sum;
      }
    }
  }
  return total;
}

}  // namespace drape
