// Data-parallel training over ranks: each rank runs its part of a global
// batch, the parts' gradients are gathered and combined in rank order.
#include <drape/distributed.hpp>
#include <drape/errors.hpp>

#include <algorithm>

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
  mine_.assign(length, 0.0f);
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
    for (std::size_t k = 0; k < size_w; ++k) {
      float sum = share[0] * all_[at + k];
      for (int q = 1; q < parts; ++q) sum += share[static_cast<std::size_t>(q)] * all_[length * static_cast<std::size_t>(q) + at + k];
      g[k] = sum;
    }
    at += size_w;
  }
  return total;
}

}  // namespace drape
