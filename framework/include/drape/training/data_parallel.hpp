#pragma once
// Data-parallel training on one machine: T replicas of a graph, each run by
// its own (OpenMP) thread on a contiguous part of every batch. Replica 0 holds the
// weights the optimiser updates; after a step sync_weights() copies them to
// the others. The batch gradient is the sample-weighted sum of the replicas'
// mean gradients, added in replica order, so a run is deterministic for a
// given thread count (and equal to one full-batch pass up to float rounding).
// Each worker runs with one OpenMP thread: the parallelism is over samples.
#include <drape/graph.hpp>
#include <drape/training/model.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace drape {

// Losses of a set of samples: the weighted total and each term (unweighted),
// both means over the samples.
struct LossValues {
  int samples = 0;
  double total = 0.0;
  std::map<std::string, double> terms;
  // Pools two sets of samples (means weighted by their counts).
  void merge(const LossValues& other);
};

class DataParallelGraph {
 public:
  // Builds `threads` identical replicas (same seed, so the same initial weights).
  DataParallelGraph(const GraphSpec& spec, const Registry& registry, const GraphOptions& options, int threads);
  ~DataParallelGraph();

  int threads() const { return static_cast<int>(replicas_.size()); }
  Graph& graph() { return *replicas_.front(); }  // the weights an optimiser updates

  // Forward and backward over the batch: replica 0's gradients then hold the
  // mean gradient over all the batch's samples. Returns the batch's losses.
  LossValues gradients(const SampleBatch& batch);
  // Forward with losses only (validation).
  LossValues losses(const SampleBatch& batch);
  // Copies replica 0's weights into the other replicas.
  void sync_weights();

 private:
  LossValues run(const SampleBatch& batch, bool backward);
  std::vector<std::unique_ptr<Graph>> replicas_;
};

// Sets this thread's OpenMP thread count for the scope and restores it after.
class OmpThreadsScope {
 public:
  explicit OmpThreadsScope(int threads);
  ~OmpThreadsScope();
  OmpThreadsScope(const OmpThreadsScope&) = delete;
  OmpThreadsScope& operator=(const OmpThreadsScope&) = delete;

 private:
  int previous_ = 1;
};

}  // namespace drape
