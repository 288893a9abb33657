// Data-parallel training over ranks: each rank runs its part of a global
// batch, the parts' gradients are gathered and combined in rank order.
#include <drape/training/distributed.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/surface_cache.hpp>

#include <algorithm>
#include <cstdint>

namespace drape {

DistributedGraph::DistributedGraph(DataParallelGraph& local, const Ranks* ranks, Reader read)
    : local_(local), ranks_(ranks && ranks->size() > 1 ? ranks : nullptr), read_(std::move(read)) {}

int DistributedGraph::rank() const { return ranks_ ? ranks_->rank() : 0; }
int DistributedGraph::size() const { return ranks_ ? ranks_->size() : 1; }

LossValues DistributedGraph::gradients(const std::vector<std::size_t>& indices) { return run(indices, true); }
LossValues DistributedGraph::losses(const std::vector<std::size_t>& indices) { return run(indices, false); }

LossValues DistributedGraph::run(const std::vector<std::size_t>& indices, bool backward) {
  if (!ranks_) return backward ? local_.gradients(read_(indices)) : local_.losses(read_(indices));
  const int n = static_cast<int>(indices.size());
  if (n <= 0) throw Error("an empty batch");
  // The cut DataParallelGraph makes among threads: as many parts as samples
  // at most, part r = [n r / parts, n (r + 1) / parts); ranks past the last
  // part sit this batch out.
  const int parts = std::min(size(), n), r = rank();
  LossValues mine;
  if (r < parts) {
    const int first = n * r / parts, count = n * (r + 1) / parts - first;
    const std::vector<std::size_t> part(indices.begin() + first, indices.begin() + first + count);
    mine = backward ? local_.gradients(read_(part)) : local_.losses(read_(part));
  }

  // The losses: [samples, total, each term] per rank, pooled in rank order.
  // The term names come from the graph, so a rank without samples sends zeros
  // of the same length.
  std::vector<std::string> names;
  for (const auto& node : local_.graph().spec().nodes)
    if (node.is_loss) names.push_back(node.name);
  std::sort(names.begin(), names.end());
  const std::size_t per_rank = 2 + names.size();
  std::vector<double> my_losses(per_rank, 0.0), all_losses(per_rank * static_cast<std::size_t>(size()));
  my_losses[0] = mine.samples;
  my_losses[1] = mine.total;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto it = mine.terms.find(names[k]);
    if (it != mine.terms.end()) my_losses[2 + k] = it->second;
  }
  ranks_->all_gather(my_losses.data(), per_rank, all_losses.data());
  LossValues total;
  std::vector<int> counts(static_cast<std::size_t>(size()));
  for (int q = 0; q < size(); ++q) {
    const double* v = all_losses.data() + per_rank * static_cast<std::size_t>(q);
    LossValues theirs;
    theirs.samples = static_cast<int>(v[0]);
    theirs.total = v[1];
    for (std::size_t k = 0; k < names.size(); ++k) theirs.terms[names[k]] = v[2 + k];
    counts[static_cast<std::size_t>(q)] = theirs.samples;
    total.merge(theirs);
  }
  if (!backward) return total;

  // The gradients: every weight's, flattened in the graph's weight order.
  const NamedWeights weights = local_.graph().weights();
  std::size_t length = 0;
  for (const auto& [name, w] : weights) length += w->grad.size();
  mine_.resize(length);
  if (r >= parts) std::fill(mine_.begin(), mine_.end(), 0.0f);
  if (r < parts) {
    std::size_t at = 0;
    for (const auto& [name, w] : weights) {
      std::copy(w->grad.data(), w->grad.data() + w->grad.size(), mine_.begin() + static_cast<long>(at));
      at += w->grad.size();
    }
  }
  all_.resize(length * static_cast<std::size_t>(size()));
  ranks_->all_gather(mine_.data(), length, all_.data());
  // share[q] * g_q summed over the parts in rank order: the expression
  // DataParallelGraph::run evaluates for its threads, so the same bits.
  std::vector<float> share(static_cast<std::size_t>(parts));
  for (int q = 0; q < parts; ++q) share[static_cast<std::size_t>(q)] = float(counts[static_cast<std::size_t>(q)]) / float(n);
  std::size_t at = 0;
  for (const auto& [name, w] : weights) {
    float* g = w->grad.data();
    const std::size_t size_w = w->grad.size();
    // Parts outermost, so that each pass is a plain vector loop; the sum of
    // every element still runs over the parts in rank order.
    const float* first_part = all_.data() + at;
    for (std::size_t k = 0; k < size_w; ++k) g[k] = share[0] * first_part[k];
    for (int q = 1; q < parts; ++q) {
      const float s = share[static_cast<std::size_t>(q)];
      const float* part = all_.data() + length * static_cast<std::size_t>(q) + at;
      for (std::size_t k = 0; k < size_w; ++k) g[k] += s * part[k];
    }
    at += size_w;
  }
  return total;
}

std::size_t share_surface_cache(const Ranks& ranks) {
  if (ranks.size() <= 1) return 0;
  geometry::SurfaceCache& cache = geometry::SurfaceCache::shared();
  // This rank's new entries, cut into rounds of at most kRound bytes (each
  // packed only when its turn comes: the first epoch's entries can be GBs).
  constexpr std::size_t kRound = std::size_t{64} << 20;
  const auto computed = cache.take_computed();
  std::vector<std::size_t> cuts{0};
  for (std::size_t e = 0, bytes = 0; e < computed.size(); ++e) {
    const std::size_t entry = geometry::packed_entry_bytes(*computed[e].second);
    if (e > cuts.back() && bytes + entry > kRound) cuts.push_back(e), bytes = 0;
    bytes += entry;
  }
  if (!computed.empty()) cuts.push_back(computed.size());
  const std::size_t my_rounds = cuts.size() - 1;
  const int size = ranks.size(), me = ranks.rank();
  auto gather_one = [&](double mine) {
    std::vector<double> all(static_cast<std::size_t>(size));
    ranks.all_gather(&mine, 1, all.data());
    return all;
  };
  const std::vector<double> round_counts = gather_one(double(my_rounds));
  const auto total_rounds = static_cast<std::size_t>(*std::max_element(round_counts.begin(), round_counts.end()));
  std::size_t adopted = 0;
  for (std::size_t round = 0; round < total_rounds; ++round) {
    std::vector<std::uint8_t> mine;
    if (round < my_rounds)
      mine = geometry::pack_surface_entries({computed.begin() + static_cast<long>(cuts[round]),
                                             computed.begin() + static_cast<long>(cuts[round + 1])});
    const std::vector<double> sizes = gather_one(double(mine.size()));
    const auto widest = static_cast<std::size_t>(*std::max_element(sizes.begin(), sizes.end()));
    if (widest == 0) continue;
    mine.resize(widest);  // every rank sends as many bytes; the sizes say how many count
    std::vector<std::uint8_t> all(widest * static_cast<std::size_t>(size));
    ranks.all_gather(mine.data(), widest, all.data());
    for (int q = 0; q < size; ++q) {
      if (q == me) continue;
      const std::uint8_t* theirs = all.data() + widest * static_cast<std::size_t>(q);
      for (auto& [key, entry] : geometry::unpack_surface_entries(theirs, static_cast<std::size_t>(sizes[static_cast<std::size_t>(q)]))) {
        cache.adopt(key, std::move(entry));
        ++adopted;
      }
    }
  }
  return adopted;
}

}  // namespace drape
