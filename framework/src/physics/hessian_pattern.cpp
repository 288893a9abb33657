#include "hessian_pattern.hpp"

#include <algorithm>
#include <map>

namespace drape::physics {

HessianPattern::HessianPattern(const Mesh& mesh) : vertices_(mesh.num_vertices()) {
  std::vector<std::pair<int, int>> pairs;
  auto add = [&](int a, int b) { pairs.emplace_back(std::max(a, b), std::min(a, b)); };
  // Faces: every pair of corners. Edges: the two vertices opposite an interior edge (bending).
  std::map<std::pair<int, int>, int> opposite;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3), c = mesh.faces(f, (k + 2) % 3);
      add(a, b);
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto [it, inserted] = opposite.emplace(key, c);
      if (!inserted) add(it->second, c);
    }
  for (int v = 0; v < vertices_; ++v) add(v, v);
  build(std::move(pairs));
}

void HessianPattern::build(std::vector<std::pair<int, int>> vertex_pairs) {
  std::sort(vertex_pairs.begin(), vertex_pairs.end());
  vertex_pairs.erase(std::unique(vertex_pairs.begin(), vertex_pairs.end()), vertex_pairs.end());
  pairs_ = std::move(vertex_pairs);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(pairs_.size() * 9);
  for (const auto& [a, b] : pairs_)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int r = 3 * a + i, c = 3 * b + j;
        if (r >= c) t.emplace_back(r, c, 0.0);
      }
  pattern_.resize(3 * vertices_, 3 * vertices_);
  pattern_.setFromTriplets(t.begin(), t.end());
  pattern_.makeCompressed();
}

namespace {
std::uint64_t key_of(int r, int c) { return (std::uint64_t(std::uint32_t(r)) << 32) | std::uint32_t(c); }
}  // namespace

bool HessianPattern::assemble_cached(const Triplets& triplets, const Eigen::VectorXd& diagonal,
                                     Eigen::SparseMatrix<double>& out) const {
  if (cached_keys_.size() != triplets.size() || out.nonZeros() != pattern_.nonZeros() || out.rows() != pattern_.rows() ||
      static_cast<Eigen::Index>(diagonal_slots_.size()) != diagonal.size())
    return false;
  for (std::size_t i = 0; i < triplets.size(); ++i)
    if (cached_keys_[i] != key_of(triplets[i].row(), triplets[i].col())) return false;
  double* values = out.valuePtr();
  std::fill(values, values + out.nonZeros(), 0.0);
  for (std::size_t i = 0; i < triplets.size(); ++i)
    if (cached_slots_[i] >= 0) values[cached_slots_[i]] += triplets[i].value();
  for (Eigen::Index k = 0; k < diagonal.size(); ++k) values[diagonal_slots_[static_cast<std::size_t>(k)]] += diagonal[k];
  return true;
}

void HessianPattern::assemble(const Triplets& triplets, const Eigen::VectorXd& diagonal, Eigen::SparseMatrix<double>& out) {
  if (assemble_cached(triplets, diagonal, out)) return;
  for (;;) {
    out = pattern_;  // same structure, zero values
    double* values = out.valuePtr();
    const int* outer = out.outerIndexPtr();
    const int* inner = out.innerIndexPtr();
    auto slot = [&](int r, int c) -> double* {
      const int* begin = inner + outer[c];
      const int* end = inner + outer[c + 1];
      const int* it = std::lower_bound(begin, end, r);
      return (it != end && *it == r) ? values + (it - inner) : nullptr;
    };
    std::vector<std::pair<int, int>> missing;
    cached_keys_.resize(triplets.size());
    cached_slots_.resize(triplets.size());
    for (std::size_t i = 0; i < triplets.size(); ++i) {
      const int r = triplets[i].row(), c = triplets[i].col();
      cached_keys_[i] = key_of(r, c);
      cached_slots_[i] = -1;
      if (r < c) continue;  // symmetric: the lower triangle carries it
      if (double* p = slot(r, c)) {
        *p += triplets[i].value();
        cached_slots_[i] = static_cast<int>(p - values);
      } else {
        missing.emplace_back(r / 3, c / 3);
      }
    }
    diagonal_slots_.resize(static_cast<std::size_t>(diagonal.size()));
    for (int k = 0; k < diagonal.size(); ++k) {
      double* p = slot(k, k);
      *p += diagonal[k];
      diagonal_slots_[static_cast<std::size_t>(k)] = static_cast<int>(p - values);
    }
    if (missing.empty()) return;
    cached_keys_.clear();  // the pattern grows: slots move
    missing.insert(missing.end(), pairs_.begin(), pairs_.end());
    build(std::move(missing));
  }
}

}  // namespace drape::physics
