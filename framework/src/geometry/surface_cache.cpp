#include <drape/geometry/surface_cache.hpp>

#include <cstdlib>
#include <cstring>
#include <string>

namespace drape::geometry {
namespace {

constexpr std::uint64_t kP1 = 0x9E3779B185EBCA87ull, kP2 = 0xC2B2AE3D27D4EB4Full, kP3 = 0x165667B19E3779F9ull,
                        kP4 = 0x85EBCA77C2B2AE63ull;

std::uint64_t rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

std::uint64_t avalanche(std::uint64_t h) {
  h ^= h >> 33;
  h *= kP2;
  h ^= h >> 29;
  h *= kP3;
  return h ^ (h >> 32);
}

// Two independent 64-bit lanes over the bytes (xxHash's round on each), so
// that two different samples share a key with probability ~2^-128.
struct Hasher {
  std::uint64_t a, b;
  explicit Hasher(std::uint64_t seed) : a(seed + kP1), b(seed ^ kP4) {}
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    for (; i + 8 <= size; i += 8) {
      std::uint64_t w;
      std::memcpy(&w, bytes + i, 8);
      a = rotl(a + w * kP2, 31) * kP1;
      b = rotl(b ^ (w * kP3), 27) * kP4 + kP1;
    }
    std::uint64_t tail = size;
    for (; i < size; ++i) tail = (tail << 8) | bytes[i];
    a = rotl(a + tail * kP2, 31) * kP1;
    b = rotl(b ^ (tail * kP3), 27) * kP4 + kP1;
  }
};

std::size_t budget_from_environment() {
  const char* v = std::getenv("DRAPE_SURFACE_CACHE_MIB");
  if (!v || !*v) return std::size_t{2048} << 20;
  char* end = nullptr;
  const double mib = std::strtod(v, &end);
  if (end == v || mib < 0) return std::size_t{2048} << 20;
  return static_cast<std::size_t>(mib * 1048576.0);
}

}  // namespace

std::uint64_t topology_hash(const Eigen::MatrixX3i& faces) {
  Hasher h(static_cast<std::uint64_t>(faces.rows()));
  h.add(faces.data(), sizeof(int) * static_cast<std::size_t>(faces.size()));
  return avalanche(h.a ^ rotl(h.b, 17));
}

SurfaceKey surface_key(std::uint64_t topology, const float* body, std::size_t m, const float* points, std::size_t n) {
  Hasher h(topology);
  h.add(&m, sizeof m);
  h.add(body, sizeof(float) * m);
  h.add(&n, sizeof n);
  h.add(points, sizeof(float) * n);
  return {avalanche(h.a), avalanche(h.b ^ topology)};
}

SurfaceCache& SurfaceCache::shared() {
  static SurfaceCache cache(budget_from_environment());
  return cache;
}

std::shared_ptr<const SurfaceCache::Hits> SurfaceCache::find(const SurfaceKey& key) const {
  std::shared_lock lock(mutex_);
  const auto it = entries_.find(key);
  return it == entries_.end() ? nullptr : it->second;
}

std::shared_ptr<const SurfaceCache::Hits> SurfaceCache::insert(const SurfaceKey& key, Hits hits) {
  auto entry = std::make_shared<const Hits>(std::move(hits));
  const std::size_t size = sizeof(SurfacePoint) * entry->size() + 64;
  std::unique_lock lock(mutex_);
  if (const auto it = entries_.find(key); it != entries_.end()) return it->second;
  if (bytes_ + size > budget_) return entry;
  bytes_ += size;
  entries_.emplace(key, entry);
  return entry;
}

std::size_t SurfaceCache::bytes() const {
  std::shared_lock lock(mutex_);
  return bytes_;
}

std::size_t SurfaceCache::entries() const {
  std::shared_lock lock(mutex_);
  return entries_.size();
}

}  // namespace drape::geometry
