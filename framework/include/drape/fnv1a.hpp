#pragma once
// FNV-1a (64 bit) over bytes: the same value on every run and machine
// (std::hash is not promised to be), for cache keys, file names, a
// dataset's template hash and the seeds derived from names.
//
// The offset basis is the project's since its first hash, 1469598103934665603:
// the published one, 14695981039346656037, lost its last digit. Kept: every
// stored template hash and assets hash, and every seed derived from a name,
// was made with it. Same prime, same steps; another start.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace drape {

class Fnv1a {
 public:
  static constexpr std::uint64_t kOffsetBasis = 1469598103934665603ull;

  explicit Fnv1a(std::uint64_t start = kOffsetBasis) : h_(start) {}

  Fnv1a& bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
    return *this;
  }
  Fnv1a& text(std::string_view s) { return bytes(s.data(), s.size()); }
  // An Eigen matrix's coefficients in storage order.
  template <class M>
  Fnv1a& matrix(const M& m) {
    return bytes(m.data(), static_cast<std::size_t>(m.size()) * sizeof(typename M::Scalar));
  }

  std::uint64_t value() const { return h_; }
  // 16 lower-case hexadecimal digits.
  std::string hex() const {
    char out[17];
    std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h_));
    return out;
  }

 private:
  std::uint64_t h_;
};

}  // namespace drape
