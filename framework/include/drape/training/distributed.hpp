#pragma once
// Data-parallel training over processes (drape/training/ranks.hpp) on top of each
// process's threads (drape/training/data_parallel.hpp). A global batch is cut into
// min(ranks, samples) contiguous parts exactly as DataParallelGraph cuts a
// batch among its threads; each rank reads and runs only its part, the parts'
// mean gradients are gathered on every rank and combined in rank order with
// the same float expression the threads use. So every rank ends a step with
// the same gradient bits, runs the same Adam step and keeps the same weights
// without a broadcast, and N ranks of one thread each give bit for bit what one
// process with N threads gives (and one thread up to float round-off).
#include <drape/training/data_parallel.hpp>
#include <drape/training/ranks.hpp>

#include <cstddef>
#include <functional>
#include <vector>

namespace drape {

class DistributedGraph {
 public:
  // Reads the samples with these dataset indices as a batch.
  using Reader = std::function<SampleBatch(const std::vector<std::size_t>& indices)>;

  // ranks null (or of size 1): this process alone, exactly DataParallelGraph.
  DistributedGraph(DataParallelGraph& local, const Ranks* ranks, Reader read);

  int rank() const;
  int size() const;
  // Forward and backward over the global batch `indices` (the same on every
  // rank): on return the local graph's gradients are the batch's mean
  // gradient, and the losses are the whole batch's, on every rank.
  LossValues gradients(const std::vector<std::size_t>& indices);
  // Forward with losses only (validation), split the same way.
  LossValues losses(const std::vector<std::size_t>& indices);

 private:
  LossValues run(const std::vector<std::size_t>& indices, bool backward);
  DataParallelGraph& local_;
  const Ranks* ranks_;
  Reader read_;
  std::vector<float> mine_, all_;  // gradient buffers, kept between steps
};

// Every rank hands the others the data-only closest points it computed since
// the last call (geometry::SurfaceCache::take_computed) and keeps theirs, so
// that after the first epoch every rank's cache holds every sample its budget
// allows, as one process's does. (Each rank meets a different half of the
// samples every epoch: with caches of their own, two ranks still missed ~6 %
// of them in the fourth epoch and trained 1.6x one rank's speed over the
// first six epochs, against 1.8x with full caches.) Collective: every rank
// calls it at the same point. Sent in rounds of at most 64 MiB a rank.
// Returns the entries adopted from the other ranks.
std::size_t share_surface_cache(const Ranks& ranks);

}  // namespace drape
