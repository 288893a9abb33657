#include <drape/errors.hpp>
#include <drape/nn/mesh_graph.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace drape::nn {

namespace {

// A row-major matrix over the 1-ring + self pattern with value(i, j) per entry.
template <typename Value>
SparseRM ring_matrix(const Neighbours& neighbours, Value value) {
  const int n = static_cast<int>(neighbours.size());
  std::vector<Eigen::Triplet<float>> entries;
  std::size_t total = static_cast<std::size_t>(n);
  for (const auto& ring : neighbours) total += ring.size();
  entries.reserve(total);
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, value(i, i));
    int previous = -1;
    for (int j : neighbours[static_cast<std::size_t>(i)]) {
      if (j < 0 || j >= n || j == i || j <= previous)
        throw Error("vertex " + std::to_string(i) + " has a bad neighbour " + std::to_string(j) + " (of " +
                    std::to_string(n) + " vertices; lists must be sorted, unique, without the vertex itself)");
      entries.emplace_back(i, j, value(i, j));
      previous = j;
    }
  }
  SparseRM a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

}  // namespace

SparseRM ring_mean(const Neighbours& neighbours) {
  return ring_matrix(neighbours, [&](int i, int) { return 1.0f / float(neighbours[std::size_t(i)].size() + 1); });
}

SparseRM kipf_adjacency(const Neighbours& neighbours) {
  std::vector<float> inv_sqrt_degree(neighbours.size());
  for (std::size_t i = 0; i < neighbours.size(); ++i)
    inv_sqrt_degree[i] = 1.0f / std::sqrt(float(neighbours[i].size() + 1));
  return ring_matrix(neighbours, [&](int i, int j) { return inv_sqrt_degree[std::size_t(i)] * inv_sqrt_degree[std::size_t(j)]; });
}

BlockPooling pool_consecutive(const Neighbours& neighbours, int stride) {
  if (stride < 1) throw ConfigError("the pooling stride must be at least 1, got " + std::to_string(stride));
  const int n = static_cast<int>(neighbours.size());
  const int blocks = (n + stride - 1) / stride;
  BlockPooling out;
  std::vector<Eigen::Triplet<float>> entries;
  entries.reserve(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    const int p = v / stride;
    const int size = std::min(n, (p + 1) * stride) - p * stride;
    entries.emplace_back(p, v, 1.0f / float(size));
  }
  out.pool.resize(blocks, n);
  out.pool.setFromTriplets(entries.begin(), entries.end());
  out.pool.makeCompressed();
  out.neighbours.assign(static_cast<std::size_t>(blocks), {});
  for (int v = 0; v < n; ++v)
    for (int u : neighbours[static_cast<std::size_t>(v)])
      if (u / stride != v / stride) out.neighbours[static_cast<std::size_t>(v / stride)].push_back(u / stride);
  for (auto& ring : out.neighbours) {
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  }
  return out;
}

SparseRM restriction_of(const SparseRM& upsample) {
  SparseRM r(upsample.transpose());  // [coarse, fine]
  for (Eigen::Index j = 0; j < r.outerSize(); ++j) {
    float sum = 0.0f;
    for (SparseRM::InnerIterator it(r, j); it; ++it) sum += it.value();
    if (!(sum > 0.0f))
      throw Error("coarse vertex " + std::to_string(j) + " is used by no fine vertex of the up-sampling");
    for (SparseRM::InnerIterator it(r, j); it; ++it) it.valueRef() /= sum;
  }
  r.makeCompressed();
  return r;
}

}  // namespace drape::nn
