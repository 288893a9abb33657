#pragma once
// Seeded randomness that gives the same numbers for the same seed on every
// platform: std::mt19937_64 is fully specified by the standard, but the
// standard distributions and std::shuffle are not, so uniform, normal, index
// and shuffle are implemented here on top of the raw engine.
#include <cstdint>
#include <random>
#include <string_view>
#include <utility>
#include <vector>

namespace drape {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0) : seed_(seed), engine_(seed) {}

  // A stable seed for a named component ("encoder", "shard-3", "split") derived
  // from a run's seed: the same pair always gives the same seed, different
  // names give unrelated streams.
  static std::uint64_t derive(std::uint64_t seed, std::string_view name);
  // derive(seed, name) of this generator's seed: independent of how much was drawn.
  Rng child(std::string_view name) const { return Rng(derive(seed_, name)); }
  std::uint64_t seed() const { return seed_; }

  std::uint64_t next() { return engine_(); }
  double uniform();                     // [0, 1) with 53 random bits
  double uniform(double lo, double hi);  // [lo, hi)
  double normal(double mean = 0.0, double stddev = 1.0);
  std::size_t index(std::size_t n);      // uniform in [0, n), unbiased; n > 0

  // Fisher-Yates with index(): the same permutation everywhere for a seed.
  template <class T> void shuffle(std::vector<T>& v) {
    for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[index(i)]);
  }
  std::vector<std::size_t> permutation(std::size_t n);  // a shuffled 0..n-1

  std::mt19937_64& engine() { return engine_; }

 private:
  std::uint64_t seed_;
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;  // Box-Muller makes normals in pairs
};

}  // namespace drape
