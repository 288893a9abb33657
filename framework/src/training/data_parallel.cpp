// Data-parallel forward/backward over graph replicas, one thread each.
#include <drape/data_parallel.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <cmath>
#include <exception>
#include <thread>

namespace drape {

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
  for (std::size_t r = 1; r < replicas_.size(); ++r) {
    const auto w = replicas_[r]->weights();
    for (std::size_t i = 0; i < w.size(); ++i) w[i].second->value.vec() = master[i].second->value.vec();
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
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t)
    pool.emplace_back([&, t] {
      const OmpThreadsScope one(1);
      work(t);
    });
  {
    const OmpThreadsScope one(1);
    work(0);
  }
  for (auto& th : pool) th.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);

  LossValues total;
  for (const auto& r : results) total.merge(r);
  if (backward) {
    // Replica 0's gradient becomes the sample-weighted mean of all replicas', in replica order.
    const auto master = replicas_.front()->weights();
    const float w0 = float(results[0].samples) / float(n);
    for (const auto& [name, w] : master) w->grad.vec() *= w0;
    for (int t = 1; t < workers; ++t) {
      const auto w = replicas_[static_cast<std::size_t>(t)]->weights();
      const float wt = float(results[static_cast<std::size_t>(t)].samples) / float(n);
      for (std::size_t i = 0; i < w.size(); ++i) master[i].second->grad.vec() += wt * w[i].second->grad.vec();
    }
  }
  return total;
}

}  // namespace drape
